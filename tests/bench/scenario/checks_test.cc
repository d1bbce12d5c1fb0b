// Evaluating checks against metrics, and the console line of each.
#include "bench/scenario/checks.h"

#include <gtest/gtest.h>

namespace shapebench::bench {
namespace {

Metrics SomeCheckedMetrics() {
  Metrics metrics;
  metrics.static_displacement_m = 8e-6;
  metrics.peak_ratio = 1.99984;
  metrics.residual_ratio = 0.004;
  return metrics;  // cruise_residual_ratio and others stay NaN
}

// Tests that inclusive min/max bounds pass and fail as expected, in the checks' order.
TEST(Checks, BoundsAreInclusive) {
  const std::vector<Check> checks = {{"peak_ratio", std::nullopt, 2.01},
                                     {"residual_ratio", 0.004, 0.004},
                                     {"peak_ratio", std::nullopt, 1.01},
                                     {"residual_ratio", 0.01, std::nullopt}};
  const auto results = EvaluateChecks(checks, SomeCheckedMetrics());
  ASSERT_EQ(results.size(), 4u);
  EXPECT_TRUE(results[0].passed);
  EXPECT_TRUE(results[1].passed);
  EXPECT_FALSE(results[2].passed);
  EXPECT_EQ(results[2].message, "above max 1.01");
  EXPECT_FALSE(results[3].passed);
  EXPECT_EQ(results[3].message, "below min 0.01");
}

// Tests that a metric not defined for the run (NaN) fails with the documented message.
TEST(Checks, NanFails) {
  const auto results =
      EvaluateChecks({{"cruise_residual_ratio", std::nullopt, 1.0}}, SomeCheckedMetrics());
  ASSERT_EQ(results.size(), 1u);
  EXPECT_FALSE(results[0].passed);
  EXPECT_EQ(results[0].message, "metric not defined for this run");
  EXPECT_EQ(FormatCheckLine("f.yaml", results[0]),
            "FAIL f.yaml cruise_residual_ratio = n/a (max 1): metric not defined for this run");
}

// Tests that a ratio that is n/a because the static displacement is 0 (a model whose
// static deflections cancel) fails naming that reason and the absolute metric to bound
// instead; the settling time (its band is 5% of static) likewise; a metric n/a for another
// reason keeps the general message.
TEST(Checks, RatioToAZeroStaticFailsNamingTheReason) {
  Metrics metrics;
  metrics.static_displacement_m = 0.0;
  metrics.peak_deflection_m = 1.35e-5;
  const auto results = EvaluateChecks({{"peak_ratio", std::nullopt, 2.0},
                                       {"settling_time_s", std::nullopt, 1.0},
                                       {"radial_error_m", std::nullopt, 1.0},
                                       {"peak_deflection_m", std::nullopt, 1e-4}},
                                      metrics);
  ASSERT_EQ(results.size(), 4u);
  EXPECT_FALSE(results[0].passed);
  EXPECT_EQ(FormatCheckLine("f.yaml", results[0]),
            "FAIL f.yaml peak_ratio = n/a (max 2): peak_ratio is n/a because the static displacement is 0 (the "
            "model's static deflections cancel in the output view), so no ratio to it is defined; bound "
            "peak_deflection_m instead");
  EXPECT_FALSE(results[1].passed);
  EXPECT_EQ(results[1].message,
            "settling_time_s is n/a because the static displacement is 0 (the model's static deflections cancel in "
            "the output view), so the settling band (5% of it) is 0");
  EXPECT_EQ(results[2].message, "metric not defined for this run");
  EXPECT_TRUE(results[3].passed);
}

// Tests that passing and failing checks print in the documented line format.
TEST(Checks, LineFormat) {
  const auto results = EvaluateChecks(
      {{"peak_ratio", std::nullopt, 2.01}, {"peak_ratio", 0.5, 1.5}}, SomeCheckedMetrics());
  EXPECT_EQ(FormatCheckLine("scenarios/fig2.yaml", results[0]),
            "PASS scenarios/fig2.yaml peak_ratio = 1.9998 (max 2.01)");
  EXPECT_EQ(FormatCheckLine("scenarios/fig2.yaml", results[1]),
            "FAIL scenarios/fig2.yaml peak_ratio = 1.9998 (min 0.5, max 1.5): above max 1.5");
}

// Tests that a value just over its bound is printed with enough digits to tell them apart.
TEST(Checks, ValueNextToBoundShowsMoreDigits) {
  Metrics metrics;
  metrics.peak_ratio = 1.0100001;
  const auto results = EvaluateChecks({{"peak_ratio", std::nullopt, 1.01}}, metrics);
  EXPECT_FALSE(results[0].passed);
  EXPECT_NE(results[0].value_text, "1.01");
  EXPECT_EQ(std::stod(results[0].value_text), 1.0100001);
}

}  // namespace
}  // namespace shapebench::bench
