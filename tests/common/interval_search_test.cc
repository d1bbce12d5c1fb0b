// The interval searches shared by band checks and sensitivity (common/interval_search.h),
// and the sensitivity band's treatment of humps (bench/sensitivity/sensitivity.h).
#include "common/interval_search.h"

#include <cmath>

#include <gtest/gtest.h>

#include "bench/sensitivity/sensitivity.h"

namespace shapebench {
namespace {

// Tests that the extremum search finds a smooth interior maximum to a fraction of the
// tolerance, and a minimum, on a function with several local extrema.
TEST(IntervalSearch, FindsInteriorMaximumAndMinimum) {
  const auto f = [](double x) { return std::sin(3.0 * x) + 0.3 * std::sin(11.0 * x); };
  double best_x = 0.0;
  double best = -1e9;
  double least_x = 0.0;
  double least = 1e9;
  for (int k = 0; k <= 400000; ++k) {
    const double x = 4.0 * k / 400000.0;
    if (f(x) > best) best = f(x), best_x = x;
    if (f(x) < least) least = f(x), least_x = x;
  }
  const ExtremumResult max = FindExtremum(f, 0.0, 4.0, Extreme::kMaximum);
  EXPECT_NEAR(max.worst.x, best_x, 4.0 * 1e-4);
  EXPECT_NEAR(max.worst.value, best, 1e-7);
  const ExtremumResult min = FindExtremum(f, 0.0, 4.0, Extreme::kMinimum);
  EXPECT_NEAR(min.worst.x, least_x, 4.0 * 1e-4);
  EXPECT_NEAR(min.worst.value, least, 1e-7);
  EXPECT_LT(max.evaluations, 64 + 3 * 20);
}

// Tests that of two humps whose scan samples rank them the wrong way round, the higher is
// found (each candidate is refined), and that a maximum at an end of the interval is kept.
TEST(IntervalSearch, NearTieAndEndMaximum) {
  // A broad hump of 0.999 at x = 1/3 and a narrow one of 1.0 at x = 2.5, halfway between
  // two scan points (spacing 3/63), where the scan sees only its foot.
  const auto f = [](double x) {
    return std::exp(-std::pow((x - 2.5) / 0.01, 2)) +
           0.999 * std::exp(-std::pow((x - 1.0 / 3.0) / 0.2, 2));
  };
  const ExtremumResult result = FindExtremum(f, 0.0, 3.0, Extreme::kMaximum);
  EXPECT_NEAR(result.worst.x, 2.5, 1e-3);
  EXPECT_GT(result.worst.value, 1.0 - 1e-4);  // within 1.5e-4 of the peak's x
  const ExtremumResult end = FindExtremum([](double x) { return x * x; }, -1.0, 2.0, Extreme::kMaximum);
  EXPECT_DOUBLE_EQ(end.worst.x, 2.0);
  EXPECT_DOUBLE_EQ(end.worst.value, 4.0);
}

// Tests that a NaN value ends the search at the point where it occurred.
TEST(IntervalSearch, NanIsReportedWhereItOccurs) {
  const auto f = [](double x) { return x > 0.5 ? std::nan("") : x; };
  const ExtremumResult result = FindExtremum(f, 0.0, 1.0, Extreme::kMaximum);
  EXPECT_TRUE(std::isnan(result.worst.value));
  EXPECT_GT(result.worst.x, 0.5);
}

// Tests that the sensitivity band ends at a hump that rises above the level between two
// of its 1e-3 steps (the crossing refined), and runs through one that only touches the
// level from below, as EI's design hump does.
TEST(IntervalSearch, SensitivityBandHumps) {
  const auto hump = [](double height) {
    return [height](double r) {
      return 0.04 + height * std::exp(-std::pow((r - 1.0205) / 0.0004, 2));
    };
  };
  const bench::Band poking = bench::BandAroundDesign(hump(0.02), 0.05, 0.5, 1.5);
  ASSERT_TRUE(poking.found);
  EXPECT_FALSE(poking.open_high);
  // 0.02 exp(-u^2) = 0.01 at u = sqrt(ln 2).
  EXPECT_NEAR(poking.high, 1.0205 - 0.0004 * std::sqrt(std::log(2.0)), 1e-7);
  const bench::Band touching = bench::BandAroundDesign(hump(0.01), 0.05, 0.5, 1.5);
  ASSERT_TRUE(touching.found);
  EXPECT_TRUE(touching.open_high);
  EXPECT_TRUE(touching.open_low);
}

// Tests that EI realized on a 1 ms grid, whose design hump overshoots its tolerance by
// about 1e-8 relative, keeps its band through the hump (the hump touches the level).
TEST(IntervalSearch, RealizedEiHumpTouchesTheLevel) {
  bench::SensitivitySpec spec;
  bench::SensitivityShaper shaper;
  shaper.pattern.method = "ei";
  shaper.pattern.frequency_hz = 33.0;
  shaper.pattern.vibration_tolerance = 0.1;
  shaper.label = "ei";
  spec.shapers = {shaper};
  spec.level = 0.1;
  spec.period_s = 0.001;
  const bench::SensitivityResult result = bench::ComputeSensitivity(spec);
  ASSERT_EQ(result.curves.size(), 2u);
  const bench::SensitivityCurve& exact = result.curves[0];
  const bench::SensitivityCurve& realized = result.curves[1];
  ASSERT_TRUE(realized.realized);
  EXPECT_GT(realized.band_level.high, 1.25);
  EXPECT_NEAR(realized.band_level.width(), exact.band_level.width(), 0.02);
}

}  // namespace
}  // namespace shapebench
