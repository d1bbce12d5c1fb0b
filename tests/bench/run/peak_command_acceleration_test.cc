// peak_command_acceleration_m_s2: the largest norm of the commanded acceleration vector,
// against the linear acc/dec's closed form (a = feed / accel_time_s) and against the
// command's own velocities (a_k = (v_k - v_{k-1}) / period), axis components together.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

// Tests that an unshaped SDOF move reports the linear acc/dec's acceleration, feed /
// accel_time_s (0.5 m/s over 0.3 s), on every sampler that takes it: the velocity ramps in
// equal steps, so the held acceleration is that ratio to rounding (1e-12 relative).
TEST(PeakCommandAcceleration, UnshapedMoveIsFeedOverAccelTime) {
  Scenario s = testing::SdofScenario(25.0, 0.02);
  s.controller.pattern.method = "none";
  const double expected = (30000.0 / 60000.0) / 0.3;
  for (const SamplerKind kind : kAllSamplers) {
    RunOptions options;
    options.record_trace = false;
    options.fastest_sampler = kind;
    const RunResult run = RunScenario(s, options);
    EXPECT_NEAR(run.metrics.peak_command_acceleration_m_s2, expected, 1e-12 * expected) << SamplerName(kind);
  }
}

// Tests that a program on two axes (a pocket with corners) reports the largest norm of
// the acceleration vector, as the command's per-axis velocity differences give it, not the
// largest axis component.
TEST(PeakCommandAcceleration, ProgramIsTheLargestVectorNorm) {
  const Scenario s = LoadScenario(std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/pocket_corner.yaml", {});
  const RunResult run = RunScenario(s, RunOptions{false});
  const controller::MultiAxisCommand& c = run.command;
  double largest = 0.0;
  double largest_component = 0.0;
  for (std::size_t k = 1; k <= c.num_ticks(); ++k) {
    const Eigen::Vector3d a = (c.velocity_m_s(k) - c.velocity_m_s(k - 1)) / c.period_s;
    largest = std::max(largest, a.norm());
    largest_component = std::max(largest_component, a.cwiseAbs().maxCoeff());
  }
  ASSERT_GT(largest, 0.0);
  EXPECT_NEAR(run.metrics.peak_command_acceleration_m_s2, largest, 1e-9 * largest);
  EXPECT_GE(run.metrics.peak_command_acceleration_m_s2, largest_component);
}

}  // namespace
}  // namespace shapebench::bench
