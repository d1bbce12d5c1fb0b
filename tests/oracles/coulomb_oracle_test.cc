// Coulomb friction with stiction against its closed form (docs/nonlinear.md): a mass on a
// spring to the driven point, Coulomb friction from the mass to the ground, no viscous
// damping, static = Coulomb, left ringing after a move with the drive at rest.
//
// The closed form: between turning points the mass slides one way under a constant
// friction force F_c, a harmonic half-cycle of the undamped frequency about the shifted
// centre -+F_c/k; each half-cycle's turning point is 2 F_c/k closer to 0 than the last (4 F_c/k
// per period), every half-cycle lasts exactly pi/w, and the mass sticks at the first turning
// point where the spring force k |y| is at most the static force F_s = F_c, i.e. |y| <= F_c/k.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario.h"
#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

constexpr double kMassKg = 100.0;
constexpr double kFrequencyHz = 10.0;
constexpr double kCoulombN = 5.0;

double Stiffness() { return kMassKg * std::pow(2.0 * kPi * kFrequencyHz, 2); }

// One body on a spring to the driven point, Coulomb friction to the ground; a 52.5 mm move
// unshaped (its acc/dec half the natural period: a large residual, about 113 F_c/k).
Scenario CoulombScenario(double coulomb_n) {
  Scenario s;
  model::LumpedMachineConfig lumped;
  lumped.bodies = {{"mass", kMassKg}};
  model::LumpedElement spring{"spring", "mass", "driven", Stiffness(), 0.0};
  model::LumpedElement guide{"guide", "mass", "ground"};
  guide.friction.model = model::FrictionModel::kCoulomb;
  guide.friction.coulomb_n = coulomb_n;
  lumped.elements = {spring, guide};
  lumped.output_body = "mass";
  s.machine.axes[s.machine.driven_axis] = model::MachineConfig{lumped};
  s.controller.period_s = 0.001;
  s.controller.feed_mm_min = 6000;
  s.controller.accel_time_s = 0.05;
  s.controller.pattern.method = "none";
  s.move.distance_mm = 52.5;
  s.integrator.method = model::IntegratorMethod::kAuto;
  s.integrator.output_substeps = 20;  // 2000 samples a period: a peak's sampling error 1e-6 of it
  return s;
}

struct Extremum {
  double t_s;
  double y_m;
};

// The turning points of the deflection after the command has come to rest.
std::vector<Extremum> FreeExtrema(const Trace& trace) {
  std::size_t start = 0;
  for (std::size_t i = 0; i < trace.time_s.size(); ++i) {
    if (trace.command_velocity_m_s[i] != 0.0 || trace.command_accel_m_s2[i] != 0.0) start = i + 1;
  }
  std::vector<Extremum> extrema;
  const std::vector<double>& y = trace.deflection_m;
  for (std::size_t i = start + 1; i + 1 < y.size(); ++i) {
    if ((y[i] > y[i - 1] && y[i] >= y[i + 1]) || (y[i] < y[i - 1] && y[i] <= y[i + 1])) {
      extrema.push_back({trace.time_s[i], y[i]});
    }
  }
  return extrema;
}

// Tests that the free vibration's peaks fall by exactly 4 F_c/k per period (2 F_c/k per
// half-period) within 1% of 4 F_c/k, that each half-cycle lasts pi/w, and that the mass
// sticks at the turning point the closed form predicts, at the deflection it predicts
// (within 1% of F_c/k) and within +-F_c/k; dead_band_m reports that rest.
TEST(CoulombOracle, PeaksFallByFourFcOverKPerPeriodAndStickWithinFcOverK) {
  const RunResult run = RunScenario(CoulombScenario(kCoulombN));
  const double unit = kCoulombN / Stiffness();  // F_c / k, 12.7 um
  const std::vector<Extremum> extrema = FreeExtrema(run.trace);
  ASSERT_GE(extrema.size(), 20u) << "too few free turning points to test";
  // The closed form from the first free turning point on.
  const double a0 = std::abs(extrema.front().y_m);
  ASSERT_GT(a0, 20.0 * unit);
  int n_stick = 0;
  while (a0 - 2.0 * n_stick * unit > unit) ++n_stick;
  const double sign0 = extrema.front().y_m > 0.0 ? 1.0 : -1.0;
  const double rest = (n_stick % 2 == 0 ? sign0 : -sign0) * (a0 - 2.0 * n_stick * unit);
  // The turning points up to the stick, one per half-period.
  ASSERT_GT(static_cast<int>(extrema.size()), n_stick);
  const double half_period = 0.5 / kFrequencyHz;
  for (int i = 0; i + 2 <= n_stick; ++i) {
    const double fall = std::abs(extrema[i].y_m) - std::abs(extrema[i + 2].y_m);
    EXPECT_NEAR(fall, 4.0 * unit, 0.01 * 4.0 * unit) << "period from turning point " << i;
    EXPECT_NEAR(extrema[i + 1].t_s - extrema[i].t_s, half_period, 2e-4 * half_period) << i;
  }
  // Stuck at turning point n_stick: after it the deflection stays where it stopped.
  const double stick_s = extrema[n_stick].t_s;
  EXPECT_NEAR(stick_s - extrema.front().t_s, n_stick * half_period, 1e-3);
  EXPECT_NEAR(extrema[n_stick].y_m, rest, 0.01 * unit);
  const double final_m = run.trace.deflection_m.back();
  EXPECT_LE(std::abs(final_m), unit);
  EXPECT_NEAR(final_m, rest, 0.01 * unit);
  for (std::size_t i = 0; i < run.trace.time_s.size(); ++i) {
    if (run.trace.time_s[i] > stick_s + 1e-3) {
      EXPECT_NEAR(run.trace.deflection_m[i], final_m, 1e-6 * unit) << i;
    }
  }
  // The turning point before the stick was beyond F_c/k (so it slid on).
  EXPECT_GT(std::abs(extrema[n_stick - 1].y_m), unit);
  EXPECT_DOUBLE_EQ(run.metrics.dead_band_m, std::abs(final_m));
  EXPECT_GT(run.stats.events, n_stick);  // one event per reversal and the stick
}

}  // namespace
}  // namespace shapebench::bench
