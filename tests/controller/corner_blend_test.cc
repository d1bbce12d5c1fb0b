// LinuxCNC's G64 (controller/corner_blend.h): corners blended within the path tolerance,
// the feed planned over the blocks ahead, each axis' commanded acceleration within the
// acc/dec's; checked against the programmed polyline geometrically, not through the
// bench's own path code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "controller/controller.h"
#include "controller/gcode_parser.h"

namespace shapebench::controller::corner_blend_test {
namespace {

Program LinuxCnc(const std::string& text) {
  GcodeOptions options;
  options.program.dialect = Dialect::kLinuxcnc;
  return ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
}

ControllerConfig BlendConfig() {
  ControllerConfig c;
  c.feed_mm_min = 6000.0;
  c.accel_time_s = 0.05;  // 2 m/s^2
  return c;
}

// The programmed polyline's vertices: the program's start and every block's end.
std::vector<Eigen::Vector3d> Vertices(const Program& program) {
  std::vector<Eigen::Vector3d> v{program.start_m};
  for (const ProgramBlock& b : program.blocks) v.push_back(b.end_m);
  return v;
}

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

double DistanceToPolyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& v) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < v.size(); ++i) best = std::min(best, DistanceToSegment(p, v[i - 1], v[i]));
  return best;
}

// The largest distance of a commanded point from the polyline.
double LargestDeviation(const MultiAxisCommand& command, const Program& program) {
  const std::vector<Eigen::Vector3d> v = Vertices(program);
  double largest = 0.0;
  for (const Eigen::Vector3d& p : command.Positions()) largest = std::max(largest, DistanceToPolyline(p, v));
  return largest;
}

// The largest |a| of any one axis over the command.
double LargestAxisAcceleration(const MultiAxisCommand& command) {
  double largest = 0.0;
  for (std::size_t k = 1; k <= command.num_ticks(); ++k) {
    largest = std::max(largest, command.accel_m_s2(k).cwiseAbs().maxCoeff());
  }
  return largest;
}

const char* const kSquare = "G1 X50 F6000\nY50\nX0\nY0\n";

// Tests that a square of four moves under G64 P0.05 stays within 0.05 mm of the programmed
// polyline at every commanded point, blends (the deviation reaches the closed form
// P cos(45 deg) from the lines), keeps each axis within the acc/dec's 2 m/s^2 and finishes
// sooner than under G61, which stops at every corner.
TEST(CornerBlendTest, SquareWithinToleranceFasterThanExactStop) {
  const ControllerConfig config = BlendConfig();
  const Program blended = LinuxCnc(std::string("G64 P0.05\n") + kSquare);
  const Program exact = LinuxCnc(std::string("G61\n") + kSquare);
  const MultiAxisCommand g64 = GenerateProgramCommand(config, blended);
  const MultiAxisCommand g61 = GenerateProgramCommand(config, exact);
  const double deviation = LargestDeviation(g64, blended);
  EXPECT_LE(deviation, 0.05e-3 + 1e-12);
  // The arc's midpoint lies P from the corner, P cos(theta/2) from the lines.
  EXPECT_NEAR(deviation, 0.05e-3 * std::cos(0.25 * 3.14159265358979323846), 0.002e-3);
  EXPECT_LE(LargestDeviation(g61, exact), 1e-12);
  EXPECT_LE(LargestAxisAcceleration(g64), config.accel_m_s2() * (1.0 + 1e-9));
  EXPECT_LT(g64.num_ticks(), g61.num_ticks());
  // The interpolator's positions are the programmed path's: they end at its 200 mm.
  EXPECT_NEAR(g64.path_position_m.back(), 0.2, 1e-12);
  EXPECT_EQ(g64.block.back(), 3);
  // The patent's shaping (method 1 at 25 Hz, stepped) on the blended feed: the same bounds.
  ControllerConfig shaped = config;
  shaped.pattern.method = "1";
  const MultiAxisCommand method1 = GenerateProgramCommand(shaped, blended);
  EXPECT_LE(LargestDeviation(method1, blended), 0.05e-3 + 1e-12);
  EXPECT_LE(LargestAxisAcceleration(method1), config.accel_m_s2() * (1.0 + 1e-9));
  EXPECT_LT(method1.num_ticks(), GenerateProgramCommand(shaped, exact).num_ticks());
}

