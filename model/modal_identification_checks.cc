// IdentificationOptions::validate, ToReceptance and RequireFinite (model/modal_identification.h).
#include "model/modal_identification.h"

#include <cmath>
#include <complex>
#include <string>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"

namespace shapebench::model {

using Complex = std::complex<double>;

std::complex<double> ToReceptance(std::complex<double> h, double frequency_hz, int derivative_order) {
  return h / std::pow(Complex(0.0, kTwoPi * frequency_hz), derivative_order);
}

void IdentificationOptions::validate() const {
  if (!(min_frequency_hz >= 0.0) || !(max_frequency_hz > min_frequency_hz)) {
    throw ValidationError("band", "expected 0 <= min < max in Hz");
  }
  if (max_order < 1 || max_order > 200) throw ValidationError("max_order", "must be in [1, 200]");
  if (!(frequency_tolerance > 0.0) || !(damping_tolerance > 0.0)) {
    throw ValidationError("tolerance", "the stabilisation tolerances must be > 0");
  }
  if (!(max_damping_ratio > 0.0 && max_damping_ratio <= 1.0)) {
    throw ValidationError("max_damping_ratio", "must be in (0, 1]");
  }
  if (!(min_stable_fraction >= 0.0 && min_stable_fraction <= 1.0)) {
    throw ValidationError("min_stable_fraction", "must be in [0, 1]");
  }
  if (!(max_work >= 1.0)) throw ValidationError("max_work", "must be >= 1");
  if (!(min_error_rise_percent >= 0.0)) throw ValidationError("min_error_rise_percent", "must be >= 0");
  if (!(min_prominence >= 0.0 && min_prominence < 1.0)) throw ValidationError("min_prominence", "must be in [0, 1)");
  if (!(min_error_drop > 0.0 && min_error_drop < 1.0)) throw ValidationError("min_error_drop", "must be in (0, 1)");
}

// A fit whose error or modes are not numbers (lines 1e-300 Hz apart: the LSCF basis
// degenerates) is refused rather than reported as "fit error -nan %" with exit 0.
void RequireFinite(const ModalIdentification& result) {
  // The lower residual's term LR / w^2 at the lowest line must be a number too.
  const double w_lo = kTwoPi * result.frequency_hz.front();
  bool finite = std::isfinite(result.fit_error_percent) && std::isfinite(1.0 / (w_lo * w_lo));
  for (const IdentifiedMode& mode : result.modes) {
    finite = finite && std::isfinite(mode.frequency_hz) && std::isfinite(mode.damping_ratio);
    for (const Complex& c : mode.modal_constants) finite = finite && std::isfinite(c.real()) && std::isfinite(c.imag());
  }
  if (!finite) {
    const std::vector<double>& f = result.frequency_hz;
    throw ValidationError("frf", "cannot be fitted: the fit's error or modes are not finite numbers (the band's " +
                                     std::to_string(f.size()) + " lines span " + FormatNumber(f.back() - f.front()) +
                                     " Hz from " + FormatNumber(f.front()) + " Hz; lines a usable distance apart "
                                     "are needed)");
  }
}

}  // namespace shapebench::model
