// RealizeOnGrid against its contract (controller/grid_realization.h): the acceleration and
// the velocity after the group exact, the group's (damped) phasor at every design frequency
// the ideal one, and the largest acceleration not raised where the span has room.
#include "common/math_constants.h"
#include "controller/grid_realization.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <gtest/gtest.h>

namespace shapebench::controller {
namespace {

constexpr double kPeriodS = 1e-3;

// sum A e^{(zeta w + i w_d) (t - origin)}: the residual of a mode of that damping after
// the group, up to a common decay.
std::complex<double> Phasor(const std::vector<Impulse>& impulses, double frequency_hz,
                            double zeta, double origin_s) {
  const double w = kTwoPi * frequency_hz;
  std::complex<double> sum = 0.0;
  for (const Impulse& impulse : impulses) {
    const double dt = impulse.time_s - origin_s;
    sum += impulse.amplitude * std::exp(zeta * w * dt) *
           std::polar(1.0, w * std::sqrt(1.0 - zeta * zeta) * dt);
  }
  return sum;
}

std::vector<Impulse> OnTheGrid(const std::vector<GridImpulse>& grid) {
  std::vector<Impulse> impulses;
  for (const GridImpulse& g : grid) impulses.push_back({static_cast<double>(g.tick) * kPeriodS, g.amplitude});
  return impulses;
}

double Sum(const std::vector<Impulse>& impulses) {
  double sum = 0.0;
  for (const Impulse& impulse : impulses) sum += impulse.amplitude;
  return sum;
}

double FirstMoment(const std::vector<Impulse>& impulses) {
  double sum = 0.0;
  for (const Impulse& impulse : impulses) sum += impulse.amplitude * impulse.time_s;
  return sum;
}

// Tests that an off-grid group designed for two damped modes keeps, on the grid, the
// acceleration and velocity after it and its damped phasor at both design frequencies
// (the plain split misses them by far more than the tolerance).
TEST(RealizeOnGridTest, DampedTwoFrequencyDesignKeepsItsPhasors) {
  const double a = 2.0;
  const std::vector<Impulse> group = {
      {0.1003, 0.5 * a}, {0.10697, 0.25 * a}, {0.11361, 0.25 * a}, {0.1214, -0.3 * a}};
  const GridDesign design({25.0, 41.0}, 0.05);
  const std::vector<GridImpulse> grid = RealizeOnGrid(group, kPeriodS, design, 0.0, 10 * a);
  const std::vector<Impulse> realized = OnTheGrid(grid);
  EXPECT_NEAR(Sum(realized), Sum(group), 1e-14);
  EXPECT_NEAR(FirstMoment(realized), FirstMoment(group), 1e-15);
  // Without a design the group is only split: its phasors are off by far more.
  const std::vector<Impulse> split = OnTheGrid(RealizeOnGrid(group, kPeriodS, {}, 0.0, 10 * a));
  const double origin_s = 0.1;
  for (const double f : design.frequencies_hz) {
    const std::complex<double> ideal = Phasor(group, f, design.damping_ratio, origin_s);
    EXPECT_LT(std::abs(Phasor(realized, f, design.damping_ratio, origin_s) - ideal), 1e-10) << f;
    EXPECT_GT(std::abs(Phasor(split, f, design.damping_ratio, origin_s) - ideal), 1e-4) << f;
  }
}

// Tests that the correction spares the periods at the acceleration limit when the others
// suffice: method 2's steps (a, -a, a at T/6 spacing, 6.67 ms on a 1 ms grid) after an
// acceleration of 0 never exceed the limit a on the grid.
TEST(RealizeOnGridTest, CorrectionDoesNotRaiseThePeak) {
  const double a = 0.5 / 0.3;
  const double t6 = 1.0 / 25.0 / 6.0;
  const std::vector<Impulse> group = {{0.0, a}, {t6, -a}, {2 * t6, a}};
  const std::vector<GridImpulse> grid = RealizeOnGrid(group, kPeriodS, 25.0, 0.0, a);
  ASSERT_GT(grid.size(), 3u);
  double level = 0.0, peak = 0.0;
  for (const GridImpulse& g : grid) {
    level += g.amplitude;
    peak = std::max(peak, std::abs(level));
  }
  EXPECT_LE(peak, a * (1 + 1e-12));
  EXPECT_NEAR(level, a, 1e-14);
  EXPECT_LT(std::abs(Phasor(OnTheGrid(grid), 25.0, 0.0, 0.0) - Phasor(group, 25.0, 0.0, 0.0)),
            1e-10);
}

// Tests that a group spanning fewer periods than the correction has rows (1 + 2 per design
// frequency) is only split: each impulse between its two ticks by its distance from them.
TEST(RealizeOnGridTest, ShortGroupIsOnlySplit) {
  const std::vector<Impulse> group = {{0.0104, 1.0}, {0.0116, -0.5}};
  const std::vector<GridImpulse> grid = RealizeOnGrid(group, kPeriodS, 25.0, 0.0, 1.0);
  ASSERT_EQ(grid.size(), 3u);
  EXPECT_EQ(grid[0].tick, 10);
  EXPECT_EQ(grid[1].tick, 11);
  EXPECT_EQ(grid[2].tick, 12);
  EXPECT_NEAR(grid[0].amplitude, 0.6, 1e-12);
  EXPECT_NEAR(grid[1].amplitude, 0.4 - 0.5 * 0.4, 1e-12);
  EXPECT_NEAR(grid[2].amplitude, -0.5 * 0.6, 1e-12);
}

}  // namespace
}  // namespace shapebench::controller
