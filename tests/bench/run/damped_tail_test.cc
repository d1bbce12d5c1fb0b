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

INSTANTIATE_TEST_SUITE_P(Frequencies, DampedTailTest,
                         ::testing::Values(15.0, 18.4, 21.0, 23.3, 25.0, 26.7, 29.0, 31.9, 35.0));

}  // namespace
}  // namespace shapebench::bench
