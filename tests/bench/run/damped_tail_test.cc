// The settling tail in closed form (bench/run/damped_tail.h, run without a trace: sweeps,
// checks) against the simulated tail (the run that records its trace simulates it, sample
// by sample): settling_time_s within the old sampling resolution dt / substeps (both read
// the same grid of samples, so they agree exactly but where a sample lies within rounding
// of the band), the same run length, on benchmark case 1 damped 2% across 15 to 35 Hz.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "tests/support/general_path.h"

namespace shapebench::bench {
namespace {

class DampedTailTest : public ::testing::TestWithParam<double> {};

// Tests that the closed-form tail gives the simulated tail's settling time and run length.
TEST_P(DampedTailTest, SettlingEqualsTheSimulatedTail) {
  for (const char* zeta : {"0.02", "0.05"}) {
    const Scenario s = LoadScenario(std::string(SHAPEBENCH_SOURCE_DIR) + "/benchmarks/cases/case1.yaml",
                                    {{"machine.modes[0].frequency_hz", std::to_string(GetParam())},
                                     {"machine.modes[0].damping_ratio", zeta}});
    const RunResult simulated = RunScenario(s, testing::GeneralPath(true));
    const RunResult closed = RunScenario(s, testing::GeneralPath(false));
    EXPECT_FALSE(simulated.tail_in_closed_form);
    const double resolution = 0.001 / closed.substeps;
    if (std::isnan(simulated.metrics.settling_time_s)) {
      EXPECT_TRUE(std::isnan(closed.metrics.settling_time_s));
    } else {
      EXPECT_NEAR(closed.metrics.settling_time_s, simulated.metrics.settling_time_s, resolution)
          << GetParam() << " Hz, zeta " << zeta;
    }
    EXPECT_EQ(closed.simulated_s, simulated.simulated_s);
    EXPECT_EQ(closed.metrics.peak_ratio, simulated.metrics.peak_ratio);
    EXPECT_EQ(closed.metrics.max_contour_error_m, simulated.metrics.max_contour_error_m);
    // A run that went on past the residual window had its tail in closed form.
    const double window_end_s = closed.metrics.motion_time_s + std::ceil(3.0 / GetParam() / 0.001) * 0.001;
    EXPECT_EQ(closed.tail_in_closed_form, simulated.simulated_s > window_end_s + 0.5e-3) << GetParam() << " " << zeta;
  }
}

// Tests that a CVODE run finds its settling tail in closed form too, from CVODE's state at
// the residual window's end: every metric the simulated tail's (settling_time_s within one
// sample), the same run length, and fewer CVODE steps (the tail is not integrated).
TEST(DampedTailCvode, ClosedFormTailKeepsTheMetrics) {
  for (const char* hz : {"15", "21.3", "27.5", "31.9", "35"}) {  // off the design: a tail
    const Scenario s = LoadScenario(std::string(SHAPEBENCH_SOURCE_DIR) + "/benchmarks/cases/case1_damped.yaml",
                                    {{"machine.modes[0].frequency_hz", hz}, {"integrator.method", "cvode"}});
    const RunResult simulated = RunScenario(s, RunOptions{true});
    const RunResult closed = RunScenario(s, RunOptions{false});
    EXPECT_FALSE(simulated.tail_in_closed_form);
    EXPECT_TRUE(closed.tail_in_closed_form) << hz;
    EXPECT_NEAR(closed.metrics.settling_time_s, simulated.metrics.settling_time_s, 0.001 / closed.substeps) << hz;
    EXPECT_EQ(closed.simulated_s, simulated.simulated_s) << hz;
    EXPECT_EQ(closed.metrics.peak_ratio, simulated.metrics.peak_ratio) << hz;
    EXPECT_EQ(closed.metrics.residual_ratio, simulated.metrics.residual_ratio) << hz;
    EXPECT_EQ(closed.metrics.residual_peak_ratio, simulated.metrics.residual_peak_ratio) << hz;
    EXPECT_EQ(closed.metrics.max_contour_error_m, simulated.metrics.max_contour_error_m) << hz;
    EXPECT_LT(closed.stats.steps, simulated.stats.steps) << hz;
  }
}

INSTANTIATE_TEST_SUITE_P(Frequencies, DampedTailTest,
                         ::testing::Values(15.0, 18.4, 21.0, 23.3, 25.0, 26.7, 29.0, 31.9, 35.0));

}  // namespace
}  // namespace shapebench::bench
