// The tail after the motion (bench/run/run_scenario.cc): the residual window of three lowest-mode
// periods, then on until a whole period stays inside the 5% band (at most 30 periods); an
// undamped structure under the kinematic drive stops at the window's end.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;

// sdof_method1 (method 1 designed for 25 Hz) on a 22 Hz mode: the residual vibration is
// far above the 5% band (0.66 of static).
RunResult RunAt22Hz(const std::string& damping_ratio) {
  return RunScenario(LoadScenario(DataPath("sweeps/sdof_method1.yaml"),
                                  {{"machine.modes[0].frequency_hz", "22"},
                                   {"machine.modes[0].damping_ratio", damping_ratio}}),
                     RunOptions{false});
}

// Tests that an undamped run that has not settled by the end of the residual window ends
// there: settling_time_s undefined, the simulated time the motion plus three periods.
TEST(CosimTail, UndampedStopsAtTheWindowsEnd) {
  const RunResult run = RunAt22Hz("0");
  const double dt = 0.001;
  EXPECT_GT(run.metrics.residual_ratio, 0.05);
  EXPECT_TRUE(std::isnan(run.metrics.settling_time_s));
  const double window_s = std::ceil(3.0 / 22.0 / dt) * dt;  // whole ticks
  EXPECT_NEAR(run.simulated_s, run.metrics.motion_time_s + window_s, 0.5 * dt);
}

// Tests that the longer tail would have changed nothing but the sampling: the same run
// with a damping ratio of 1e-12 (which decays by 1e-10 over the tail, so the run goes on
// its 30 periods) has the same residual and a peak within the sampling bound
// 1 - cos(pi / 200) = 1.2e-4 of the undamped run's.
TEST(CosimTail, LongerTailOnlyRepeatsTheWindow) {
  const RunResult undamped = RunAt22Hz("0");
  const RunResult barely = RunAt22Hz("1e-12");
  const double tail_s = 30.0 * std::ceil(1.0 / 22.0 / 0.001) * 0.001;  // 30 periods in whole ticks
  EXPECT_NEAR(barely.simulated_s, undamped.metrics.motion_time_s + tail_s, 0.5e-3);
  EXPECT_NEAR(barely.metrics.residual_ratio, undamped.metrics.residual_ratio,
              1e-9 * undamped.metrics.residual_ratio);
  EXPECT_NEAR(barely.metrics.peak_ratio, undamped.metrics.peak_ratio,
              (1.0 - std::cos(M_PI / 200.0)) * undamped.metrics.peak_ratio);
}

// Tests that a damped structure keeps its tail: it runs past the window until it settles,
// and the settling time is that of the mode's envelope, ln(R / 0.05) / (zeta w), within a
// period (the band is watched sample by sample, the envelope crosses it within one).
TEST(CosimTail, DampedRunsUntilSettled) {
  const double zeta = 0.05;
  const RunResult run = RunAt22Hz("0.05");
  ASSERT_TRUE(std::isfinite(run.metrics.settling_time_s));
  const double w = 2.0 * M_PI * 22.0;
  const double residual = run.metrics.residual_ratio;  // the window's first peak, about
  EXPECT_GT(residual, 0.05);
  const double envelope_s = std::log(residual / 0.05) / (zeta * w);
  EXPECT_NEAR(run.metrics.settling_time_s, envelope_s, 1.0 / 22.0);
  EXPECT_GT(run.simulated_s, run.metrics.motion_time_s + run.metrics.settling_time_s);
}

}  // namespace
}  // namespace shapebench::bench
