// grbl's junction rule (controller/block_planner.h, JunctionDeviationLimit): every junction
// of a grbl program is run at the speed grbl's planner gives it from the junction deviation
// and the acceleration, the feed planned over the blocks with the look-ahead. Checked
// against closed forms written here from grbl's definition, not through the planner's code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/math_constants.h"
#include "common/validation_error.h"
#include "controller/block_planner.h"
#include "controller/controller.h"
#include "controller/gcode_parser.h"

namespace shapebench::controller::grbl_junction_test {
namespace {

Program Parse(const std::string& text, Dialect dialect) {
  GcodeOptions options;
  options.program.dialect = dialect;
  return ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
}

ControllerConfig GrblConfig(double deviation_mm) {
  ControllerConfig c;
  c.feed_mm_min = 6000.0;
  c.accel_time_s = 0.05;  // a = 2 m/s^2
  c.junction_deviation_mm = deviation_mm;
  return c;
}

// grbl's junction speed for a turn by `turn_rad` in the XY plane from +X, from its
// definition: the interior angle is pi - turn, the junction vector (cos turn - 1, sin turn)
// normalised, each axis held to a.
double ClosedFormJunctionSpeed(double turn_rad, double a, double delta) {
  const double s = std::sin((kPi - turn_rad) / 2);
  const double jx = std::cos(turn_rad) - 1.0, jy = std::sin(turn_rad);
  const double norm = std::hypot(jx, jy);
  const double a_j = a / std::max(std::abs(jx), std::abs(jy)) * norm;
  return std::sqrt(a_j * delta * s / (1.0 - s));
}

// Tests that the junction speed follows grbl's formula v^2 = a_j delta sin(phi/2) /
// (1 - sin(phi/2)) at every turn from 10 to 170 degrees, and that a 90-degree corner's
// equals sqrt(sqrt(2) a delta (sqrt(2)/2) / (1 - sqrt(2)/2)) (a_j = sqrt(2) a along the
// diagonal, each axis at a).
TEST(GrblJunctionTest, JunctionSpeedIsGrblsFormula) {
  const double a = 2.0, delta = 1e-5;
  for (int deg = 10; deg <= 170; deg += 10) {
    const double turn = deg * kPi / 180.0;
    const Eigen::Vector3d before(1, 0, 0), after(std::cos(turn), std::sin(turn), 0);
    EXPECT_NEAR(JunctionDeviationLimit(before, after, a, delta), ClosedFormJunctionSpeed(turn, a, delta), 1e-12)
        << deg << " deg";
  }
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(JunctionDeviationLimit({1, 0, 0}, {0, 1, 0}, a, delta),
              std::sqrt(std::sqrt(2.0) * a * delta * s / (1.0 - s)), 1e-12);
}

// Tests that a 90-degree corner of a grbl program is cut at the formula's junction speed:
// the last period along X alone averages between v_j and v_j + 2 a T (the deceleration
// ends at v_j at the corner, within the next period), at a 0.1 ms period.
TEST(GrblJunctionTest, CornerOfAProgramRunsAtTheJunctionSpeed) {
  for (const double deviation_mm : {0.01, 0.05}) {
    ControllerConfig config = GrblConfig(deviation_mm);
    config.period_s = 1e-4;
    const MultiAxisCommand command = GenerateProgramCommand(config, Parse("G1 X50 F6000\nY50\n", Dialect::kGrbl));
    const double v_j = ClosedFormJunctionSpeed(kPi / 2, config.accel_m_s2(), deviation_mm * 1e-3);
    std::size_t last_x = 0;  // the last tick moving X only
    for (std::size_t k = 1; k <= command.num_ticks(); ++k) {
      if (command.axes[1].velocity_m_s[k] != 0.0) break;
      last_x = k;
    }
    ASSERT_GT(last_x, 0u);
    const double vx = command.axes[0].velocity_m_s[last_x];
    EXPECT_GE(vx, v_j - 1e-9) << deviation_mm;
    EXPECT_LE(vx, v_j + 2 * config.accel_m_s2() * config.period_s) << deviation_mm;
    EXPECT_GT(v_j, 0.005);  // well above a stop: 8.3 mm/s at 0.01 mm
  }
}

// Tests that a straight continuation (interior angle 180 degrees) runs through without
// slowing: two collinear blocks give the command of the one block they make, period for
// period (within rounding).
TEST(GrblJunctionTest, StraightContinuationDoesNotSlow) {
  const ControllerConfig config = GrblConfig(0.01);
  EXPECT_TRUE(std::isinf(JunctionDeviationLimit({1, 0, 0}, {1, 0, 0}, 2.0, 1e-5)));
  const MultiAxisCommand two = GenerateProgramCommand(config, Parse("G1 X50 F6000\nX100\n", Dialect::kGrbl));
  const MultiAxisCommand one = GenerateProgramCommand(config, Parse("G1 X100 F6000\n", Dialect::kGrbl));
  ASSERT_EQ(two.num_ticks(), one.num_ticks());
  for (std::size_t k = 1; k <= one.num_ticks(); ++k) {
    EXPECT_NEAR(two.axes[0].velocity_m_s[k], one.axes[0].velocity_m_s[k], 1e-12) << k;
  }
  EXPECT_NEAR(*std::max_element(two.axes[0].velocity_m_s.begin(), two.axes[0].velocity_m_s.end()), 0.1, 1e-12);
}

// Tests that a reversal (interior angle 0) stops: the junction speed is 0 and X passes
// through a period at rest between the two directions.
TEST(GrblJunctionTest, ReversalStops) {
  EXPECT_EQ(JunctionDeviationLimit({1, 0, 0}, {-1, 0, 0}, 2.0, 1e-5), 0.0);
  const MultiAxisCommand command =
      GenerateProgramCommand(GrblConfig(0.01), Parse("G1 X50 F6000\nX0\n", Dialect::kGrbl));
  const std::vector<double>& v = command.axes[0].velocity_m_s;
  bool rested = false;
  for (std::size_t k = 1; k < v.size(); ++k) {
    EXPECT_FALSE(v[k - 1] > 0.0 && v[k] < 0.0) << "tick " << k << ": reversed without a stop";
    rested = rested || (v[k] == 0.0 && k + 1 < v.size() && v[k + 1] < 0.0);
  }
  EXPECT_TRUE(rested);
}

// Tests that each axis' commanded acceleration stays within the acc/dec's a in the acc/dec
// phases (every period but the corners', where grbl steps each axis' velocity by at most
// v_j |t2 - t1| per axis, here v_j for a right angle), and that the acceleration the
// junction speed is computed with, a_j along the junction vector, holds each axis within a.
TEST(GrblJunctionTest, EachAxisWithinTheLimit) {
  const ControllerConfig config = GrblConfig(0.01);
  const double a = config.accel_m_s2();
  const MultiAxisCommand command =
      GenerateProgramCommand(config, Parse("G1 X50 F6000\nY50\nX0\nY0\n", Dialect::kGrbl));
  const double v_j = ClosedFormJunctionSpeed(kPi / 2, a, 1e-5);
  int corner_ticks = 0;
  for (std::size_t k = 1; k <= command.num_ticks(); ++k) {
    const Eigen::Vector3d acc = command.accel_m_s2(k);
    const double largest = acc.cwiseAbs().maxCoeff();
    if (largest > a * (1 + 1e-9)) {
      ++corner_ticks;
      EXPECT_LE(largest * config.period_s, v_j + a * config.period_s + 1e-9) << "tick " << k;
    }
  }
  EXPECT_LE(corner_ticks, 3 * 2);  // at most two periods at each of the three corners
  const Eigen::Vector3d junction = (Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(1, 0, 0)).normalized();
  const double a_j = a / junction.cwiseAbs().maxCoeff();
  EXPECT_LE((a_j * junction).cwiseAbs().maxCoeff(), a * (1 + 1e-12));
}

// Tests that the square finishes sooner under grbl's junction rule than with a stop at
// every corner (junction deviation 0, which is the stop-at-corner rule: the same command,
// bit for bit, as linuxcnc's G61 with the corner rule's 0).
TEST(GrblJunctionTest, FinishesSoonerThanStoppingAtCorners) {
  const std::string square = "G1 X50 F6000\nY50\nX0\nY0\n";
  const MultiAxisCommand junction = GenerateProgramCommand(GrblConfig(0.01), Parse(square, Dialect::kGrbl));
  const MultiAxisCommand stop = GenerateProgramCommand(GrblConfig(0.0), Parse(square, Dialect::kGrbl));
  const MultiAxisCommand g61 = GenerateProgramCommand(GrblConfig(0.01), Parse("G61\n" + square, Dialect::kLinuxcnc));
  EXPECT_LT(junction.num_ticks(), stop.num_ticks());
  for (int a = 0; a < kNumAxes; ++a) EXPECT_EQ(stop.axes[a].velocity_m_s, g61.axes[a].velocity_m_s) << a;
}

// Tests that a negative or non-finite junction deviation is refused naming the key.
TEST(GrblJunctionTest, NegativeDeviationIsRefused) {
  for (const double bad : {-0.01, std::nan("")}) {
    ControllerConfig config;
    config.junction_deviation_mm = bad;
    try {
      config.validate();
      ADD_FAILURE() << "accepted " << bad;
    } catch (const ValidationError& error) {
      EXPECT_EQ(error.field(), "junction_deviation_mm");
    }
  }
}

}  // namespace
}  // namespace shapebench::controller::grbl_junction_test
