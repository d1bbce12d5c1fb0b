// The extra-insensitive family (V = vibration_tolerance, z = design_damping_ratio, T the
// undamped period): positive impulses whose residual vibration rises to exactly V in
// humps and is zero between and beside them (Singhose, Seering & Singer, "Residual
// vibration reduction using vector diagrams to generate shaping inputs", ASME J. Mech.
// Design 116, 1994; Singhose, Derezinski & Singer, "Extra-insensitive input shapers for
// controlling flexible spacecraft", J. Guidance, Control & Dynamics 19, 1996; Singhose,
// Porter, Tuttle & Singer, "Vibration reduction using multi-hump input shapers", ASME J.
// Dyn. Sys. Meas. Control 119, 1997):
// - ei: 3 impulses, one hump at the design frequency (V there, dV/dw = 0), a zero on
//   either side. z = 0: [(1 + V)/4, (1 - V)/2, (1 + V)/4] at [0, T/2, T].
// - ei_2hump: 4 impulses, a zero at the design frequency, a hump on either side, a zero
//   beyond each. z = 0: [A1, 1/2 - A1, 1/2 - A1, A1] at [0, T/2, T, 3T/2], A1 = (3 X^2 +
//   2 X + 3 V^2) / (16 X), X = (V^2 (sqrt(1 - V^2) + 1))^(1/3).
// - ei_3hump: 5 impulses, humps at the design frequency and on either side, four zeros
//   between and beyond them. z = 0: [A1, A2, 1 - 2 (A1 + A2), A2, A1] at [0, T/2, T, 3T/2,
//   2T], A1 = (1 + 3 V + 2 sqrt(2 V (V + 1))) / 16, A2 = (1 - V) / 4.
// z > 0: the same conditions for the damped mode (the humps' heights V, their slopes 0,
// the zeros, unit gain) solved exactly by Newton's method from the undamped closed form
// (vibration_conditions.h), so that z -> 0 gives the closed form continuously. The papers
// give curve fits of these designs instead (the EI's as widely implemented, e.g. by
// Klipper), whose residual at the design frequency misses V by up to a few percent.
#include <cmath>
#include <optional>
#include <string>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"
#include "controller/vibration_conditions.h"

