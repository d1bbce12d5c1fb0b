// ParseGcode under GcodeLimits: reading stops at the line whose block crosses the path-time
// or block-count limit, so a huge file never becomes a whole program in memory.
#include <string>

#include <gtest/gtest.h>

#include "controller/gcode_parser.h"

namespace shapebench::controller {
namespace {

GcodeLimits TestLimits() {
  GcodeLimits limits;
  limits.max_blocks = 5;
  limits.max_blocks_key = "limits.blocks";
  limits.max_path_s = 1.0;
  limits.max_path_key = "limits.seconds";
  limits.default_feed_m_s = 0.01;  // 600 mm/min
  limits.rapid_feed_m_s = 1.0;
  return limits;
}

std::string LimitErrorOf(const std::string& text, int* line) {
  try {
    ParseGcode(text, Eigen::Vector3d::Zero(), TestLimits());
  } catch (const ProgramError& error) {
    *line = error.line();
    return error.message();
  }
  return "";
}

// Tests that the path's time at its feeds (chord over feed, F words and the default feed,
// plus dwells) stops the parse at the line that crosses max_path_s, naming its key, and
// that a program within the limits parses as before.
TEST(GcodeLimits, PathTimeStopsTheParseAtTheCrossingLine) {
  int line = 0;
  // 4 mm at 600 mm/min: 0.4 s each; the third block crosses 1 s.
  std::string message = LimitErrorOf("G1 X4\nX0\nX4\nX0\n", &line);
  EXPECT_EQ(line, 3);
  EXPECT_NE(message.find("more than limits.seconds allows; reading stopped here"), std::string::npos) << message;
  // A dwell counts; F6000 (0.1 m/s) makes the moves short in time.
  message = LimitErrorOf("G1 F6000 X4\nG4 P990\nX0\n", &line);
  EXPECT_EQ(line, 2);
  // Rapids at the rapid feed: 1 m in 1 s is not more than the limit.
  EXPECT_EQ(ParseGcode("G0 X1000\n", Eigen::Vector3d::Zero(), TestLimits()).blocks.size(), 1u);
}

// Tests that more blocks than max_blocks stop the parse even when they take no time.
TEST(GcodeLimits, BlockCountStopsTheParse) {
  int line = 0;
  const std::string message = LimitErrorOf("G4 P0\nG4 P0\nG4 P0\nG4 P0\nG4 P0\nG4 P0\nG4 P0\n", &line);
  EXPECT_EQ(line, 6);
  EXPECT_NE(message.find("more than 5 blocks by this line, more than limits.blocks"), std::string::npos) << message;
}

}  // namespace
}  // namespace shapebench::controller
