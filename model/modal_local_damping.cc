// LocalDampingOfNarrowPeaks (model/modal_local_damping.h).
#include "model/modal_local_damping.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace shapebench::model {
namespace {

using Complex = std::complex<double>;

// The pole of natural frequency |pole| at damping ratio zeta.
Complex WithDamping(Complex pole, double zeta) {
  const double w = std::abs(pole);
  return {-zeta * w, w * std::sqrt(1.0 - zeta * zeta)};
}

// The line spacing at the line nearest x0.
double SpacingAt(const std::vector<double>& x, double x0) {
  const std::size_t k = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), x0) - x.begin());
  const std::size_t i = std::min(std::max<std::size_t>(k, 1), x.size() - 1);
  return x[i] - x[i - 1];
}

struct Neighbourhood {
  std::vector<double> x;
  std::vector<std::vector<Complex>> data;
};

Neighbourhood LinesBetween(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, double lo,
                           double hi) {
  Neighbourhood local;
  local.data.resize(data.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] < lo || x[k] > hi) continue;
    local.x.push_back(x[k]);
    for (std::size_t o = 0; o < data.size(); ++o) local.data[o].push_back(data[o][k]);
  }
  return local;
}

// The damping ratio of `pole` that best fits `local` with that pole alone and the
// residuals: a golden-section search on log zeta in [zeta / 5, 5 zeta].
double BestLocalDamping(const Neighbourhood& local, int d, Complex pole, double max_damping_ratio) {
  const double zeta = -pole.real() / std::abs(pole);
  const auto error = [&](double log_zeta) {
    ModalModel single;
    single.poles = {WithDamping(pole, std::exp(log_zeta))};
    FitLinear(local.x, local.data, d, &single);
    return SquaredError(local.x, local.data, d, single);
  };
  double a = std::log(zeta / 5.0), b = std::log(std::min(5.0 * zeta, 0.999 * max_damping_ratio));
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), e = a + g * (b - a);
  double fc = error(c), fe = error(e);
  for (int i = 0; i < kGoldenSectionSteps && b - a > 1e-6; ++i) {
    if (fc < fe) {
      b = e, e = c, fe = fc, c = b - g * (b - a), fc = error(c);
    } else {
      a = c, c = e, fc = fe, e = a + g * (b - a), fe = error(e);
    }
  }
  return std::exp(0.5 * (a + b));
}

}  // namespace

std::vector<bool> LocalDampingOfNarrowPeaks(const std::vector<double>& x,
                                            const std::vector<std::vector<Complex>>& data, int d,
                                            double max_damping_ratio, double max_error_growth, ModalModel* model) {
  const std::size_t m = model->poles.size();
  std::vector<bool> local(m, false);
  if (x.size() < 2) return local;
  ModalModel trial = *model;
  for (std::size_t r = 0; r < m; ++r) {
    const Complex pole = model->poles[r];
    const double wn = std::abs(pole), zeta = -pole.real() / wn;
    if (!(2.0 * zeta * wn < SpacingAt(x, wn))) continue;  // its top is seen by the lines
    const double lo = r == 0 ? x.front() : 0.5 * (std::abs(model->poles[r - 1]) + wn);
    const double hi = r + 1 == m ? x.back() : 0.5 * (std::abs(model->poles[r + 1]) + wn);
    const Neighbourhood lines = LinesBetween(x, data, lo, hi);
    if (lines.x.size() < 8) continue;  // too few lines for the mode and the residuals
    trial.poles[r] = WithDamping(pole, BestLocalDamping(lines, d, pole, max_damping_ratio));
    local[r] = true;
  }
  if (std::none_of(local.begin(), local.end(), [](bool b) { return b; })) return local;
  FitLinear(x, data, d, &trial);
  if (!(SquaredError(x, data, d, trial) <= (1.0 + max_error_growth) * SquaredError(x, data, d, *model))) {
    return std::vector<bool>(m, false);
  }
  *model = trial;
  return local;
}

std::size_t LeastContribution(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                              const ModalModel& model, double* rise_percent) {
  double total = 0.0;
  for (const auto& frf : data) {
    for (const Complex& h : frf) total += std::norm(h);
  }
  const double with = 100.0 * std::sqrt(SquaredError(x, data, d, model) / total);
  std::size_t least = 0;
  *rise_percent = std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r < model.poles.size(); ++r) {
    ModalModel without;
    without.poles = model.poles;
    without.poles.erase(without.poles.begin() + static_cast<std::ptrdiff_t>(r));
    FitLinear(x, data, d, &without);
    const double rise = 100.0 * std::sqrt(SquaredError(x, data, d, without) / total) - with;
    if (rise < *rise_percent) *rise_percent = rise, least = r;
  }
  return least;
}

}  // namespace shapebench::model
