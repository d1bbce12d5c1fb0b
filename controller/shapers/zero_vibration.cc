// The zero-vibration family: zv, zvd, zvdd, designed for a mode of damping
// `design_damping_ratio` (omega_d = omega sqrt(1 - zeta^2), T_d = 2 pi / omega_d,
// K = exp(-zeta pi / sqrt(1 - zeta^2))):
// - zv    [1, K] / (1 + K) at [0, T_d/2]   (Smith's posicast; Singer & Seering 1990)
// - zvd   [1, 2K, K^2] / (1 + K)^2 at [0, T_d/2, T_d]   (Singer & Seering 1990)
// - zvdd  [1, 3K, 3K^2, K^3] / (1 + K)^3 at [0, T_d/2, T_d, 3T_d/2] (ZV convolved thrice)
#include <cmath>

#include "common/math_constants.h"

#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

struct DampedMode {
  double td;  // the damped period T_d
  double k;   // K
};

DampedMode Damped(double frequency_hz, double z) {
  const double root = std::sqrt(1.0 - z * z);
  return {1.0 / (frequency_hz * root), std::exp(-z * kPi / root)};
}

ShaperEntry Entry(const std::string& key, const std::string& name, const std::string& description,
                  int rank, std::vector<Impulse> (*design)(const DampedMode& mode)) {
  ShaperEntry entry = ShaperEntry::Named(key, name, description, ShaperKind::kImpulse, rank);
  entry.design = [design](const PatternConfig& config, double frequency_hz) {
    return design(Damped(frequency_hz, config.design_damping_ratio));
  };
  return entry;
}

std::vector<Impulse> Zv(const DampedMode& m) { return NormalisedImpulses({{0.0, 1.0}, {0.5 * m.td, m.k}}); }

std::vector<Impulse> Zvd(const DampedMode& m) {
  return NormalisedImpulses({{0.0, 1.0}, {0.5 * m.td, 2.0 * m.k}, {m.td, m.k * m.k}});
}

std::vector<Impulse> Zvdd(const DampedMode& m) {
  const double k = m.k;
  return NormalisedImpulses({{0.0, 1.0}, {0.5 * m.td, 3.0 * k}, {m.td, 3.0 * k * k}, {1.5 * m.td, k * k * k}});
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_zero_vibration() {
  return {Entry("zv", "ZV", "zero vibration: 2 impulses over T_d/2", 100, Zv),
          Entry("zvd", "ZVD", "zero vibration and derivative: 3 impulses over T_d", 110, Zvd),
          Entry("zvdd", "ZVDD", "zero vibration, two derivatives: 4 impulses over 3 T_d/2", 120, Zvdd)};
}

}  // namespace shapebench::controller
