// LSCF poles, the stabilisation diagram and LSFD modal constants (model/modal_identification.h).
#include "model/modal_identification.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "model/integrator.h"

namespace shapebench::model {
namespace {

using Complex = std::complex<double>;

// The FRFs restricted to the band, scaled to unit RMS (the poles do not depend on the
// scale; the normal equations stay well scaled whatever the unit).
struct BandData {
  std::vector<double> omega;               // rad/s
  std::vector<std::vector<Complex>> frfs;  // measured form, scaled
  double scale = 1.0;                      // original = scaled * scale
};

BandData SelectBand(const std::vector<double>& frequency_hz, const std::vector<std::vector<Complex>>& frfs,
                    const IdentificationOptions& options, std::vector<double>* lines_hz) {
  BandData band;
  band.frfs.resize(frfs.size());
  double sum_squares = 0.0;
  double largest = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < frequency_hz.size(); ++k) {
    const double f = frequency_hz[k];
    if (!(f > 0.0) || f < options.min_frequency_hz || f > options.max_frequency_hz) continue;
    lines_hz->push_back(f);
    band.omega.push_back(kTwoPi * f);
    for (std::size_t o = 0; o < frfs.size(); ++o) {
      const Complex h = frfs[o][k];
      if (!std::isfinite(h.real()) || !std::isfinite(h.imag())) {
        throw ValidationError("frf", "a value at " + std::to_string(f) + " Hz is not finite");
      }
      band.frfs[o].push_back(h);
      sum_squares += std::norm(h);
      largest = std::max({largest, std::abs(h.real()), std::abs(h.imag())});
      ++count;
    }
  }
  if (band.omega.size() < 4) {
    throw ValidationError("band", "fewer than 4 spectral lines above 0 Hz lie in the band [" +
                                      std::to_string(options.min_frequency_hz) + ", " +
                                      std::to_string(options.max_frequency_hz) + "] Hz (" +
                                      std::to_string(band.omega.size()) + ")");
  }
  if (!(largest > 0.0)) throw ValidationError("frf", "every value in the band is 0");
  band.scale = std::sqrt(sum_squares / static_cast<double>(count));
  if (!(band.scale > 0.0) || !std::isfinite(band.scale)) {
    // The squares overflowed (values near 1e155) or underflowed: the RMS of values / largest.
    sum_squares = 0.0;
    for (const auto& frf : band.frfs) {
      for (const Complex& h : frf) sum_squares += std::norm(h / largest);
    }
    band.scale = largest * std::sqrt(sum_squares / static_cast<double>(count));
  }
  for (auto& frf : band.frfs) {
    for (Complex& h : frf) h /= band.scale;
  }
  return band;
}

// The lag sums of the LSCF normal equations (real coefficients, basis Omega^p with
// Omega = exp(-j theta), theta = w Ts): R[p][q] = r[q-p], S_o[p][q] = s_o[q-p],
// T[p][q] = t[q-p] (Verboven 2002, eq. 5.26), for lags -n..n.
struct LagSums {
  int n = 0;
  std::vector<double> r, t;             // index lag + n
  std::vector<std::vector<double>> s;   // per FRF, index lag + n
};

LagSums ComputeLagSums(const BandData& band, double ts, int n) {
  LagSums sums;
  sums.n = n;
  sums.r.assign(2 * n + 1, 0.0);
  sums.t.assign(2 * n + 1, 0.0);
  sums.s.assign(band.frfs.size(), std::vector<double>(2 * n + 1, 0.0));
  for (std::size_t k = 0; k < band.omega.size(); ++k) {
    const double theta = band.omega[k] * ts;
    double magnitude_squared = 0.0;
    for (const auto& frf : band.frfs) magnitude_squared += std::norm(frf[k]);
    for (int lag = -n; lag <= n; ++lag) {
      const Complex basis = std::polar(1.0, -lag * theta);
      sums.r[lag + n] += basis.real();
      sums.t[lag + n] += magnitude_squared * basis.real();
      for (std::size_t o = 0; o < band.frfs.size(); ++o) sums.s[o][lag + n] -= (band.frfs[o][k] * basis).real();
    }
  }
  return sums;
}

// The denominator's roots at polynomial degree `degree`, as continuous poles
// lambda = -ln(z) / Ts; empty when the normal equations are singular.
std::vector<Complex> LscfPoles(const LagSums& sums, int degree, double ts) {
  const int size = degree + 1;
  Eigen::MatrixXd r(size, size), t(size, size);
  for (int p = 0; p < size; ++p) {
    for (int q = 0; q < size; ++q) {
      r(p, q) = sums.r[q - p + sums.n];
      t(p, q) = sums.t[q - p + sums.n];
    }
  }
  const Eigen::LDLT<Eigen::MatrixXd> r_solver(r);
  Eigen::MatrixXd m = t;
  for (const auto& s_lags : sums.s) {
    Eigen::MatrixXd s(size, size);
    for (int p = 0; p < size; ++p) {
      for (int q = 0; q < size; ++q) s(p, q) = s_lags[q - p + sums.n];
    }
    m -= s.transpose() * r_solver.solve(s);
  }
  // Monic: a_degree = 1; the rest minimises a^T M a.
  const Eigen::VectorXd a = m.topLeftCorner(degree, degree).colPivHouseholderQr().solve(-m.topRightCorner(degree, 1));
  if (!a.allFinite()) return {};
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -a(i);
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(companion, /*computeEigenvectors=*/false);
  if (eigen.info() != Eigen::Success) return {};
  std::vector<Complex> poles;
  for (int i = 0; i < degree; ++i) {
    const Complex z = eigen.eigenvalues()(i);
    if (std::abs(z) == 0.0) continue;
    poles.push_back(-std::log(z) / ts);
  }
  return poles;
}

DiagramPole ToDiagramPole(int order, Complex lambda) {
  DiagramPole pole;
  pole.order = order;
  pole.frequency_hz = std::abs(lambda) / kTwoPi;
  pole.damping_ratio = -lambda.real() / std::abs(lambda);
  return pole;
}

// Each order's physical poles, marked against the previous order's.
std::vector<DiagramPole> BuildDiagram(const BandData& band, const IdentificationOptions& options,
                                      double band_lo_hz, double band_hi_hz, int max_order) {
  const double ts = kPi / band.omega.back();  // the band's top line maps to theta = pi
  const LagSums sums = ComputeLagSums(band, ts, 2 * max_order);
  std::vector<DiagramPole> diagram;
  std::vector<DiagramPole> previous;
  for (int order = 1; order <= max_order; ++order) {
    std::vector<DiagramPole> current;
    for (const Complex& lambda : LscfPoles(sums, 2 * order, ts)) {
      if (!(lambda.imag() > 0.0)) continue;  // one of each pair; real poles are not modes
      DiagramPole pole = ToDiagramPole(order, lambda);
      if (!(pole.damping_ratio > 0.0 && pole.damping_ratio < options.max_damping_ratio)) continue;
      if (pole.frequency_hz < band_lo_hz || pole.frequency_hz > band_hi_hz) continue;
      const DiagramPole* nearest = nullptr;
      for (const DiagramPole& before : previous) {
        if (!nearest || std::abs(before.frequency_hz - pole.frequency_hz) <
                            std::abs(nearest->frequency_hz - pole.frequency_hz)) {
          nearest = &before;
        }
      }
      if (nearest && std::abs(nearest->frequency_hz - pole.frequency_hz) <=
                         options.frequency_tolerance * pole.frequency_hz) {
        const bool damping = std::abs(nearest->damping_ratio - pole.damping_ratio) <=
                             options.damping_tolerance * pole.damping_ratio;
        pole.stability = damping ? PoleStability::kStable : PoleStability::kFrequency;
      }
      current.push_back(pole);
    }
    diagram.insert(diagram.end(), current.begin(), current.end());
    previous = std::move(current);
  }
  return diagram;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The modes: clusters of stable poles (each within frequency_tolerance of its cluster's
// mean frequency) seen at enough orders; a mode is its cluster's median frequency and
// damping.
std::vector<IdentifiedMode> PickModes(const std::vector<DiagramPole>& diagram, const IdentificationOptions& options,
                                      int max_order) {
  std::vector<DiagramPole> stable;
  for (const DiagramPole& pole : diagram) {
    if (pole.stability == PoleStability::kStable) stable.push_back(pole);
  }
  std::sort(stable.begin(), stable.end(),
            [](const DiagramPole& a, const DiagramPole& b) { return a.frequency_hz < b.frequency_hz; });
  const int needed = std::max(3, static_cast<int>(std::ceil(options.min_stable_fraction * max_order)));
  std::vector<IdentifiedMode> modes;
  std::size_t begin = 0;
  while (begin < stable.size()) {
    double sum = stable[begin].frequency_hz;
    std::size_t end = begin + 1;
    while (end < stable.size() &&
           stable[end].frequency_hz - sum / static_cast<double>(end - begin) <=
               options.frequency_tolerance * sum / static_cast<double>(end - begin)) {
      sum += stable[end].frequency_hz;
      ++end;
    }
    std::vector<double> frequencies, dampings;
    std::vector<int> orders;
    for (std::size_t i = begin; i < end; ++i) {
      frequencies.push_back(stable[i].frequency_hz);
      dampings.push_back(stable[i].damping_ratio);
      orders.push_back(stable[i].order);
    }
    std::sort(orders.begin(), orders.end());
    const int distinct = static_cast<int>(std::unique(orders.begin(), orders.end()) - orders.begin());
    if (distinct >= needed) {
      IdentifiedMode mode;
      mode.frequency_hz = Median(frequencies);
      mode.damping_ratio = Median(dampings);
      mode.stable_orders = distinct;
      modes.push_back(mode);
    }
    begin = end;
  }
  return modes;
}

Complex Pole(const IdentifiedMode& mode) {
  const double w = kTwoPi * mode.frequency_hz;
  const double zeta = mode.damping_ratio;
  return {-zeta * w, w * std::sqrt(1.0 - zeta * zeta)};
}

// LSFD of one FRF (measured form, scaled): Re and Im of each residue A_r, then LR and UR,
// fitted as real unknowns over the real and imaginary parts of every line; the columns
// are normalised for the solve. Returns the modal constants R_r = 2 j w_d A_r and fills `fit`.
std::vector<Complex> FitConstants(const BandData& band, std::size_t o, const std::vector<IdentifiedMode>& modes,
                                  int derivative_order, FrfFit* fit) {
  const int lines = static_cast<int>(band.omega.size());
  const int unknowns = 2 * static_cast<int>(modes.size()) + 2;
  Eigen::MatrixXcd basis(lines, unknowns);
  for (int k = 0; k < lines; ++k) {
    const Complex jw(0.0, band.omega[k]);
    const Complex form = std::pow(jw, derivative_order);
    for (std::size_t r = 0; r < modes.size(); ++r) {
      const Complex lambda = Pole(modes[r]);
      const Complex g = form / (jw - lambda);
      const Complex g_conjugate = form / (jw - std::conj(lambda));
      basis(k, 2 * r) = g + g_conjugate;                       // Re A_r
      basis(k, 2 * r + 1) = Complex(0.0, 1.0) * (g - g_conjugate);  // Im A_r
    }
    basis(k, unknowns - 2) = -form / (band.omega[k] * band.omega[k]);  // LR: -LR / w^2
    basis(k, unknowns - 1) = form;                                        // UR
  }
  Eigen::MatrixXd real_rows(2 * lines, unknowns);
  Eigen::VectorXd measured(2 * lines);
  real_rows << basis.real(), basis.imag();
  for (int k = 0; k < lines; ++k) {
    measured(k) = band.frfs[o][k].real();
    measured(lines + k) = band.frfs[o][k].imag();
  }
  Eigen::VectorXd norms = real_rows.colwise().norm().transpose();
  for (int c = 0; c < unknowns; ++c) {
    if (!(norms(c) > 0.0)) norms(c) = 1.0;
    real_rows.col(c) /= norms(c);
  }
  Eigen::VectorXd x = real_rows.colPivHouseholderQr().solve(measured);
  x = x.cwiseQuotient(norms);
  if (!x.allFinite()) x.setZero();
  const Eigen::VectorXcd synthesized = basis * x.cast<Complex>();
  double error = 0.0, total = 0.0;
  fit->synthesized.resize(lines);
  for (int k = 0; k < lines; ++k) {
    error += std::norm(synthesized(k) - band.frfs[o][k]);
    total += std::norm(band.frfs[o][k]);
    fit->synthesized[k] = synthesized(k) * band.scale;
  }
  fit->error_percent = total > 0.0 ? 100.0 * std::sqrt(error / total) : 0.0;
  fit->lower_residual = x(unknowns - 2) * band.scale;
  fit->upper_residual = x(unknowns - 1) * band.scale;
  std::vector<Complex> constants;
  for (std::size_t r = 0; r < modes.size(); ++r) {
    const Complex residue(x(2 * r), x(2 * r + 1));
    constants.push_back(Complex(0.0, 2.0 * Pole(modes[r]).imag()) * residue * band.scale);
  }
  return constants;
}

}  // namespace

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
}

namespace {

// A fit whose error or modes are not numbers (lines 1e-300 Hz apart: the LSCF basis
// degenerates) is refused rather than reported as "fit error -nan %" with exit 0.
void RequireFinite(const ModalIdentification& result) {
  bool finite = std::isfinite(result.fit_error_percent);
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
// record at order 200 took 40 s; a thousand records an estimated hour).
void RequireWithinWork(int lines, int frfs, int max_order, const IdentificationOptions& options) {
  const double work = IdentificationWork(lines, frfs, max_order);
  if (!(work > options.max_work)) return;
  const double suggested = std::pow(10.0, std::ceil(std::log10(work)));
  throw SolverError("WORK_LIMIT", "identifying " + std::to_string(frfs) + " FRF" + (frfs == 1 ? "" : "s") + " of " +
                                      std::to_string(lines) + " lines up to order " + std::to_string(max_order) +
                                      " would take about " + FormatNumber(work, 3) +
                                      " multiply-adds, more than " + options.max_work_key + " (" +
                                      FormatNumber(options.max_work, 3) + "); nothing was fitted: raise " +
                                      options.max_work_key + " (e.g. to " + FormatNumber(suggested, 3) +
                                      "), or lower the order, narrow the band or take fewer records");
}

}  // namespace

double IdentificationWork(int lines, int frfs, int max_order) {
  const double l = lines;
  const double r = frfs;
  const double m = max_order;
  double work = l * (4.0 * m + 1.0) * (r + 2.0) + r * 2.0 * l * (2.0 * m + 2.0) * (2.0 * m + 2.0);
  for (int o = 1; o <= max_order; ++o) work += (2.0 * r + 12.0) * std::pow(2.0 * o + 1.0, 3);
  return work;
}

ModalIdentification IdentifyModes(const std::vector<double>& frequency_hz,
                                  const std::vector<std::vector<Complex>>& frfs, int derivative_order,
                                  const IdentificationOptions& options) {
  options.validate();
  if (frfs.empty()) throw ValidationError("frf", "no FRF to identify");
  for (const auto& frf : frfs) {
    if (frf.size() != frequency_hz.size()) throw ValidationError("frf", "an FRF and its frequencies differ in length");
  }
  ModalIdentification result;
  const BandData band = SelectBand(frequency_hz, frfs, options, &result.frequency_hz);
  // An order's polynomial has 2 order + 1 coefficients per FRF; keep it under the lines.
  const int lines = static_cast<int>(band.omega.size());
  result.max_order = std::max(1, std::min(options.max_order, (lines - 2) / 4));
  RequireWithinWork(lines, static_cast<int>(frfs.size()), result.max_order, options);
  const double band_lo = std::max(options.min_frequency_hz, result.frequency_hz.front());
  const double band_hi = std::min(options.max_frequency_hz, result.frequency_hz.back());
  result.diagram = BuildDiagram(band, options, band_lo, band_hi, result.max_order);
  result.modes = PickModes(result.diagram, options, result.max_order);
  result.fits.resize(frfs.size());
  double error = 0.0, total = 0.0;
  for (std::size_t o = 0; o < frfs.size(); ++o) {
    const std::vector<Complex> constants = FitConstants(band, o, result.modes, derivative_order, &result.fits[o]);
    for (std::size_t r = 0; r < result.modes.size(); ++r) result.modes[r].modal_constants.push_back(constants[r]);
    for (int k = 0; k < lines; ++k) {
      error += std::norm(result.fits[o].synthesized[k] / band.scale - band.frfs[o][k]);
      total += std::norm(band.frfs[o][k]);
    }
  }
  result.fit_error_percent = total > 0.0 ? 100.0 * std::sqrt(error / total) : 0.0;
  RequireFinite(result);
  return result;
}

}  // namespace shapebench::model
