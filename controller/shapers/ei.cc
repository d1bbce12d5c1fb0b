// ei, the extra-insensitive shaper (V = vibration_tolerance, z = design_damping_ratio):
// - z = 0: [(1 + V)/4, (1 - V)/2, (1 + V)/4] at [0, T/2, T] (Singhose, Seering & Singer,
//   "Shaping inputs to reduce vibration: a vector diagram approach", IEEE ICRA 1990;
//   Singhose, Derezinski & Singer, "Extra-insensitive input shapers for controlling
//   flexible spacecraft", J. Guidance, Control & Dynamics 19, 1996): V at the design
//   frequency, zero on either side.
// - z > 0: the published curve fit (Singhose, Porter, Tuttle & Singer, "Vibration
//   reduction using multi-hump input shapers", ASME J. Dyn. Sys. Meas. Control 119, 1997)
//   A1 = 0.24968 + 0.24961 V + (0.80008 + 1.23328 V) z + (0.49599 + 3.17316 V) z^2,
//   A3 = 0.25149 + 0.21474 V + (-0.83249 + 1.41498 V) z + (0.85181 - 4.90094 V) z^2,
//   A2 = 1 - A1 - A3, t2 = (0.49990 + 0.46159 V z + 4.26169 V z^2 + 1.75601 V z^3 +
//   8.57843 V^2 z - 108.644 V^2 z^2 + 336.989 V^2 z^3) T_d, t3 = T_d (coefficients as
//   widely implemented, e.g. by Klipper): a fit, so the damped EI's residual at the design
//   point is V only approximately (limitation; the undamped one is exact): within 0.01
//   absolute for V <= 0.2 and z <= 0.3, the range allowed (ValidateEi), and within about
//   5% of V for z <= 0.1, V >= 0.02.
#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

// The damped EI (above): Singhose et al.'s curve fit; {A1, A2, A3, t2 / T_d}.
struct EiFit {
  double a1, a2, a3, t2_over_td;
};
EiFit DampedEiFit(double v, double z) {
  EiFit fit{};
  fit.a1 = 0.24968 + 0.24961 * v + (0.80008 + 1.23328 * v) * z + (0.49599 + 3.17316 * v) * z * z;
  fit.a3 = 0.25149 + 0.21474 * v + (-0.83249 + 1.41498 * v) * z + (0.85181 - 4.90094 * v) * z * z;
  fit.a2 = 1.0 - fit.a1 - fit.a3;
  fit.t2_over_td = 0.49990 + (0.46159 * v + 8.57843 * v * v) * z +
                   (4.26169 * v - 108.644 * v * v) * z * z +
                   (1.75601 * v + 336.989 * v * v) * z * z * z;
  return fit;
}

std::vector<Impulse> Ei(double frequency_hz, double z, double v) {
  const double root = std::sqrt(1.0 - z * z);
  const double td = 1.0 / (frequency_hz * root);  // damped period T_d
  if (z == 0.0) return {{0.0, (1.0 + v) / 4.0}, {0.5 * td, (1.0 - v) / 2.0}, {td, (1.0 + v) / 4.0}};
  const EiFit fit = DampedEiFit(v, z);
  return {{0.0, fit.a1}, {fit.t2_over_td * td, fit.a2}, {td, fit.a3}};
}

void ValidateEi(const PatternConfig& config) {
  const double v = config.vibration_tolerance;
  const double z = config.design_damping_ratio;
  // The damped EI is a curve fit (above); outside its range it is not an EI shaper.
  if (z > 0.0 && (v > 0.2 || z > 0.3)) {
    throw ValidationError(v > 0.2 ? "vibration_tolerance" : "design_damping_ratio",
                          "the damped EI is Singhose et al.'s curve fit, made for "
                          "vibration_tolerance <= 0.2 and design_damping_ratio <= 0.3 (got " +
                              FormatNumber(v) + ", " + FormatNumber(z) + "); allowed: design_damping_ratio 0 for "
                              "the exact undamped EI with any tolerance in (0, 1)");
  }
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_ei() {
  ShaperEntry ei;
  ei.key = "ei";
  ei.name = "EI";
  ei.description = "extra-insensitive: vibration_tolerance left at the design frequency, zero on either side";
  ei.kind = ShaperKind::kImpulse;
  ei.rank = 140;
  ei.design = [](const PatternConfig& config, double frequency_hz) {
    return Ei(frequency_hz, config.design_damping_ratio, config.vibration_tolerance);
  };
  ei.validate = ValidateEi;
  ei.parameters = {"vibration_tolerance"};
  ei.summary = [](const PatternConfig& config) {
    return "extra-insensitive: vibration_tolerance " + FormatNumber(config.vibration_tolerance);
  };
  return {ei};
}

}  // namespace shapebench::controller
