// IdentificationOptions::validate, ToReceptance and the identification's checks
// (model/modal_checks.h).
#include "model/modal_checks.h"

#include <cmath>
#include <complex>
#include <string>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "model/integrator.h"

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

// Refused before the fit starts when its work exceeds options.max_work (ten copies of a
// record at order 200 took 40 s; a thousand records an estimated hour); in a sub-band,
// options.max_work is what the sub-bands below left.
void RequireWithinWork(int lines, int frfs, int max_order, const IdentificationOptions& options, double spent) {
  const double work = IdentificationWork(lines, frfs, max_order);
  if (!(work > options.max_work)) return;
  const double suggested = std::pow(10.0, std::ceil(std::log10(work + spent)));
  throw SolverError("WORK_LIMIT", "identifying " + std::to_string(frfs) + " FRF" + (frfs == 1 ? "" : "s") + " of " +
                                      std::to_string(lines) + " lines up to order " + std::to_string(max_order) +
                                      " would take about " + FormatNumber(work, 3) +
                                      " multiply-adds, more than " + options.max_work_key + " (" +
                                      FormatNumber(spent + options.max_work, 3) + ")" +
                                      (spent > 0.0 ? " less the " + FormatNumber(spent, 3) + " spent on the sub-bands "
                                                     "below; stopped, no mode is reported" : "; nothing was fitted") +
                                      ": raise " + options.max_work_key + " (e.g. to " + FormatNumber(suggested, 3) +
                                      "), or lower the order, narrow the band or take fewer records");
}

}  // namespace shapebench::model
