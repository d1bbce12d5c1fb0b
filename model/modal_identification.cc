// LSCF poles, the stabilisation diagram and LSFD modal constants (model/modal_identification.h).
#include "model/modal_identification.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "model/integrator.h"
#include "model/modal_local_damping.h"
#include "model/modal_refinement.h"
#include "model/modal_subbands.h"

namespace shapebench::model {
namespace {

using Complex = std::complex<double>;

// A narrow peak's damping from its neighbourhood is kept while the whole band's squared
// error grows by at most this fraction (model/modal_local_damping.h; 0.3 % on pyuff's beam).
constexpr double kLocalDampingErrorGrowth = 0.02;

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

// The stabilisation diagram of orders 1..built: each order's physical poles, marked
// against the previous order's.
struct Diagram {
  int built = 0;
  std::vector<DiagramPole> poles;
  std::vector<DiagramPole> last;  // order `built`'s
};

// Extends `diagram` to `to_order` (the lag sums hold lags up to 2 to_order at least).
void ExtendDiagram(const LagSums& sums, double ts, const IdentificationOptions& options, double band_lo_hz,
                   double band_hi_hz, int to_order, Diagram* diagram) {
  for (int order = diagram->built + 1; order <= to_order; ++order) {
    std::vector<DiagramPole> current;
    for (const Complex& lambda : LscfPoles(sums, 2 * order, ts)) {
      if (!(lambda.imag() > 0.0)) continue;  // one of each pair; real poles are not modes
      DiagramPole pole = ToDiagramPole(order, lambda);
      if (!(pole.damping_ratio > 0.0 && pole.damping_ratio < options.max_damping_ratio)) continue;
      if (pole.frequency_hz < band_lo_hz || pole.frequency_hz > band_hi_hz) continue;
      const DiagramPole* nearest = nullptr;
      for (const DiagramPole& before : diagram->last) {
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
    diagram->poles.insert(diagram->poles.end(), current.begin(), current.end());
    diagram->last = std::move(current);
    diagram->built = order;
  }
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The cluster stable[begin, end) as a mode when seen at `needed` orders. Two close modes
// fall in one cluster (within frequency_tolerance of its mean): when `needed` orders hold
// two poles of it, it is split at its widest frequency gap and each part tried.
void AddClusterModes(const std::vector<DiagramPole>& stable, std::size_t begin, std::size_t end, int needed,
                     std::vector<IdentifiedMode>* modes) {
  std::vector<double> frequencies, dampings;
  std::vector<int> orders;
  for (std::size_t i = begin; i < end; ++i) {
    frequencies.push_back(stable[i].frequency_hz);
    dampings.push_back(stable[i].damping_ratio);
    orders.push_back(stable[i].order);
  }
  std::sort(orders.begin(), orders.end());
  int doubled = 0;
  for (std::size_t i = 1; i < orders.size(); ++i) {
    if (orders[i] == orders[i - 1] && (i < 2 || orders[i - 2] != orders[i])) ++doubled;
  }
  if (doubled >= needed && end - begin >= 2) {
    std::size_t split = begin + 1;
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (stable[i].frequency_hz - stable[i - 1].frequency_hz >
          stable[split].frequency_hz - stable[split - 1].frequency_hz) {
        split = i;
      }
    }
    AddClusterModes(stable, begin, split, needed, modes);
    AddClusterModes(stable, split, end, needed, modes);
    return;
  }
  const int distinct = static_cast<int>(std::unique(orders.begin(), orders.end()) - orders.begin());
  if (distinct < needed) return;
  IdentifiedMode mode;
  mode.frequency_hz = Median(frequencies);
  mode.damping_ratio = Median(dampings);
  mode.stable_orders = distinct;
  modes->push_back(mode);
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
    AddClusterModes(stable, begin, end, needed, &modes);
    begin = end;
  }
  return modes;
}

// The modes picked from the diagram's orders 1..order.
std::vector<IdentifiedMode> ModesUpTo(const Diagram& diagram, const IdentificationOptions& options, int order) {
  std::vector<DiagramPole> poles;
  for (const DiagramPole& pole : diagram.poles) {
    if (pole.order <= order) poles.push_back(pole);
  }
  return PickModes(poles, options, order);
}

// As many modes (at least one), each frequency within `tolerance` of the other's.
bool SameModes(const std::vector<IdentifiedMode>& a, const std::vector<IdentifiedMode>& b, double tolerance) {
  if (a.empty() || a.size() != b.size()) return false;
  for (std::size_t r = 0; r < a.size(); ++r) {
    if (std::abs(a[r].frequency_hz - b[r].frequency_hz) > tolerance * b[r].frequency_hz) return false;
  }
  return true;
}

// IdentificationOptions::auto_order: the diagram is extended by doubling the order from
// kFirstAutoOrder (at most `cap`, and while the work stays within max_work) until the
// modes picked up to one order are those picked up to the next; returns that next order.
int ChooseOrder(const LagSums& sums, double ts, const IdentificationOptions& options, double band_lo_hz,
                double band_hi_hz, int cap, int lines, int frfs, Diagram* diagram, ModalIdentification* result) {
  int order = std::min(kFirstAutoOrder, cap);
  ExtendDiagram(sums, ts, options, band_lo_hz, band_hi_hz, order, diagram);
  std::vector<IdentifiedMode> modes = ModesUpTo(*diagram, options, order);
  result->orders_compared = {order};
  result->order_stop = "cap";
  while (order < cap) {
    const int next = std::min(2 * order, cap);
    if (IdentificationWork(lines, frfs, next) > options.max_work) {
      result->order_stop = "work";
      break;
    }
    ExtendDiagram(sums, ts, options, band_lo_hz, band_hi_hz, next, diagram);
    std::vector<IdentifiedMode> next_modes = ModesUpTo(*diagram, options, next);
    result->orders_compared.push_back(next);
    const bool settled = SameModes(modes, next_modes, options.frequency_tolerance);
    order = next;
    modes = std::move(next_modes);
    if (settled) {
      result->order_stop = "settled";
      break;
    }
  }
  return order;
}

Complex Pole(const IdentifiedMode& mode) {
  const double w = kTwoPi * mode.frequency_hz;
  const double zeta = mode.damping_ratio;
  return {-zeta * w, w * std::sqrt(1.0 - zeta * zeta)};
}

// The modes that show in the data: the least prominent below options.min_prominence is
// dropped (kept in `rejected`) and the linear terms refitted, until none is.
void DropHidden(const std::vector<double>& x, const BandData& band, int derivative_order,
                const IdentificationOptions& options, std::vector<IdentifiedMode>* modes, ModalModel* model,
                std::vector<RejectedMode>* rejected, WorkBudget* budget) {
  while (!modes->empty()) {
    std::size_t weakest = 0;
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < modes->size(); ++r) {
      const double prominence = Prominence(x, band.frfs, derivative_order, *model, r);
      (*modes)[r].prominence = prominence;
      if (prominence < lowest) lowest = prominence, weakest = r;
    }
    if (!(lowest < options.min_prominence)) return;
    const IdentifiedMode& mode = (*modes)[weakest];
    rejected->push_back({mode.frequency_hz, mode.damping_ratio, mode.stable_orders, lowest});
    modes->erase(modes->begin() + static_cast<std::ptrdiff_t>(weakest));
    model->poles.erase(model->poles.begin() + static_cast<std::ptrdiff_t>(weakest));
    budget->Charge(LsfdWork(static_cast<int>(x.size()), static_cast<int>(band.frfs.size()),
                            static_cast<int>(model->poles.size())), "refitting the modal constants");
    FitLinear(x, band.frfs, derivative_order, model);
  }
}

// The refinement may carry a pole past its neighbour: modes in ascending frequency again.
void SortByFrequency(ModalModel* model, std::vector<IdentifiedMode>* modes) {
  const std::size_t m = model->poles.size();
  std::vector<std::size_t> order(m);
  for (std::size_t r = 0; r < m; ++r) order[r] = r;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return std::abs(model->poles[a]) < std::abs(model->poles[b]); });
  const ModalModel before = *model;
  const std::vector<IdentifiedMode> modes_before = *modes;
  for (std::size_t r = 0; r < m; ++r) {
    model->poles[r] = before.poles[order[r]];
    (*modes)[r] = modes_before[order[r]];
    for (std::size_t o = 0; o < model->linear.size(); ++o) {
      model->linear[o][2 * r] = before.linear[o][2 * order[r]];
      model->linear[o][2 * r + 1] = before.linear[o][2 * order[r] + 1];
    }
  }
}

