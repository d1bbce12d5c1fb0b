// The oracles for the whole pipeline (program -> planner -> interpolation ->
// post-interpolation acc/dec -> drive -> machine): Fanuc's radial-error formulas on the
// circle test, seed 000's tangential distribution, and the patent's pocket-corner story.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bench/run/run_scenario.h"
#include "bench/config/override.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

constexpr double kRadiusM = 0.010;
constexpr double kT1 = 1.0 / 30.0;  // post-interpolation time constant
constexpr double kKp = 30.0;        // position gain; T2 = 1 / Kp

Metrics RunWith(const std::string& file, std::vector<std::string> sets) {
  const std::vector<Override> overrides = ParseOverrides(sets);
  return RunScenario(LoadScenario(kSourceDir + "/configs/scenarios/" + file, overrides)).metrics;
}

std::vector<std::string> CircleAt(double feed_mm_min, std::vector<std::string> more) {
  more.push_back("program[1].f=" + std::to_string(feed_mm_min));
  return more;
}

class CircleTest : public ::testing::TestWithParam<double> {
 protected:
  double feed_mm_min() const { return GetParam(); }
  double v() const { return GetParam() / 60000.0; }
};

// Tests Fanuc's formula for per-axis exponential acc/dec with the kinematic drive:
// radial error T1^2 v^2 / (2 r) within 5%. (The exact steady state of a first-order lag,
// r (1 - 1/sqrt(1 + (w T1)^2)), is below it by 3/4 (w T1)^2 relative: 2% at 3000 mm/min.)
TEST_P(CircleTest, ExponentialPerAxisPullsInByFanucsFormula) {
  const Metrics m = RunWith("circle_test.yaml", CircleAt(feed_mm_min(), {}));
  const double formula = kT1 * kT1 * v() * v() / (2 * kRadiusM);
  EXPECT_NEAR(m.radial_error_m, formula, 0.05 * formula);
}

// Tests the servo term: with ideal inner loops and no feedforward the position loop is
// a second first-order lag, and the radial error is (T1^2 + T2^2) v^2 / (2 r) within 5%.
TEST_P(CircleTest, ServoAddsItsLagTerm) {
  const Metrics m = RunWith("circle_test.yaml",
                            CircleAt(feed_mm_min(), {"drive.type=servo", "drive.position_gain=30",
                                                     "drive.velocity_feedforward=0",
                                                     "drive.velocity_loop_hz=0"}));
  const double t2 = 1.0 / kKp;
  const double formula = (kT1 * kT1 + t2 * t2) * v() * v() / (2 * kRadiusM);
  EXPECT_NEAR(m.radial_error_m, formula, 0.05 * formula);
}

// Tests linear acc/dec after interpolation (a moving-average profile table of length
// T1 = 32 ms): radial error T1^2 v^2 / (24 r) within 5%.
TEST_P(CircleTest, MovingAverageTableGivesTheLinearFormula) {
  const Metrics m = RunWith(
      "circle_test.yaml",
      CircleAt(feed_mm_min(), {"controller.post_interp={type: profile_table, moving_average_s: 0.032}"}));
  const double t1 = 0.032;
  const double formula = t1 * t1 * v() * v() / (24 * kRadiusM);
  EXPECT_NEAR(m.radial_error_m, formula, 0.05 * formula);
}

// Tests seed 000: distributing the filtered tangential displacement keeps the tool on the
// interpolated path, removing the post-interpolation term: at most 2% of the per-axis
// radial error with the same filter (what is left is the chords' sag, r theta^2 / 8).
TEST_P(CircleTest, TangentialDistributionRemovesThePostInterpolationTerm) {
  const Metrics per_axis = RunWith("circle_test.yaml", CircleAt(feed_mm_min(), {}));
  const Metrics tangential = RunWith(
      "circle_test.yaml", CircleAt(feed_mm_min(), {"controller.post_interp.distribution=tangential"}));
  EXPECT_LE(std::abs(tangential.radial_error_m), 0.02 * per_axis.radial_error_m);
  EXPECT_LE(tangential.max_contour_error_m, 0.02 * per_axis.max_contour_error_m);
}

INSTANTIATE_TEST_SUITE_P(Feeds, CircleTest, ::testing::Values(1000.0, 2000.0, 3000.0),
                         [](const auto& info) {
                           return "F" + std::to_string(static_cast<int>(info.param));
                         });

struct StoryCase {
  std::string name;
  std::vector<std::string> sets;
  double min_peak_ratio;
  double max_peak_ratio;
};

// Names the case in test output instead of dumping its bytes.
void PrintTo(const StoryCase& c, std::ostream* out) { *out << c.name; }

class PocketCornerTest : public ::testing::TestWithParam<StoryCase> {};

// Tests the patent's story on the moving-column machine: a pocket corner at 30 m/min and
// 0.17 G swings the tool tip to about twice the static deflection unshaped, and methods 1
// and 3 keep it within 5% of static in both realizations (the 4% left is the machine's
// damping and its higher modes, which the 25 Hz design does not address); the servo with
// full velocity feedforward stays within 10%.
TEST_P(PocketCornerTest, PeakRatio) {
  const StoryCase& c = GetParam();
  const Metrics m = RunWith("pocket_corner.yaml", c.sets);
  EXPECT_GE(m.peak_ratio, c.min_peak_ratio);
  EXPECT_LE(m.peak_ratio, c.max_peak_ratio);
}

INSTANTIATE_TEST_SUITE_P(
    Story, PocketCornerTest,
    ::testing::Values(
        StoryCase{"Unshaped", {"controller.pattern.method=none"}, 1.9, 2.15},
        StoryCase{"Method1Stepped", {"controller.pattern.method=1"}, 0.95, 1.05},
        StoryCase{"Method1Table",
                  {"controller.pattern.method=1", "controller.pattern.realization=profile_table"}, 0.95, 1.05},
        StoryCase{"Method3Stepped", {"controller.pattern.method=3"}, 0.95, 1.05},
        StoryCase{"Method3Table",
                  {"controller.pattern.method=3", "controller.pattern.realization=profile_table"}, 0.95, 1.05},
        StoryCase{"ServoFullFeedforward",
                  {"controller.pattern.method=1", "drive.type=servo", "drive.velocity_feedforward=1"}, 0.95, 1.10}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace shapebench::bench