// Tests the look-ahead on short blocks in three dimensions (no blend in a coordinate
// plane): every point within P of the polyline and every axis within the acc/dec's
// acceleration, where the speed a blend allows must be reached on the short lines before
// it; sooner than G61, and as G61 where P is too small for a blend to pay.
TEST(CornerBlendTest, ShortBlocksInSpaceStayWithinLimits) {
  const ControllerConfig config = BlendConfig();
  std::string text = "G64 P0.01\nG1 F6000\n";
  for (int i = 1; i <= 40; ++i) {
    const double x = 2.0 * i;
    const double y = (i % 2) * 1.5;
    const double z = (i % 3) * 0.7;
    text += "X" + std::to_string(x) + " Y" + std::to_string(y) + " Z" + std::to_string(z) + "\n";
  }
  text += "X0 Y0 Z0\n";  // back along the row: a near reversal
  const Program program = LinuxCnc(text);
  const MultiAxisCommand command = GenerateProgramCommand(config, program);
  EXPECT_LE(LargestDeviation(command, program), 0.01e-3 + 1e-12);
  EXPECT_LE(LargestAxisAcceleration(command), config.accel_m_s2() * (1.0 + 1e-9));
  const MultiAxisCommand exact = GenerateProgramCommand(config, LinuxCnc("G61\n" + text.substr(10)));
  EXPECT_LT(command.num_ticks(), exact.num_ticks());
  // A tolerance too small for the blend to pay (r < 16 a T^2) leaves the stop.
  EXPECT_EQ(GenerateProgramCommand(config, LinuxCnc("G64 P0.001\n" + text.substr(10))).num_ticks(),
            exact.num_ticks());
}

// Tests G64 without P: the blend takes half of the shorter line (the best speed, no
// tolerance), so the 10 mm square's corners deviate by r (1 / cos(45 deg) - 1) from the
// corner, r = 5 mm / tan(45 deg).
TEST(CornerBlendTest, NoToleranceTakesHalfTheLine) {
  const Program program = LinuxCnc("G64\nG1 X10 F6000\nY10\nX0\n");
  EXPECT_TRUE(std::isinf(program.blocks[0].blend_tolerance_m));
  const MultiAxisCommand command = GenerateProgramCommand(BlendConfig(), program);
  const Eigen::Vector3d corner(0.01, 0.0, 0.0);
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : command.Positions()) nearest = std::min(nearest, (p - corner).norm());
  const double r = 0.005;
  EXPECT_NEAR(nearest, r * (std::sqrt(2.0) - 1.0), 2e-6);
}

// Tests G64 Q: lines within Q of their chord run as the chord (at full feed, no blend in
// between), while P alone keeps the kinks.
TEST(CornerBlendTest, CollinearMergeWithinQ) {
  const std::string moves = "G1 X10 Y0.002 F6000\nX20 Y0\nX30 Y0.002\nX40 Y0\n";
  const Program merged = LinuxCnc("G64 P0.01 Q0.005\n" + moves);
  const MultiAxisCommand command = GenerateProgramCommand(BlendConfig(), merged);
  const Eigen::Vector3d end(0.04, 0.0, 0.0);
  double off_chord = 0.0;
  for (const Eigen::Vector3d& p : command.Positions()) off_chord = std::max(off_chord, std::abs(p.y()));
  EXPECT_LE(off_chord, 1e-12);
  EXPECT_NEAR(command.path_position_m.back(), PathGeometry(merged).length_m(), 1e-12);
  EXPECT_EQ(command.block.back(), 3);
  const Program kinks = LinuxCnc("G64 P0.01\n" + moves);
  off_chord = 0.0;
  for (const Eigen::Vector3d& p : GenerateProgramCommand(BlendConfig(), kinks).Positions()) {
    off_chord = std::max(off_chord, std::abs(p.y()));
  }
  EXPECT_GT(off_chord, 1e-6);
}

// Tests how the reader records the path mode: linuxcnc's G64 P in program units, G64
// alone without tolerance, G61 and fanuc's G64 none (with fanuc's one warning).
TEST(CornerBlendTest, ReaderRecordsTheMode) {
  const Program inch = LinuxCnc("G20 G64 P0.001 Q0.0005 G1 X1 F10\nG61 X2\n");
  EXPECT_DOUBLE_EQ(inch.blocks[0].blend_tolerance_m, 0.0254e-3);
  EXPECT_DOUBLE_EQ(inch.blocks[0].merge_tolerance_m, 0.0127e-3);
  EXPECT_LT(inch.blocks[1].blend_tolerance_m, 0.0);
  EXPECT_EQ(inch.blocks[1].merge_tolerance_m, 0.0);
  EXPECT_TRUE(inch.warnings.empty());
  GcodeOptions fanuc;
  const Program cutting = ParseGcode("G64 G1 X1 F100\nY1\n", Eigen::Vector3d::Zero(), {}, fanuc);
  EXPECT_LT(cutting.blocks[0].blend_tolerance_m, 0.0);
  ASSERT_EQ(cutting.warnings.size(), 1u);
  EXPECT_NE(cutting.warnings[0].find("corner rule"), std::string::npos);
}

}  // namespace
}  // namespace shapebench::controller::corner_blend_test
