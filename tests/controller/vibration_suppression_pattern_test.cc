// Oracles: the patent's own closed forms (paras. 38-45) and the phase-plane condition
// that a pattern leaves no vibration: sum_j dA_j exp(i w t_j) = 0 at the design w.
#include "common/math_constants.h"
#include "controller/vibration_suppression_pattern.h"

#include <cmath>
#include <complex>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

constexpr double kT = 0.040;  // 25 Hz

PatternConfig Config(const std::string& method) {
  PatternConfig config;
  config.method = method;
  config.frequency_hz = 25.0;
  return config;
}

// |sum dA_j e^{i w t_j}| of the acceleration steps SR1 -> SR2 -> 1, computed here from the
// step times and ratios (independent of PatternImpulses/ResidualVibration).
double PhasePlaneResidual(const StepPattern& p) {
  const double w = 2 * kPi / kT;
  const std::complex<double> i(0, 1);
  const double t1 = p.step1.duration_s;
  const double t2 = t1 + p.step2.duration_s;
  return std::abs(p.step1.ratio + (p.step2.ratio - p.step1.ratio) * std::exp(i * w * t1) +
                  (1.0 - p.step2.ratio) * std::exp(i * w * t2));
}

// Tests that method 1 is a/2 for T/2 (para. 38) and method 2 is a, 0 for T/6 each (para. 40).
TEST(VibrationSuppressionPatternTest, Methods1And2MatchThePatent) {
  const StepPattern m1 = MakeStepPattern(Config("1"));
  EXPECT_DOUBLE_EQ(m1.step1.duration_s, kT / 2);
  EXPECT_DOUBLE_EQ(m1.step1.ratio, 0.5);
  EXPECT_DOUBLE_EQ(m1.step2.duration_s, 0.0);
  const StepPattern m2 = MakeStepPattern(Config("2"));
  EXPECT_DOUBLE_EQ(m2.step1.duration_s, kT / 6);
  EXPECT_DOUBLE_EQ(m2.step1.ratio, 1.0);
  EXPECT_DOUBLE_EQ(m2.step2.duration_s, kT / 6);
  EXPECT_DOUBLE_EQ(m2.step2.ratio, 0.0);
}

// Tests that method 3 with K1 = 0.675 gives t1 = 5T/24 as the patent states (para. 43; the
// patent rounds, so 0.1% of T), and that K1 = 0.5 and 1 are methods 1 and 2 (para. 44):
// K1 = 0.5 gives two steps of a/2 for T/4 each (a/2 for T/2), K1 = 1 gives a, 0 for T/6.
TEST(VibrationSuppressionPatternTest, Method3StepTimeFollowsTheCosineLaw) {
  EXPECT_NEAR(Method3StepTime(0.675, kT), 5.0 * kT / 24.0, 1e-3 * kT);
  EXPECT_NEAR(Method3StepTime(0.5, kT), kT / 4, 1e-12);
  EXPECT_NEAR(Method3StepTime(1.0, kT), kT / 6, 1e-12);
}

// Tests that method 4's a2 is a/2 at t1 = 0 (method 1) and 0 at t1 = T/6 (method 2).
TEST(VibrationSuppressionPatternTest, Method4EndsAreMethods1And2) {
  EXPECT_NEAR(Method4SecondRatio(0.0, kT), 0.5, 1e-12);
  EXPECT_NEAR(Method4SecondRatio(kT / 6, kT), 0.0, 1e-12);
}

struct PatternCase {
  std::string method;
  double k1;
  double t1_s;
};

class PatternZeroTest : public ::testing::TestWithParam<PatternCase> {};

// Tests that every method leaves no vibration at the design frequency (phase plane) and
// that the residual formula used by `shapebench pattern` agrees.
TEST_P(PatternZeroTest, LeavesNoVibrationAtTheDesignFrequency) {
  PatternConfig config = Config(GetParam().method);
  config.k1 = GetParam().k1;
  config.t1_s = GetParam().t1_s;
  const StepPattern pattern = MakeStepPattern(config);
  EXPECT_LT(PhasePlaneResidual(pattern), 1e-12);
  EXPECT_LT(ResidualVibration(PatternImpulses(pattern), 25.0), 1e-12);
  // Off design (20% low) the vibration is not cancelled: the check can fail.
  EXPECT_GT(ResidualVibration(PatternImpulses(pattern), 20.0), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Methods, PatternZeroTest,
    ::testing::Values(PatternCase{"1", 0, 0}, PatternCase{"2", 0, 0},
                      PatternCase{"3", 0.55, 0}, PatternCase{"3", 0.675, 0},
                      PatternCase{"3", 0.8, 0}, PatternCase{"3", 0.95, 0},
                      PatternCase{"4", 0, 0.001}, PatternCase{"4", 0, 0.003},
                      PatternCase{"4", 0, 0.005}, PatternCase{"4", 0, kT / 6}));

// Tests that rounding step times to the patent's 0.1 ms units leaves the ~1% residual the
// README warns about for method 2 (6.667 ms -> 6.7 ms), closed form |1 - e^{iwt} + e^{2iwt}|.
TEST(VibrationSuppressionPatternTest, PatentResolutionRoundsMethod2) {
  PatternConfig config = Config("2");
  config.step_resolution_s = 1e-4;
  const StepPattern pattern = MakeStepPattern(config);
  EXPECT_DOUBLE_EQ(pattern.step1.duration_s, 0.0067);
  const double wt = 2 * kPi * 25.0 * 0.0067;
  const std::complex<double> z = std::exp(std::complex<double>(0, wt));
  EXPECT_NEAR(ResidualVibration(PatternImpulses(pattern), 25.0), std::abs(1.0 - z + z * z), 1e-12);
  EXPECT_GT(ResidualVibration(PatternImpulses(pattern), 25.0), 0.005);
}

// Tests that a damped residual formula is 1 for a single impulse and decays as expected
// for two impulses (closed form of a ZV pair at zeta = 0.1 is zero by construction).
TEST(VibrationSuppressionPatternTest, DampedResidualOfAZvPairIsZero) {
  const double zeta = 0.1;
  const double k = std::exp(-zeta * kPi / std::sqrt(1 - zeta * zeta));
  const double td = 0.5 / (25.0 * std::sqrt(1 - zeta * zeta));
  EXPECT_NEAR(ResidualVibration({{0.0, 1.0 / (1 + k)}, {td, k / (1 + k)}}, 25.0, zeta), 0.0, 1e-12);
  EXPECT_NEAR(ResidualVibration({{0.0, 1.0}}, 25.0, zeta), 1.0, 1e-15);
}

// Tests that out-of-range parameters are rejected naming the field.
TEST(VibrationSuppressionPatternTest, ValidateNamesTheField) {
  PatternConfig config = Config("3");
  config.k1 = 0.4;
  try {
    config.validate();
    FAIL() << "k1 = 0.4 accepted";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "k1");
  }
  config = Config("4");
  config.t1_s = kT / 6 * 1.01;
  try {
    config.validate();
    FAIL() << "t1 > T/6 accepted";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "t1_s");
  }
  config = Config("1");
  config.frequency_hz = 0.0;
  EXPECT_THROW(config.validate(), ValidationError);
}

}  // namespace
}  // namespace shapebench::controller
