// residual_ratio and cruise_residual_ratio of one mode for every damping in [0, 1), through
// every sampler, against the closed-form free response of the damped mode from its state:
// the state at motion end (and at the cruise probe) is the sum of held-acceleration step
// responses of the move's piecewise-constant acceleration, written out here; the free
// response's envelope and largest |value| from that state in the phase form.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "common/math_constants.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

constexpr long double kPiL = 3.14159265358979323846264338327950288L;

// One mode q'' + 2 zeta w q' + w^2 q = -a(t), deflection q (gain 1), from rest.
struct DampedSdof {
  long double w = 0.0L, zeta = 0.0L, sigma = 0.0L, wd = 0.0L;
  DampedSdof(double frequency_hz, double damping_ratio)
      : w(2.0L * kPiL * frequency_hz),
        zeta(damping_ratio),
        sigma(zeta * w),
        wd(w * std::sqrt(1.0L - zeta * zeta)) {}
};

// The state (q, q') at time t of the mode under an acceleration that steps by `steps`
// (time, change) from 0: per step of da at t_k, q = -da / w^2 (1 - e^{-sigma tau} (cos w_d
// tau + sigma sin(w_d tau) / w_d)), q' = -da e^{-sigma tau} sin(w_d tau) / w_d, tau = t -
// t_k (the step response; sin(w_d tau) / w_d stays finite as w_d -> 0).
struct ModeState {
  long double q = 0.0L, v = 0.0L;
};
ModeState MoveStateAt(const DampedSdof& m, const std::vector<std::pair<double, double>>& steps, double t) {
  ModeState s;
  for (const auto& [at, da] : steps) {
    const long double tau = static_cast<long double>(t) - at;
    if (tau <= 0.0L) continue;
    const long double decay = std::exp(-m.sigma * tau);
    const long double sinc = std::sin(m.wd * tau) / m.wd;
    s.q += -da / (m.w * m.w) * (1.0L - decay * (std::cos(m.wd * tau) + m.sigma * sinc));
    s.v += -da * decay * sinc;
  }
  return s;
}

// The free response from (q0, q0'), y(t) = E e^{-sigma t} cos(w_d t + phi): its envelope E
// and largest |y(t)|, t >= 0. Stationary points where w_d t + phi = -asin(zeta) + k pi, |y|
// = E sqrt(1 - zeta^2) e^{-sigma t} there, decreasing with k: the peak is |q0| or the first.
struct FreeFigures {
  long double envelope = 0.0L;
  long double peak = 0.0L;
};
FreeFigures FreeFrom(const DampedSdof& m, const ModeState& s) {
  const long double b = (s.v + m.sigma * s.q) / m.wd;
  FreeFigures f;
  f.envelope = std::sqrt(s.q * s.q + b * b);
  long double angle = std::fmod(-std::asin(m.zeta) - std::atan2(-b, s.q), kPiL);
  if (angle < 0.0L) angle += kPiL;
  f.peak = std::max(std::abs(s.q), f.envelope * std::sqrt(1.0L - m.zeta * m.zeta) * std::exp(-m.sigma * angle / m.wd));
  return f;
}

// The stated cap (docs/metrics.md): e^{pi z / sqrt(1 - z^2)}, z = min(zeta, 1 - zeta).
double CapFor(double zeta) {
  const double z = std::min(zeta, 1.0 - zeta);
  return std::exp(kPi * z / std::sqrt(1.0 - z * z));
}

// The SDOF move (25 Hz, 213 mm at 30 m/min, 0.3 s linear acc/dec, 1 ms: every phase on a
// tick), unshaped or with method 1 at 25 Hz (para. 38: impulses 1/2 at 0 and 1/2 at 20 ms,
// on both acceleration and deceleration): its acceleration steps, written out.
std::vector<std::pair<double, double>> MoveSteps(bool shaped) {
  const double a = 0.5 / 0.3;
  const std::vector<std::pair<double, double>> unshaped = {{0.0, a}, {0.3, -a}, {0.426, -a}, {0.726, a}};
  if (!shaped) return unshaped;
  std::vector<std::pair<double, double>> steps;
  for (const auto& [t, da] : unshaped) {
    steps.push_back({t, 0.5 * da});
    steps.push_back({t + 0.02, 0.5 * da});
  }
  return steps;
}