// Poles the diagram missed (AddMissedPoles); each mode keeps the diagram's metadata of
// the mode nearest its pole, an added one its error drop.
void AddMissed(const BandData& band, int derivative_order, const IdentificationOptions& options,
               const std::vector<double>& x, ModalModel* model, ModalIdentification* result, WorkBudget* budget) {
  if (options.max_added_modes <= 0) return;
  const ModalModel before = *model;
  const std::vector<double> drops =
      AddMissedPoles(x, band.frfs, derivative_order, options.max_damping_ratio, options.min_prominence,
                     options.min_error_drop, options.max_added_modes, model, budget);
  if (model->poles.size() == before.poles.size()) {
    *model = before;  // nothing added: the refined model as it was
    return;
  }
  result->refined = true;
  std::vector<IdentifiedMode> modes;
  for (std::size_t r = 0; r < model->poles.size(); ++r) {
    IdentifiedMode mode;
    if (drops[r] > 0.0 || before.poles.empty()) {
      mode.error_drop = drops[r];
    } else {
      std::size_t nearest = 0;
      for (std::size_t q = 1; q < before.poles.size(); ++q) {
        if (std::abs(before.poles[q] - model->poles[r]) < std::abs(before.poles[nearest] - model->poles[r])) nearest = q;
      }
      mode = result->modes[nearest];
    }
    mode.prominence = Prominence(x, band.frfs, derivative_order, *model, r);
    modes.push_back(mode);
  }
  result->modes = std::move(modes);
}