namespace shapebench::controller {
namespace {

using Kind = ConditionKind;

// The undamped designs (above), in phases w0 t = pi per half period, with their
// conditions at ratios r = w / w0 in ascending order.
ConditionedShaper UndampedEi(double v) {
  const double zero = std::acos(-(1.0 - v) / (1.0 + v)) / kPi;  // (1+V)/2 cos(pi r) = -(1-V)/2
  return {{(1.0 + v) / 4.0, (1.0 - v) / 2.0, (1.0 + v) / 4.0},
          {0.0, kPi, 2.0 * kPi},
          {{Kind::kZero, zero}, {Kind::kHump, 1.0, true}, {Kind::kZero, 2.0 - zero}}};
}

// V(r) = 2 |u (4 A1 u^2 - 4 A1 + 1/2)|, u = cos(pi r / 2): zeros at u = 0 and u^2 =
// k / (4 A1), humps at u^2 = k / (12 A1), k = 4 A1 - 1/2.
ConditionedShaper UndampedTwoHumpEi(double v) {
  const double x = std::cbrt(v * v * (std::sqrt(1.0 - v * v) + 1.0));
  const double a1 = (3.0 * x * x + 2.0 * x + 3.0 * v * v) / (16.0 * x);
  const double k = 4.0 * a1 - 0.5;
  const double zero = 2.0 / kPi * std::acos(std::sqrt(k / (4.0 * a1)));
  const double hump = 2.0 / kPi * std::acos(std::sqrt(k / (12.0 * a1)));
  return {{a1, 0.5 - a1, 0.5 - a1, a1},
          {0.0, kPi, 2.0 * kPi, 3.0 * kPi},
          {{Kind::kZero, zero},
           {Kind::kHump, hump},
           {Kind::kZero, 1.0, true},
           {Kind::kHump, 2.0 - hump},
           {Kind::kZero, 2.0 - zero}}};
}

// V(r) = |p(x)|, p(x) = 4 A1 x^2 + 2 A2 x + A3 - 2 A1, x = cos(pi r): humps at x = -1
// (r = 1) and at p's vertex x = -A2 / (4 A1), zeros at p's two roots.
ConditionedShaper UndampedThreeHumpEi(double v) {
  const double a1 = (1.0 + 3.0 * v + 2.0 * std::sqrt(2.0 * v * (v + 1.0))) / 16.0;
  const double a2 = (1.0 - v) / 4.0;
  const double a3 = 1.0 - 2.0 * (a1 + a2);
  const double root = std::sqrt(a2 * a2 - 4.0 * a1 * (a3 - 2.0 * a1));
  const double zero_near = std::acos((-a2 - root) / (4.0 * a1)) / kPi;
  const double zero_far = std::acos((-a2 + root) / (4.0 * a1)) / kPi;
  const double hump = std::acos(-a2 / (4.0 * a1)) / kPi;
  return {{a1, a2, a3, a2, a1},
          {0.0, kPi, 2.0 * kPi, 3.0 * kPi, 4.0 * kPi},
          {{Kind::kZero, zero_far},
           {Kind::kHump, hump},
           {Kind::kZero, zero_near},
           {Kind::kHump, 1.0, true},
           {Kind::kZero, 2.0 - zero_near},
           {Kind::kHump, 2.0 - hump},
           {Kind::kZero, 2.0 - zero_far}}};
}

using Undamped = ConditionedShaper (*)(double v);

// The design for damping z (z > 0: solved; see above); throws ValidationError naming
// design_damping_ratio where Newton's method finds none.
ConditionedShaper Design(Undamped undamped, const std::string& key, double z, double v) {
  if (z == 0.0) return undamped(v);
  const std::optional<ConditionedShaper> solved = SolveForDamping(undamped(v), z, v);
  if (!solved) {
    throw ValidationError("design_damping_ratio",
                          "no " + key + " shaper found for damping ratio " + FormatNumber(z) +
                              " with vibration_tolerance " + FormatNumber(v) +
                              " (its damped design conditions have no solution on the undamped "
                              "design's branch); allowed: a smaller design_damping_ratio or "
                              "vibration_tolerance");
  }
  return *solved;
}

std::vector<Impulse> Impulses(const ConditionedShaper& s, double frequency_hz) {
  std::vector<Impulse> impulses;
  for (std::size_t j = 0; j < s.amplitudes.size(); ++j) {
    impulses.push_back({s.phases[j] / (2.0 * kPi * frequency_hz), s.amplitudes[j]});
  }
  return impulses;
}

std::vector<Impulse> Ei(double frequency_hz, double z, double v) {
  if (z == 0.0) {
    // The closed form, written as it always was (the golden set's EI).
    const double t = 1.0 / frequency_hz;
    return {{0.0, (1.0 + v) / 4.0}, {0.5 * t, (1.0 - v) / 2.0}, {t, (1.0 + v) / 4.0}};
  }
  return Impulses(Design(UndampedEi, "ei", z, v), frequency_hz);
}

ShaperEntry Entry(const std::string& key, const std::string& name, const std::string& description,
                  int rank, Undamped undamped) {
  ShaperEntry entry = ShaperEntry::Named(key, name, description, ShaperKind::kImpulse, rank);
  entry.design = [undamped, key](const PatternConfig& config, double frequency_hz) {
    const double z = config.design_damping_ratio;
    return Impulses(Design(undamped, key, z, config.vibration_tolerance), frequency_hz);
  };
  // A damping the continuation cannot reach is a config error, found before the run.
  entry.validate = [undamped, key](const PatternConfig& config) {
    Design(undamped, key, config.design_damping_ratio, config.vibration_tolerance);
  };
  entry.parameters = {"vibration_tolerance"};
  entry.summary = [name](const PatternConfig& config) {
    return name + ": vibration_tolerance " + FormatNumber(config.vibration_tolerance);
  };
  return entry;
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_ei() {
  ShaperEntry ei = Entry("ei", "EI",
                         "extra-insensitive: vibration_tolerance left at the design frequency, zero on either side",
                         140, UndampedEi);
  ei.design = [](const PatternConfig& config, double frequency_hz) {
    return Ei(frequency_hz, config.design_damping_ratio, config.vibration_tolerance);
  };
  ei.summary = [](const PatternConfig& config) {
    return "extra-insensitive: vibration_tolerance " + FormatNumber(config.vibration_tolerance);
  };
  return {ei,
          Entry("ei_2hump", "2-hump EI",
                "two-hump extra-insensitive: zero at the design frequency, humps of vibration_tolerance on "
                "either side, 4 impulses over 3 T/2",
                142, UndampedTwoHumpEi),
          Entry("ei_3hump", "3-hump EI",
                "three-hump extra-insensitive: humps of vibration_tolerance at the design frequency and on "
                "either side, 5 impulses over 2 T",
                144, UndampedThreeHumpEi)};
}

}  // namespace shapebench::controller