struct SamplerCase {
  SamplerKind fastest;
  model::IntegratorMethod method;
  double tolerance;  // of the state, relative to the static deflection (CVODE: rtol 1e-10)
};

// Tests that, for one mode of damping ratio zeta in [0, 1) (0 to 0.9999999, where the
// envelope of the unshaped move's residual is 2236 x its largest |value|), every sampler
// (the closed form, the general exact path, CVODE) reports as residual_amplitude_m the
// free response's envelope E while zeta <= 0.5 and never more than CapFor(zeta) x its
// largest |value| P (nor less than P), the oracle's E and P from the state at motion end;
// the same for cruise_residual_ratio from the state at the cruise probe (one 40 ms period
// into the cruise); unshaped and with method 1. 1e-9 of static (CVODE 1e-6).
TEST(DampedResidual, BoundedByTheFreeResponseForEveryDamping) {
  const std::vector<SamplerCase> samplers = {{SamplerKind::kClosedForm, model::IntegratorMethod::kExact, 1e-9},
                                             {SamplerKind::kGeneral, model::IntegratorMethod::kExact, 1e-9},
                                             {SamplerKind::kGeneral, model::IntegratorMethod::kCvode, 1e-6}};
  for (const bool shaped : {false, true}) {
    for (const double zeta : {0.0, 0.03, 0.1, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 0.97, 0.99, 0.999, 0.99999, 0.9999999}) {
      const DampedSdof mode(25.0, zeta);
      const std::vector<std::pair<double, double>> steps = MoveSteps(shaped);
      const double motion_end = shaped ? 0.746 : 0.726, probe = (shaped ? 0.32 : 0.3) + 0.04;
      const FreeFigures end = FreeFrom(mode, MoveStateAt(mode, steps, motion_end));
      const FreeFigures cruise = FreeFrom(mode, MoveStateAt(mode, steps, probe));
      const double static_m = static_cast<double>((0.5L / 0.3L) / (mode.w * mode.w));
      for (const SamplerCase& c : samplers) {
        Scenario s = testing::SdofScenario(25.0, zeta, c.method);
        s.controller.pattern.method = shaped ? "1" : "none";
        s.controller.pattern.mode = controller::PatternMode::kBoth;
        RunOptions options;
        options.record_trace = false;
        options.fastest_sampler = c.fastest;
        const RunResult run = RunScenario(s, options);
        const Metrics& m = run.metrics;
        SCOPED_TRACE(std::string(shaped ? "method 1" : "unshaped") + ", zeta " + std::to_string(zeta) + ", " +
                     std::string(SamplerName(run.sampler)) + (c.tolerance > 1e-9 ? " (CVODE)" : ""));
        ASSERT_NEAR(m.motion_time_s, motion_end, 1e-12);
        ASSERT_NEAR(m.static_displacement_m, static_m, 1e-12 * static_m);
        const double tol = c.tolerance * static_m;
        const struct {
          const char* name;
          double value;
          FreeFigures oracle;
        } residuals[] = {{"residual_amplitude_m", m.residual_amplitude_m, end},
                         {"cruise_residual_ratio x static", m.cruise_residual_ratio * m.static_displacement_m, cruise}};
        for (const auto& r : residuals) {
          const double e = static_cast<double>(r.oracle.envelope), p = static_cast<double>(r.oracle.peak);
          ASSERT_TRUE(std::isfinite(r.value)) << r.name;
          EXPECT_GE(r.value, p - tol) << r.name;
          EXPECT_LE(r.value, CapFor(zeta) * p * (1.0 + 2e-9) + tol) << r.name;
          if (zeta <= 0.5) {
            EXPECT_NEAR(r.value, e, tol + 1e-9 * e) << r.name;
          }
          if (zeta == 0.9999999) {
            EXPECT_LE(r.value, p * (1.0 + 1e-6) + tol) << r.name << ": envelope " << e;
          }
        }
        ASSERT_EQ(run.residual_modes.size(), 1u);
        EXPECT_EQ(run.residual_modes[0].amplitude, m.residual_amplitude_m);
      }
    }
  }
}

}  // namespace
}  // namespace shapebench::bench