// The picked modes fitted to the band: LSFD, the hidden ones dropped, the rest refined by
// nonlinear least squares (then checked again), in normalised units (model/modal_refinement.h).
ModalModel FitModes(const BandData& band, int derivative_order, const IdentificationOptions& options,
                    const std::vector<double>& x, ModalIdentification* result, WorkBudget* budget) {
  const double w_ref = band.omega.back();
  ModalModel model;
  for (const IdentifiedMode& mode : result->modes) model.poles.push_back(Pole(mode) / w_ref);
  FitLinear(x, band.frfs, derivative_order, &model);
  DropHidden(x, band, derivative_order, options, &result->modes, &model, &result->rejected, budget);
  const int lines = static_cast<int>(x.size());
  const int frfs = static_cast<int>(band.frfs.size());
  const auto refining = [&](const ModalModel& m) {
    budget->Charge(RefinementWork(lines, frfs, static_cast<int>(m.poles.size())),
                   "refining " + std::to_string(m.poles.size()) + " modes over " + std::to_string(lines) + " lines");
  };
  if (!options.refine || RefinementWork(lines, frfs, static_cast<int>(model.poles.size())) > options.max_work) {
    return model;
  }
  refining(model);
  const double x_lo = x.front(), x_hi = x.back();
  result->refined = RefineModalModel(x, band.frfs, derivative_order, options.max_damping_ratio, x_lo, x_hi, &model);
  const std::size_t before = model.poles.size();
  for (std::size_t r = 0; r < model.poles.size(); ++r) {
    result->modes[r].frequency_hz = std::abs(model.poles[r]) * w_ref / kTwoPi;
    result->modes[r].damping_ratio = -model.poles[r].real() / std::abs(model.poles[r]);
  }
  DropHidden(x, band, derivative_order, options, &result->modes, &model, &result->rejected, budget);
  if (model.poles.size() != before && result->refined) {
    refining(model);
    RefineModalModel(x, band.frfs, derivative_order, options.max_damping_ratio, x_lo, x_hi, &model);
  }
  AddMissed(band, derivative_order, options, x, &model, result, budget);
  SortByFrequency(&model, &result->modes);
  // Each narrow mode's golden section (its steps and two to start, an LSFD of one mode each)
  // on its neighbourhood, then one refit.
  budget->Charge(2.0 * (kGoldenSectionSteps + 2) * LsfdWork(lines, frfs, 1) +
                     LsfdWork(lines, frfs, static_cast<int>(model.poles.size())),
                 "fitting narrow peaks' damping on their neighbourhoods");
  const std::vector<bool> local = LocalDampingOfNarrowPeaks(x, band.frfs, derivative_order, options.max_damping_ratio,
                                                            kLocalDampingErrorGrowth, &model);
  for (std::size_t r = 0; r < local.size(); ++r) result->modes[r].local_damping = local[r];
  // Modes that explain too little of the data (IdentificationOptions::min_error_rise_percent).
  double rise = 0.0;
  while (options.min_error_rise_percent > 0.0 && !model.poles.empty()) {
    const int m = static_cast<int>(model.poles.size());
    budget->Charge(m * LsfdWork(lines, frfs, m) + LsfdWork(lines, frfs, m), "checking what each of " +
                   std::to_string(m) + " modes explains");
    const std::size_t r = LeastContribution(x, band.frfs, derivative_order, model, &rise);
    if (!(rise < options.min_error_rise_percent)) break;
    const Complex lambda = model.poles[r] * band.omega.back();  // an added mode has only its pole yet
    result->rejected.push_back({std::abs(lambda) / kTwoPi, -lambda.real() / std::abs(lambda),
                                result->modes[r].stable_orders, result->modes[r].prominence, rise});
    result->modes.erase(result->modes.begin() + static_cast<std::ptrdiff_t>(r));
    model.poles.erase(model.poles.begin() + static_cast<std::ptrdiff_t>(r));
    FitLinear(x, band.frfs, derivative_order, &model);
  }
  return model;
}

