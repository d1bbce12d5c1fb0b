// mzv, the modified ZV: three positive impulses 3 T_d / 8 apart, c = [1 - 1/sqrt(2),
// sqrt(2) - 1, 1 - 1/sqrt(2)] scaled by K_m^j, K_m = exp(-0.75 zeta pi / sqrt(1 - zeta^2)),
// and normalised (the vector-diagram construction of Singhose, Seering & Singer,
// "Residual vibration reduction using vector diagrams to generate shaping inputs", ASME
// J. Mech. Design 116, 1994, in the form commonly implemented, e.g. by Klipper; not
// checked here against the paper's own table). Its zero at the design point is exact for
// any zeta (the K_m^j scaling cancels the decay).
#include <cmath>

#include "common/math_constants.h"

#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

std::vector<Impulse> Mzv(double frequency_hz, double z) {
  const double root = std::sqrt(1.0 - z * z);
  const double td = 1.0 / (frequency_hz * root);  // damped period T_d
  const double km = std::exp(-0.75 * z * kPi / root);
  const double outer = 1.0 - 1.0 / std::sqrt(2.0);
  const double middle = std::sqrt(2.0) - 1.0;
  return NormalisedImpulses({{0.0, outer}, {0.375 * td, middle * km}, {0.75 * td, outer * km * km}});
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_mzv() {
  ShaperEntry mzv;
  mzv.key = "mzv";
  mzv.name = "MZV";
  mzv.description = "modified zv: 3 impulses over 3 T_d/4";
  mzv.kind = ShaperKind::kImpulse;
  mzv.rank = 130;
  mzv.design = [](const PatternConfig& config, double frequency_hz) {
    return Mzv(frequency_hz, config.design_damping_ratio);
  };
  return {mzv};
}

}  // namespace shapebench::controller
