// Oracles: kinematics of piecewise-constant acceleration, the patent's para. 49-50 rules,
// and the vibration phasor of the grid command computed here from its accelerations.
#include "common/math_constants.h"
#include "controller/linear_acc_dec.h"

#include <cmath>
#include <complex>

#include <gtest/gtest.h>

#include "controller/grid_realization.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {


StepPattern Pattern(const std::string& method, PatternMode mode = PatternMode::kBoth) {
  PatternConfig config;
  config.method = method;
  config.mode = mode;
  config.frequency_hz = 25.0;
  return MakeStepPattern(config);
}

// Residual vibration (fraction of static) an undamped mode at `frequency_hz` keeps after
// the grid command: w |integral a(t) e^{iwt} dt| / max|a|, accelerations held per period.
double AccDecGridResidual(const CommandTrajectory& c, double frequency_hz) {
  const double w = 2 * kPi * frequency_hz;
  std::complex<double> sum = 0.0;
  for (std::size_t k = 1; k <= c.num_ticks(); ++k) {
    const std::complex<double> e1 = std::exp(std::complex<double>(0, w * c.tick_time_s(k)));
    const std::complex<double> e0 = std::exp(std::complex<double>(0, w * c.tick_time_s(k - 1)));
    sum += c.accel_m_s2(k) * (e1 - e0) / std::complex<double>(0, w);
  }
  return w * std::abs(sum) / c.MaxAbsAccel();
}

// Tests that an acc phase reaches the speed and runs the steps in para. 49's order: at the
// start SR1, SR2, steady; at the end steady, SR2, SR1.
TEST(LinearAccDecTest, AccelPhaseRunsStepsInPatentOrder) {
  const StepPattern p = Pattern("3");
  const double a = 1.6667;
  const IdealProfile phase = AccelPhase(0.5, a, p);
  ASSERT_EQ(phase.segments.size(), 5u);
  EXPECT_DOUBLE_EQ(phase.segments[0].accel_m_s2, p.step1.ratio * a);
  EXPECT_DOUBLE_EQ(phase.segments[1].accel_m_s2, p.step2.ratio * a);
  EXPECT_DOUBLE_EQ(phase.segments[2].accel_m_s2, a);
  EXPECT_DOUBLE_EQ(phase.segments[3].accel_m_s2, p.step2.ratio * a);
  EXPECT_DOUBLE_EQ(phase.segments[4].accel_m_s2, p.step1.ratio * a);
  double v = 0;
  for (const AccelSegment& s : phase.segments) v += s.duration_s * s.accel_m_s2;
  EXPECT_NEAR(v, 0.5, 1e-15);
}

