// The static reference of programs (issue 36): the deflection under the acc/dec's
// acceleration along the program's directions, not a corner's one-period velocity step,
// so the ratios keep their meaning; a single move's stays the commanded acceleration's.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "common/math_constants.h"
#include "controller/gcode_parser.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench::program_static_reference_test {
namespace {

// An undamped 5 Hz mode on Y (period T = 0.2 s), 0.5 m/s with a 0.4 s = 2 T acc/dec
// (1.25 m/s^2), unshaped; corners taken at full feed (the corner rule's allowance above
// the steps), so at each corner Y's velocity steps by 0.02 m/s within two periods (the
// corner falls inside one): 10 m/s^2, 8 times the acc/dec's.
Scenario CornerScenario() {
  Scenario s = testing::SdofScenario(5.0, 0.0);
  s.controller.pattern.method = "none";
  s.controller.feed_mm_min = 30000.0;
  s.controller.accel_time_s = 0.4;
  s.controller.corner_velocity_change_mm_min = 9000.0;
  // Y 300 mm, then 100 mm along (0.28, 0.96) (one period T at 0.5 m/s, so the second
  // corner's step cancels the ring of the first), then Y 300 mm.
  s.program = controller::ParseGcode("G1 Y300 F30000\nX28 Y396\nY696\n");
  return s;
}

// Tests that an unshaped program whose acceleration stretches (2 T) last longer than T/2
// of an undamped mode has peak_ratio in [1.9, 2.0] (the held step's 1 - cos peak, 2), while
// the command's own largest acceleration, a corner's step, would have read 2 / 8 = 0.25:
// the static reference is the acc/dec's 1.25 m/s^2 along Y.
TEST(ProgramStaticReference, UnshapedProgramPeaksAtTwice) {
  const Scenario s = CornerScenario();
  const RunResult run = RunScenario(s, RunOptions{false});
  const controller::MultiAxisCommand& c = run.command;
  double largest_y = 0.0;
  for (std::size_t k = 1; k <= c.num_ticks(); ++k) largest_y = std::max(largest_y, std::abs(c.accel_m_s2(k).y()));
  EXPECT_GT(largest_y, 7.9 * s.controller.accel_m_s2());
  const double w = 2.0 * kPi * 5.0;
  EXPECT_NEAR(run.metrics.static_displacement_m, 1.25 / (w * w), 1e-9 * 1.25 / (w * w));
  EXPECT_GE(run.metrics.peak_ratio, 1.9);
  EXPECT_LE(run.metrics.peak_ratio, 2.0 * (1.0 + 1e-9)) << run.metrics.peak_ratio;
  // Where the commanded acceleration peaked: a corner (block 1 or 2, 0-based).
  ASSERT_TRUE(run.sources.peak_command_acceleration.present);
  EXPECT_GE(run.sources.peak_command_acceleration.at.block, 0);
  EXPECT_LE(run.sources.peak_command_acceleration.at.block, 2);
}

// Tests that a single move keeps its reference: the commanded acceleration's, equal to the
// acc/dec's along its axis.
TEST(ProgramStaticReference, SingleMoveUnchanged) {
  Scenario s = testing::SdofScenario(25.0, 0.0);
  s.controller.pattern.method = "none";
  const RunResult run = RunScenario(s, RunOptions{false});
  const double w = 2.0 * kPi * 25.0;
  const double a = s.controller.accel_m_s2();
  EXPECT_NEAR(run.metrics.static_displacement_m, a / (w * w), 1e-9 * a / (w * w));
}

}  // namespace
}  // namespace shapebench::bench::program_static_reference_test