// The modes' frequencies, damping and modal constants R_r = 2 j w_d A_r, and each FRF's
// residuals and synthesis, in the FRFs' units, from the normalised model.
void StoreFit(const BandData& band, int derivative_order, const std::vector<double>& x, const ModalModel& model,
              ModalIdentification* result) {
  const double w_ref = band.omega.back();
  const double d = derivative_order;
  const std::size_t m = model.poles.size();
  for (std::size_t r = 0; r < m; ++r) {
    const Complex lambda = model.poles[r] * w_ref;
    result->modes[r].frequency_hz = std::abs(lambda) / kTwoPi;
    result->modes[r].damping_ratio = -lambda.real() / std::abs(lambda);
    result->modes[r].modal_constants.clear();
    for (std::size_t o = 0; o < band.frfs.size(); ++o) {
      const Complex a(model.linear[o][2 * r], model.linear[o][2 * r + 1]);
      const Complex residue = a * band.scale * std::pow(w_ref, 1.0 - d);
      result->modes[r].modal_constants.push_back(Complex(0.0, 2.0 * lambda.imag()) * residue);
    }
  }
  result->fits.assign(band.frfs.size(), FrfFit{});
  double error = 0.0, total = 0.0;
  for (std::size_t o = 0; o < band.frfs.size(); ++o) {
    FrfFit& fit = result->fits[o];
    fit.lower_residual = model.linear[o][2 * m] * band.scale * std::pow(w_ref, 2.0 - d);
    fit.upper_residual = model.linear[o][2 * m + 1] * band.scale * std::pow(w_ref, -d);
    double frf_error = 0.0, frf_total = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const Complex value = ModelValue(model, o, x[k], derivative_order);
      fit.synthesized.push_back(value * band.scale);
      frf_error += std::norm(value - band.frfs[o][k]);
      frf_total += std::norm(band.frfs[o][k]);
    }
    fit.error_percent = frf_total > 0.0 ? 100.0 * std::sqrt(frf_error / frf_total) : 0.0;
    error += frf_error;
    total += frf_total;
  }
  result->fit_error_percent = total > 0.0 ? 100.0 * std::sqrt(error / total) : 0.0;
}

ModalIdentification IdentifyWithin(const std::vector<double>& frequency_hz,
                                   const std::vector<std::vector<Complex>>& frfs, int derivative_order,
                                   const IdentificationOptions& options, WorkBudget* budget);

