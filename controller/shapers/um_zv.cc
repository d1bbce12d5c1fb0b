// um_zv, the unity-magnitude ZV, negative: [1, -1, 1]. zeta = 0: at [0, T/6, T/3], the
// same impulses as the patent's method 2 (a for T/6, 0 for T/6, then a). zeta > 0: the
// times solve 1 - e^{s t2} + e^{s t3} = 0 with s = zeta omega + i omega_d exactly (Newton
// from the undamped times, to 1e-14), which is the damped UM-ZV of Singhose, Seering &
// Singer ("Time-optimal negative input shapers", ASME J. Dyn. Sys. Meas. Control 119,
// 1997, who give a curve fit of these times). The continuation finds solutions up to
// zeta of about 0.6; beyond, an error.
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <utility>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

// The damped UM-ZV times (t2, t3) for a mode of `frequency_hz` and `damping_ratio`;
// throws ValidationError("design_damping_ratio") when Newton finds no solution.
std::pair<double, double> UnityMagnitudeZvTimes(double frequency_hz, double damping_ratio) {
  const double root = std::sqrt(1.0 - damping_ratio * damping_ratio);
  const double wd = 2.0 * kPi * frequency_hz * root;
  // In theta = w_d t: 1 - e^{c theta2} + e^{c theta3} = 0, c = beta + i, beta = zeta / root.
  // Continuation in beta from the undamped solution (pi/3, 2pi/3), Newton at each step.
  const double beta_target = damping_ratio / root;
  double theta2 = kPi / 3.0;
  double theta3 = 2.0 * kPi / 3.0;
  const int stages = std::max(1, static_cast<int>(std::ceil(beta_target / 0.02)));
  for (int stage = 1; stage <= stages; ++stage) {
    const std::complex<double> c(beta_target * stage / stages, 1.0);
    bool converged = false;
    for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
      const std::complex<double> e2 = std::exp(c * theta2);
      const std::complex<double> e3 = std::exp(c * theta3);
      const std::complex<double> f = 1.0 - e2 + e3;
      const std::complex<double> d2 = -c * e2;  // dF / dtheta2
      const std::complex<double> d3 = c * e3;   // dF / dtheta3
      const double det = d2.real() * d3.imag() - d3.real() * d2.imag();
      if (!(std::abs(det) > 0.0)) break;
      const double step2 = (-f.real() * d3.imag() + d3.real() * f.imag()) / det;
      const double step3 = (-d2.real() * f.imag() + f.real() * d2.imag()) / det;
      theta2 += step2;
      theta3 += step3;
      converged = std::abs(step2) + std::abs(step3) < 1e-15 * (1.0 + theta3) ||
                  std::abs(1.0 - std::exp(c * theta2) + std::exp(c * theta3)) < 1e-15;
    }
    if (!converged || !(theta2 > 0.0 && theta3 > theta2 && theta3 < 2.0 * kPi)) {
      throw ValidationError("design_damping_ratio",
                            "no unity-magnitude ZV shaper found for damping ratio " +
                                FormatNumber(damping_ratio) + " (um_zv's damped times do not converge); "
                                "allowed: a smaller design_damping_ratio");
    }
  }
  return {theta2 / wd, theta3 / wd};
}

std::vector<Impulse> UmZv(double frequency_hz, double z) {
  const double root = std::sqrt(1.0 - z * z);
  const double td = 1.0 / (frequency_hz * root);  // damped period T_d
  if (z == 0.0) return {{0.0, 1.0}, {td / 6.0, -1.0}, {td / 3.0, 1.0}};
  const auto [t2, t3] = UnityMagnitudeZvTimes(frequency_hz, z);
  return {{0.0, 1.0}, {t2, -1.0}, {t3, 1.0}};
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_um_zv() {
  ShaperEntry um_zv;
  um_zv.key = "um_zv";
  um_zv.name = "UM-ZV";
  um_zv.description = "unity-magnitude zv, negative: 1, -1, 1 over T/3";
  um_zv.kind = ShaperKind::kImpulse;
  um_zv.rank = 150;
  um_zv.design = [](const PatternConfig& config, double frequency_hz) {
    return UmZv(frequency_hz, config.design_damping_ratio);
  };
  // A damping the continuation cannot reach is a config error, found before the run.
  um_zv.validate = [](const PatternConfig& config) {
    const double z = config.design_damping_ratio;
    if (z > 0.0) {
      for (const double f : config.DesignFrequencies()) UnityMagnitudeZvTimes(f, z);
    }
  };
  return {um_zv};
}

}  // namespace shapebench::controller