// Tests para. 50: lowering the speed shortens the steady acceleration first, then step 2,
// then step 1 (method 3 at both ends: steps gain (K1 + 1 - K1) a t1 each).
TEST(LinearAccDecTest, ShorteningOrderIsSteadyThenStep2ThenStep1) {
  const StepPattern p = Pattern("3");
  const double a = 1.0;
  const double t1 = p.step1.duration_s;
  const double steps_speed = 2 * a * t1;  // (K1 + (1-K1)) a t1 per end
  // Just above the steps' speed: steady phase short, steps whole.
  IdealProfile phase = AccelPhase(steps_speed + 0.001, a, p);
  EXPECT_NEAR(phase.segments[2].duration_s, 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(phase.segments[1].duration_s, t1);
  // Below: no steady phase, step 2 shortened, step 1 whole.
  phase = AccelPhase(steps_speed * 0.9, a, p);
  ASSERT_EQ(phase.segments.size(), 4u);
  EXPECT_DOUBLE_EQ(phase.segments[0].duration_s, t1);
  EXPECT_LT(phase.segments[1].duration_s, t1);
  // Below step 1 alone: step 2 gone, step 1 shortened.
  phase = AccelPhase(2 * a * p.step1.ratio * t1 * 0.5, a, p);
  ASSERT_EQ(phase.segments.size(), 2u);
  EXPECT_NEAR(phase.segments[0].duration_s, 0.5 * t1, 1e-15);
  EXPECT_NEAR(LowestShapedSpeed(a, p), 2 * a * p.step1.ratio * t1, 1e-15);
}

// Tests that a rest-to-rest move covers its distance, with the cruise where the feed
// allows it and a lowered peak speed where it does not.
TEST(LinearAccDecTest, RestToRestCoversTheDistance) {
  for (double distance : {0.2, 0.05, 0.01}) {
    const IdealProfile profile = PlanRestToRest(distance, 0.5, 1.6667, Pattern("1"));
    EXPECT_NEAR(profile.Distance(), distance, 1e-13 * distance);
    EXPECT_EQ(profile.VelocityAt(profile.Duration() + 1.0), 0.0);
  }
}

struct GridCase {
  std::string method;
  PatternMode mode;
  double period_s;
  double distance_m;
};

class GridRealizationTest : public ::testing::TestWithParam<GridCase> {};

// Tests that the tick-grid command covers the distance to 1e-15 relative, starts and ends
// at rest, and keeps the pattern's zero of vibration even where steps fall between ticks
// (method 2 and 3 at 1 ms; the plain split of steps leaves ~1%).
TEST_P(GridRealizationTest, KeepsDistanceRestAndTheVibrationZero) {
  const GridCase c = GetParam();
  const CommandTrajectory command =
      SampleOnTicks(c.distance_m, 0.5, 0.5 / 0.3, Pattern(c.method, c.mode), c.period_s, 25.0);
  EXPECT_NEAR(command.Positions().back(), c.distance_m, 1e-15 * 10);
  EXPECT_EQ(command.velocity_m_s.front(), 0.0);
  EXPECT_EQ(command.velocity_m_s.back(), 0.0);
  // The grid correction of off-grid steps does not raise the largest acceleration where
  // the phase has a steady part to spare; in a move shortened by para. 50 the step groups
  // touch and one period may rise by about (w dt)^2 / 2 = 1%.
  const bool shortened = c.distance_m < 0.05;
  EXPECT_LE(command.MaxAbsAccel(), 0.5 / 0.3 * (shortened ? 1.02 : 1 + 1e-12));
  if (c.mode == PatternMode::kBoth) {
    EXPECT_LT(AccDecGridResidual(command, 25.0), 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Grid, GridRealizationTest,
    ::testing::Values(GridCase{"1", PatternMode::kBoth, 1e-3, 0.213},
                      GridCase{"2", PatternMode::kBoth, 1e-3, 0.213},
                      GridCase{"3", PatternMode::kBoth, 1e-3, 0.2},
                      GridCase{"4", PatternMode::kBoth, 1e-3, 0.123},
                      GridCase{"2", PatternMode::kBoth, 3e-4, 0.1},
                      GridCase{"3", PatternMode::kStart, 1e-3, 0.213},
                      GridCase{"none", PatternMode::kOff, 1e-3, 0.0071},
                      GridCase{"2", PatternMode::kBoth, 1e-3, 0.03}));

// Tests that a grid-aligned pattern (method 1 at 1 ms: steps at multiples of 20 ms) is
// carried exactly: the velocity at every tick equals the ideal profile's.
TEST(LinearAccDecTest, GridAlignedPatternIsCarriedExactly) {
  const StepPattern p = Pattern("1");
  const double a = 0.5 / 0.3;
  const CommandTrajectory command = SampleOnTicks(0.2, 0.5, a, p, 1e-3, 25.0);
  const IdealProfile ideal = PlanRestToRest(0.2, 0.5, a, p);
  for (std::size_t k = 0; k <= command.num_ticks(); ++k) {
    ASSERT_NEAR(command.velocity_m_s[k], ideal.VelocityAt(command.tick_time_s(k)), 1e-12) << k;
  }
}

// Tests that the grid realization adds nothing to steps already on ticks: a method-1 group
// (a/2 at t, a/2 at t + T/2, T = 40 ms) on the 1 ms grid comes back as exactly its two
// impulses, also late in a move where t carries rounding (1.07 s), while the least-squares
// correction of an off-grid group (method 2's T/6) still acts. (The correction of nothing
// but rounding used to spread ~1e-17 over every tick of the group.)
TEST(LinearAccDecTest, GridAlignedGroupsComeBackUnchanged) {
  const double a = 0.5 / 0.3;
  for (double t0 : {0.0, 0.3, 1.07, 12.345}) {
    const std::vector<Impulse> group = {{t0, 0.5 * a}, {t0 + 0.02, 0.5 * a}};
    const std::vector<GridImpulse> grid = RealizeOnGrid(group, 1e-3, 25.0, 0.0, a);
    ASSERT_EQ(grid.size(), 2u) << t0;
    EXPECT_EQ(grid[0].tick, std::lround(t0 / 1e-3)) << t0;
    EXPECT_EQ(grid[1].tick, std::lround(t0 / 1e-3) + 20) << t0;
    EXPECT_EQ(grid[0].amplitude, 0.5 * a) << t0;
    EXPECT_EQ(grid[1].amplitude, 0.5 * a) << t0;
  }
  const double t6 = 1.0 / 25.0 / 6.0;  // 6.67 ms: between ticks
  const std::vector<Impulse> off_grid = {{0.0, a}, {t6, -a}, {2 * t6, a}};
  EXPECT_GT(RealizeOnGrid(off_grid, 1e-3, 25.0, 0.0, a).size(), 5u);
}

}  // namespace
}  // namespace shapebench::controller
