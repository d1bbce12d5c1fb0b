// mzv_n, the modified-ZV family (n = impulse_count >= 3, s = impulse_spacing_periods in
// (1/4, 1/2], z = design_damping_ratio): n positive impulses s T_d apart, with zero
// vibration at n - 1 frequency ratios spread evenly from the design frequency up,
//   r_k = 1 + k (1/s - 2) / (n - 2),  k = 0 .. n - 2,
// the general form of the mzv shaper given by D. Butyugin for Klipper
// (klippy/extras/shaper_defs.py, get_mzv_shaper(n, t) with the duration t = (n - 1) s).
// Undamped, with x = e^{i w s T} the residual is |P(x)|, P(x) = sum_j A_j x^j; its zeros'
// phases theta_k = 2 pi s r_k pair up as theta_k + theta_{n-2-k} = 2 pi, so P(x) =
// prod_k (x - e^{i theta_k}) / P(1) has real coefficients: a product of x^2 - 2 cos(theta_k)
// x + 1 (and x + 1 for the middle zero, theta = pi, when n is even), all positive for
// s > 1/4 (every cos(theta_k) < 0). Damped: A_j scaled by K^j, K = exp(-2 pi z s /
// sqrt(1 - z^2)), and normalised, as mzv: the scaling cancels the decay between impulses,
// so the zero at the design frequency stays exact; the upper zeros move a little.
// n = 3, s = 3/8 is mzv (zeros at 1 and 5/3); s = 1/2 puts every zero at the design
// frequency, (x + 1)^(n - 1): zvd for n = 3, zvdd for n = 4.
#include <cmath>
#include <string>
#include <vector>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

constexpr int kMaxImpulses = 16;

std::vector<double> Multiply(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> product(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) product[i + j] += a[i] * b[j];
  }
  return product;
}

std::vector<Impulse> MzvFamily(double frequency_hz, double z, int n, double s) {
  const double root = std::sqrt(1.0 - z * z);
  const double td = 1.0 / (frequency_hz * root);  // damped period T_d
  std::vector<double> p = {1.0};
  const int zeros = n - 1;
  for (int k = 0; k < zeros / 2; ++k) {
    const double theta = 2.0 * kPi * s + k * (2.0 * kPi - 4.0 * kPi * s) / (n - 2);
    p = Multiply(p, {1.0, -2.0 * std::cos(theta), 1.0});
  }
  if (zeros % 2 == 1) p = Multiply(p, {1.0, 1.0});
  const double k = std::exp(-2.0 * kPi * z * s / root);
  std::vector<Impulse> impulses;
  double scale = 1.0;
  for (int j = 0; j < n; ++j) {
    impulses.push_back({j * s * td, p[j] * scale});
    scale *= k;
  }
  return NormalisedImpulses(impulses);
}

void ValidateMzvFamily(const PatternConfig& config) {
  const int n = config.impulse_count;
  if (n < 3 || n > kMaxImpulses) {
    throw ValidationError("impulse_count", "must be in [3, " + std::to_string(kMaxImpulses) +
                                               "] for mzv_n (got " + std::to_string(n) + ")");
  }
  const double s = config.impulse_spacing_periods;
  if (!(std::isfinite(s) && s > 0.25 && s <= 0.5)) {
    throw ValidationError("impulse_spacing_periods",
                          "must be in (0.25, 0.5] damped periods for mzv_n (0.5 is the zv convolved "
                          "n - 1 times; at 0.25 and below an impulse is zero or negative; got " +
                              FormatNumber(s) + ")");
  }
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_mzv_family() {
  ShaperEntry family;
  family.key = "mzv_n";
  family.name = "MZV-n";
  family.description =
      "modified zv family: impulse_count impulses impulse_spacing_periods T_d apart, zeros spread from "
      "the design frequency up";
  family.kind = ShaperKind::kImpulse;
  family.rank = 135;
  family.design = [](const PatternConfig& config, double frequency_hz) {
    return MzvFamily(frequency_hz, config.design_damping_ratio, config.impulse_count,
                     config.impulse_spacing_periods);
  };
  family.validate = ValidateMzvFamily;
  family.parameters = {"impulse_count", "impulse_spacing_periods"};
  family.summary = [](const PatternConfig& config) {
    return "modified zv family: " + std::to_string(config.impulse_count) + " impulses " +
           FormatNumber(config.impulse_spacing_periods) + " T_d apart";
  };
  return {family};
}

}  // namespace shapebench::controller
