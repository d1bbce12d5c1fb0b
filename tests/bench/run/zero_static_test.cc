// A valid model whose static deflections cancel in the output view (static displacement
// 0): the ratios to it are n/a (NaN), the absolute metrics stand, on every sampler.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench {
namespace {

const std::string kCancelling = std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/bench/data/reliability/cancelling_modes.yaml";

// Tests that the cancelling model (25 Hz gain 0.1, 50 Hz gain -0.4: the static
// deflections -0.1 / w^2 + 0.4 / (2 w)^2 = 0 exactly) runs on every sampler that takes it,
// CVODE and exact, magnitude and Y views: static_displacement_m 0, peak_ratio,
// residual_ratio, residual_peak_ratio, cruise_residual_ratio and settling_time_s NaN
// (no ratio to 0, no 5% band of it), the absolute metrics finite and the same on every
// sampler (peak_deflection_m > 0: the 25 Hz mode's first swing, 2 x 0.1 a / w^2 = 13.5 um
// at most, the 50 Hz mode's only a quarter of that).
TEST(ZeroStatic, RatiosAreNotAvailableAbsoluteMetricsStand) {
  const double a = 0.5 / 0.3, w = 2.0 * 3.14159265358979323846 * 25.0;
  for (const char* method : {"cvode", "exact"}) {
    for (const char* view : {"magnitude", "y"}) {
      const Scenario scenario = LoadScenario(
          kCancelling, {{"integrator.method", method}, {"output.direction", view}});
      double peak = NAN;
      for (const SamplerKind kind : kAllSamplers) {
        RunOptions options;
        options.record_trace = false;
        options.fastest_sampler = kind;
        const RunResult run = RunScenario(scenario, options);
        const Metrics& m = run.metrics;
        SCOPED_TRACE(std::string(method) + ", " + view + ", " + std::string(SamplerName(run.sampler)));
        EXPECT_EQ(m.static_displacement_m, 0.0);
        for (const double ratio : {m.peak_ratio, m.residual_ratio, m.residual_peak_ratio, m.cruise_residual_ratio,
                                   m.settling_time_s}) {
          EXPECT_TRUE(std::isnan(ratio)) << ratio;
        }
        EXPECT_GT(m.peak_deflection_m, 0.5 * 0.1 * a / (w * w));
        EXPECT_LE(m.peak_deflection_m, 2.0 * 0.1 * a / (w * w) * (1.0 + 1e-6) + 0.5 * 0.4 * a / (4.0 * w * w));
        EXPECT_TRUE(std::isfinite(m.residual_amplitude_m));
        EXPECT_TRUE(std::isfinite(m.residual_peak_m));
        EXPECT_TRUE(std::isfinite(m.max_contour_error_m));
        if (std::isnan(peak)) peak = m.peak_deflection_m;
        EXPECT_NEAR(m.peak_deflection_m, peak, 1e-9 * peak);
      }
    }
  }
}

}  // namespace
}  // namespace shapebench::bench
