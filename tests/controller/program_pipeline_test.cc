// The controller from program to per-axis command: look-ahead planning, interpolation,
// post-interpolation acc/dec (per axis and tangential).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"
#include "controller/block_planner.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"

namespace shapebench::controller {
namespace {


ProgramBlock Line(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double feed_mm_min,
                  MotionKind kind = MotionKind::kLinear) {
  ProgramBlock b;
  b.kind = kind;
  b.start_m = from;
  b.end_m = to;
  b.feed_m_s = feed_mm_min / 60000.0;
  return b;
}

// A full circle in XY starting at (r, 0) around the origin, CCW.
ProgramBlock Circle(double r, double feed_mm_min) {
  ProgramBlock b;
  b.kind = MotionKind::kArcCcw;
  b.start_m = {r, 0, 0};
  b.end_m = b.start_m;
  b.center_m = Eigen::Vector3d::Zero();
  b.feed_m_s = feed_mm_min / 60000.0;
  return b;
}

Program Make(std::vector<ProgramBlock> blocks) {
  Program p;
  p.start_m = blocks.front().start_m;
  p.blocks = std::move(blocks);
  return p;
}

ControllerConfig PipelineConfig() {
  ControllerConfig c;
  c.feed_mm_min = 6000;
  c.accel_time_s = 0.06;  // 1.667 m/s^2
  return c;
}

double SpeedAtPosition(const MultiAxisCommand& command, double s_m) {
  for (std::size_t k = 1; k < command.path_position_m.size(); ++k) {
    if (command.path_position_m[k] >= s_m) return command.velocity_m_s(k).norm();
  }
  return 0.0;
}

// Tests that two collinear blocks at one feed run as one move: no slowdown at the
// junction and the same motion time as the single 100 mm block.
TEST(BlockPlannerTest, CollinearBlocksDoNotStop) {
  const Eigen::Vector3d o(0, 0, 0), m(0.03, 0.04, 0), e(0.06, 0.08, 0);
  const MultiAxisCommand two = GenerateProgramCommand(PipelineConfig(), Make({Line(o, m, 6000), Line(m, e, 6000)}));
  const MultiAxisCommand one = GenerateProgramCommand(PipelineConfig(), Make({Line(o, e, 6000)}));
  EXPECT_NEAR(SpeedAtPosition(two, 0.05), 0.1, 1e-12);
  EXPECT_EQ(two.num_ticks(), one.num_ticks());
  EXPECT_NEAR((two.Positions().back() - e).norm(), 0.0, 1e-12);
}

// Tests the corner rule: a 90-degree corner stops with no allowance, and with one
// passes at allowance / max|t2 - t1| (= the allowance itself at 90 degrees).
TEST(BlockPlannerTest, CornerRuleSetsTheJunctionSpeed) {
  const Eigen::Vector3d o(0, 0, 0), c(0, 0.05, 0), e(0.05, 0.05, 0);
  const Program corner = Make({Line(o, c, 6000), Line(c, e, 6000)});
  ControllerConfig config = PipelineConfig();
  const MultiAxisCommand stop = GenerateProgramCommand(config, corner);
  double at_corner = 1e9;
  for (std::size_t k = 0; k < stop.path_position_m.size(); ++k) {
    if (std::abs(stop.path_position_m[k] - 0.05) < 1e-12) at_corner = std::min(at_corner, stop.velocity_m_s(k).norm());
  }
  EXPECT_EQ(at_corner, 0.0);
  config.corner_velocity_change_mm_min = 600;  // 10 mm/s per axis
  const MultiAxisCommand pass = GenerateProgramCommand(config, corner);
  // Around the corner the speed is the allowance (the tick nearest the corner).
  double nearest = 1e9;
  double speed = 0;
  for (std::size_t k = 1; k < pass.path_position_m.size(); ++k) {
    const double d = std::abs(pass.path_position_m[k] - 0.05);
    if (d < nearest) {
      nearest = d;
      speed = pass.velocity_m_s(k).norm();
    }
  }
  EXPECT_NEAR(speed, 0.01, 2e-3 * 1.6667);  // within one period's acceleration
  EXPECT_LT(pass.num_ticks(), stop.num_ticks());
  EXPECT_EQ(CornerSpeedLimit({0, 1, 0}, {1, 0, 0}, 0.01), 0.01);
  EXPECT_TRUE(std::isinf(CornerSpeedLimit({0, 1, 0}, {0, 1, 0}, 0.01)));
}

// Tests that a line tangent to an arc needs no slowdown, that a lower F on the next
// block slows to it before the junction, and that G0 runs at the rapid feed.
TEST(BlockPlannerTest, TangentArcFeedChangeAndRapid) {
  const double r = 0.01;
  ProgramBlock arc;
  arc.kind = MotionKind::kArcCcw;
  arc.start_m = {0.05, 0, 0};
  arc.center_m = {0.05, r, 0};
  arc.end_m = {0.05 + r, r, 0};  // a quarter arc, tangent +x at the start, +y at the end
  arc.feed_m_s = 0.05;
  ProgramBlock slow = Line({0.05 + r, r, 0}, {0.05 + r, 0.05, 0}, 1500);
  const Program program = Make({Line({0, 0, 0}, {0.05, 0, 0}, 3000), arc, slow});
  const MultiAxisCommand command = GenerateProgramCommand(PipelineConfig(), program);
  // Line -> arc: no stop. On the arc the axes run along chords: |chord| / period is
  // below the path speed by theta^2 / 24 = 1.04e-6 relative (theta = v dt / r = 0.005).
  EXPECT_NEAR(SpeedAtPosition(command, 0.055), 0.05 * (1 - 0.005 * 0.005 / 24), 1e-12);
  const double arc_end = 0.05 + kPi / 2 * r;
  EXPECT_NEAR(SpeedAtPosition(command, arc_end + 1e-4), 0.025, 1e-9);
  EXPECT_NEAR((command.Positions().back() - slow.end_m).norm(), 0.0, 1e-12);

  ControllerConfig config = PipelineConfig();
  config.rapid_feed_mm_min = 12000;
  config.accel_time_s = 0.06;
  const MultiAxisCommand rapid = GenerateProgramCommand(
      config, Make({Line({0, 0, 0}, {0.2, 0, 0}, 6000, MotionKind::kRapid)}));
  double top = 0;
  for (std::size_t k = 0; k <= rapid.num_ticks(); ++k) top = std::max(top, rapid.velocity_m_s(k).norm());
  EXPECT_NEAR(top, 0.2, 1e-12);
}

// Tests that a dwell holds the axes still for its duration between two motions.
TEST(BlockPlannerTest, DwellHolds) {
  ProgramBlock dwell;
  dwell.kind = MotionKind::kDwell;
  dwell.start_m = dwell.end_m = {0.01, 0, 0};
  dwell.dwell_s = 0.25;
  const Program with = Make({Line({0, 0, 0}, {0.01, 0, 0}, 6000), dwell, Line({0.01, 0, 0}, {0.02, 0, 0}, 6000)});
  const Program without = Make({Line({0, 0, 0}, {0.01, 0, 0}, 6000), Line({0.01, 0, 0}, {0.01, 0.01, 0}, 6000)});
  const MultiAxisCommand a = GenerateProgramCommand(PipelineConfig(), with);
  const MultiAxisCommand b = GenerateProgramCommand(PipelineConfig(), without);
  EXPECT_EQ(a.num_ticks(), b.num_ticks() + 250);
  std::size_t longest_rest = 0, run = 0;
  for (std::size_t k = 0; k <= a.num_ticks(); ++k) {
    run = a.velocity_m_s(k).norm() == 0.0 ? run + 1 : 0;
    longest_rest = std::max(longest_rest, run);
  }
  EXPECT_EQ(longest_rest, 251u);  // 250 periods at rest: 251 zero samples
}

// Tests that every realization of post-interpolation acc/dec moves the axes by exactly
// the programmed displacement (1e-12 m), for programs with lines, arcs and corners.
TEST(ProgramPipelineTest, NoMotionIsLost) {
  ControllerConfig config = PipelineConfig();
  config.corner_velocity_change_mm_min = 300;
  const Program program = Make({Line({0, 0, 0}, {0.02, 0.0, 0}, 6000), Circle(0.02, 3000),
                                Line({0.02, 0, 0}, {0.03, -0.01, 0.005}, 6000),
                                Line({0.03, -0.01, 0.005}, {0.0, 0.0, 0.0}, 6000, MotionKind::kRapid)});
  for (Distribution distribution : {Distribution::kPerAxis, Distribution::kTangential}) {
    for (int variant = 0; variant < 4; ++variant) {
      ControllerConfig c = config;
      c.post_interp.distribution = distribution;
      if (variant == 1) {
        c.post_interp.type = PostInterpType::kExponential;
      } else if (variant == 2) {
        c.post_interp.type = PostInterpType::kProfileTable;
        c.post_interp.moving_average_s = 0.032;
      } else if (variant == 3) {
        c.pattern.method = "2";
        c.pattern.realization = PatternRealization::kProfileTable;
        c.post_interp.type = PostInterpType::kProfileTable;
        c.post_interp.table = {0.2, 0.5, 0.3};
      }
      c.validate();
      const MultiAxisCommand command = GenerateProgramCommand(c, program);
      EXPECT_LT((command.Positions().back() - program.start_m).norm(), 1e-12)
          << static_cast<int>(distribution) << " " << variant;
      EXPECT_EQ(command.velocity_m_s(command.num_ticks()).norm(), 0.0);
    }
  }
}

// Tests that the profile_table realization of method 1 gives the stepped realization's
// acceleration (a/2 for T/2, then a) on a single move, shifted by nothing at the start.
TEST(ProgramPipelineTest, TableRealizationMatchesSteps) {
  ControllerConfig c = PipelineConfig();
  c.feed_mm_min = 30000;
  c.accel_time_s = 0.3;
  c.pattern.method = "1";
  ControllerConfig table = c;
  table.pattern.realization = PatternRealization::kProfileTable;
  MoveConfig move;
  move.distance_mm = 200;
  const CommandTrajectory stepped = GenerateCommand(c, move);
  const CommandTrajectory tabled = GenerateCommand(table, move);
  const double a = 0.5 / 0.3;
  for (std::size_t k = 1; k <= 20; ++k) {
    EXPECT_NEAR(stepped.accel_m_s2(k), a / 2, 1e-9) << k;
    EXPECT_NEAR(tabled.accel_m_s2(k), a / 2, 1e-9) << k;
  }
  EXPECT_NEAR(tabled.accel_m_s2(21), a, 1e-9);
  EXPECT_NEAR(stepped.accel_m_s2(21), a, 1e-9);
}

// Tests the geometry: arc length and points of a CW half circle and a helix.
TEST(PathGeometryTest, ArcsAndHelix) {
  ProgramBlock half;
  half.kind = MotionKind::kArcCw;
  half.start_m = {-0.01, 0, 0};
  half.end_m = {0.01, 0, 0};
  half.center_m = {0, 0, 0};
  ProgramBlock helix = Circle(0.01, 1000);
  helix.start_m = {0.01, 0, 0};
  helix.end_m = {0.01, 0, 0.002};
  const PathGeometry path(Make({half, helix}));
  ASSERT_EQ(path.elements().size(), 2u);
  EXPECT_NEAR(path.elements()[0].length_m, kPi * 0.01, 1e-15);
  // CW from (-r, 0) seen from +z passes through (0, +r).
  EXPECT_NEAR((path.PointAt(kPi * 0.005) - Eigen::Vector3d(0, 0.01, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(path.elements()[1].length_m, std::hypot(2 * kPi * 0.01, 0.002), 1e-15);
  const double mid = kPi * 0.01 + 0.5 * path.elements()[1].length_m;
  EXPECT_NEAR((path.PointAt(mid) - Eigen::Vector3d(-0.01, 0, 0.001)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(path.DistanceTo({0, 0.012, 0}), 0.002, 1e-15);
  EXPECT_NEAR(path.DistanceTo({0.02, 0, 0}), 0.01, 1e-15);
}

}  // namespace
}  // namespace shapebench::controller

namespace shapebench::controller {
namespace {

// Tests the arc feed clamp: on a small arc the path speed is at most sqrt(a r), so the
// centripetal acceleration stays within the acc/dec's acceleration.
TEST(BlockPlannerTest, ArcFeedIsClampedByItsRadius) {
  ControllerConfig c = PipelineConfig();  // a = 0.1 / 0.06 = 1.667 m/s^2
  const Program program = Make({Circle(0.005, 30000)});
  const MultiAxisCommand command = GenerateProgramCommand(c, program);
  double top = 0;
  for (std::size_t k = 0; k <= command.num_ticks(); ++k) top = std::max(top, command.velocity_m_s(k).norm());
  // The axes run along chords: |chord| / period = v (1 - theta^2 / 24), theta = v dt / r.
  const double v = std::sqrt(c.accel_m_s2() * 0.005);
  const double theta = v * 0.001 / 0.005;
  EXPECT_NEAR(top, v * (1 - theta * theta / 24), 1e-9);
}

}  // namespace
}  // namespace shapebench::controller