// A band of more than kMaxLinesPerFit lines: each sub-band identified on its own
// (model/modal_subbands.h), within what the budget has left; the modes merged and their
// linear terms fitted on the whole band.
ModalIdentification FitInSubBands(const std::vector<double>& frequency_hz,
                                  const std::vector<std::vector<Complex>>& frfs, int derivative_order,
                                  const IdentificationOptions& options, const BandData& band,
                                  ModalIdentification result, WorkBudget* budget) {
  const std::vector<std::size_t> edges = SubBandEdges(band.frfs);
  for (std::size_t e : edges) result.sub_band_edges_hz.push_back(result.frequency_hz[e]);
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    IdentificationOptions sub = options;
    sub.min_frequency_hz = result.sub_band_edges_hz[i];
    sub.max_frequency_hz = result.sub_band_edges_hz[i + 1];
    sub.max_work = budget->remaining();
    ModalIdentification part = IdentifyWithin(frequency_hz, frfs, derivative_order, sub, budget);
    result.sub_band_orders.push_back(part.max_order);
    if (part.max_order > result.max_order) {
      result.max_order = part.max_order;
      result.orders_compared = part.orders_compared;
      result.order_stop = part.order_stop;
    }
    result.diagram.insert(result.diagram.end(), part.diagram.begin(), part.diagram.end());
    result.rejected.insert(result.rejected.end(), part.rejected.begin(), part.rejected.end());
    result.refined = result.refined || part.refined;
    // Each sub-band's modes ascend, inside its edges: the list stays ascending.
    const std::vector<double>& f = result.frequency_hz;
    for (const IdentifiedMode& mode : part.modes) {
      if (!NearInnerEdge(mode.frequency_hz, result.sub_band_edges_hz, (f.back() - f.front()) / (f.size() - 1.0))) {
        result.modes.push_back(mode);
      }
    }
  }
  ModalModel model;
  for (const IdentifiedMode& mode : result.modes) model.poles.push_back(Pole(mode) / band.omega.back());
  std::vector<double> x;
  for (double w : band.omega) x.push_back(w / band.omega.back());
  budget->Charge(LsfdWork(static_cast<int>(x.size()), static_cast<int>(frfs.size()),
                          static_cast<int>(model.poles.size())), "fitting the sub-bands' modes on the whole band");
  FitLinear(x, band.frfs, derivative_order, &model);
  StoreFit(band, derivative_order, x, model, &result);
  return result;
}

ModalIdentification IdentifyWithin(const std::vector<double>& frequency_hz,
                                   const std::vector<std::vector<Complex>>& frfs, int derivative_order,
                                   const IdentificationOptions& options, WorkBudget* budget) {
  ModalIdentification result;
  const BandData band = SelectBand(frequency_hz, frfs, options, &result.frequency_hz);
  const int lines = static_cast<int>(band.omega.size());
  if (lines > kMaxLinesPerFit) {
    return FitInSubBands(frequency_hz, frfs, derivative_order, options, band, std::move(result), budget);
  }
  // An order's polynomial has 2 order + 1 coefficients per FRF; keep it under the lines.
  const int cap = std::max(1, std::min(options.max_order, (lines - 2) / 4));
  const int count = static_cast<int>(frfs.size());
  RequireWithinWork(lines, count, options.auto_order ? std::min(kFirstAutoOrder, cap) : cap, *budget);
  const double band_lo = std::max(options.min_frequency_hz, result.frequency_hz.front());
  const double band_hi = std::min(options.max_frequency_hz, result.frequency_hz.back());
  const double ts = kPi / band.omega.back();  // the band's top line maps to theta = pi
  const LagSums sums = ComputeLagSums(band, ts, 2 * cap);
  Diagram diagram;
  result.max_order = options.auto_order
                         ? ChooseOrder(sums, ts, options, band_lo, band_hi, cap, lines, count, &diagram, &result)
                         : cap;
  budget->Charge(IdentificationWork(lines, count, result.max_order), "the stabilisation diagram");
  ExtendDiagram(sums, ts, options, band_lo, band_hi, result.max_order, &diagram);
  result.diagram = std::move(diagram.poles);
  result.modes = PickModes(result.diagram, options, result.max_order);
  std::vector<double> x;
  for (double w : band.omega) x.push_back(w / band.omega.back());
  const ModalModel model = FitModes(band, derivative_order, options, x, &result, budget);
  StoreFit(band, derivative_order, x, model, &result);
  return result;
}

}  // namespace

ModalIdentification IdentifyModes(const std::vector<double>& frequency_hz,
                                  const std::vector<std::vector<Complex>>& frfs, int derivative_order,
                                  const IdentificationOptions& options) {
  options.validate();
  if (frfs.empty()) throw ValidationError("frf", "no FRF to identify");
  for (const auto& frf : frfs) {
    if (frf.size() != frequency_hz.size()) throw ValidationError("frf", "an FRF and its frequencies differ in length");
  }
  WorkBudget budget(options.max_work, options.max_work_key);
  ModalIdentification result = IdentifyWithin(frequency_hz, frfs, derivative_order, options, &budget);
  result.work = budget.used();
  RequireFinite(result);
  return result;
}

}  // namespace shapebench::model
