// LSFD, the modes' prominence and the nonlinear refinement (model/modal_refinement.h).
#include "model/modal_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>
#include <ceres/ceres.h>

namespace shapebench::model {
namespace {

using Complex = std::complex<double>;
constexpr Complex kJ(0.0, 1.0);

Complex Form(double x, int d) { return std::pow(Complex(0.0, x), d); }

// One FRF's residuals (real and imaginary part of model - data at each line) and their
// derivatives by the poles (one block of Re mu, Im mu each) and by the FRF's linear terms
// (the last block), analytically.
class FrfResidual : public ceres::CostFunction {
 public:
  FrfResidual(const std::vector<double>& x, const std::vector<Complex>& data, int d, int modes)
      : x_(x), data_(data), d_(d), modes_(modes) {
    set_num_residuals(2 * static_cast<int>(x.size()));
    for (int r = 0; r < modes; ++r) mutable_parameter_block_sizes()->push_back(2);
    mutable_parameter_block_sizes()->push_back(2 * modes + 2);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* linear = parameters[modes_];
    const int width = 2 * modes_ + 2;
    for (std::size_t k = 0; k < x_.size(); ++k) {
      const Complex jx(0.0, x_[k]);
      const Complex form = Form(x_[k], d_);
      Complex sum = -linear[2 * modes_] / (x_[k] * x_[k]) + linear[2 * modes_ + 1];
      double* linear_rows = jacobians && jacobians[modes_] ? jacobians[modes_] + 2 * k * width : nullptr;
      for (int r = 0; r < modes_; ++r) {
        const Complex mu(parameters[r][0], parameters[r][1]);
        const Complex a(linear[2 * r], linear[2 * r + 1]);
        const Complex g1 = 1.0 / (jx - mu);
        const Complex g2 = 1.0 / (jx - std::conj(mu));
        sum += a * g1 + std::conj(a) * g2;
        if (jacobians && jacobians[r]) {
          const Complex by_re = form * (a * g1 * g1 + std::conj(a) * g2 * g2);
          const Complex by_im = form * kJ * (a * g1 * g1 - std::conj(a) * g2 * g2);
          double* rows = jacobians[r] + 4 * k;
          rows[0] = by_re.real(), rows[1] = by_im.real(), rows[2] = by_re.imag(), rows[3] = by_im.imag();
        }
        if (linear_rows) {
          const Complex by_a_re = form * (g1 + g2);
          const Complex by_a_im = form * kJ * (g1 - g2);
          linear_rows[2 * r] = by_a_re.real(), linear_rows[2 * r + 1] = by_a_im.real();
          linear_rows[width + 2 * r] = by_a_re.imag(), linear_rows[width + 2 * r + 1] = by_a_im.imag();
        }
      }
      if (linear_rows) {
        const Complex by_lower = -form / (x_[k] * x_[k]);
        linear_rows[2 * modes_] = by_lower.real(), linear_rows[2 * modes_ + 1] = form.real();
        linear_rows[width + 2 * modes_] = by_lower.imag(), linear_rows[width + 2 * modes_ + 1] = form.imag();
      }
      const Complex residual = form * sum - data_[k];
      residuals[2 * k] = residual.real();
      residuals[2 * k + 1] = residual.imag();
    }
    return true;
  }

 private:
  const std::vector<double>& x_;
  const std::vector<Complex>& data_;
  int d_;
  int modes_;
};

bool Physical(const ModalModel& model, double max_damping_ratio, double x_lo, double x_hi) {
  for (const Complex& mu : model.poles) {
    const double zeta = -mu.real() / std::abs(mu);
    if (!(zeta > 0.0 && zeta < max_damping_ratio) || !(mu.imag() > 0.0)) return false;
    if (!(std::abs(mu) >= x_lo && std::abs(mu) <= x_hi)) return false;
  }
  return true;
}

}  // namespace

Complex ModeTerm(const ModalModel& model, std::size_t frf, std::size_t r, double x, int d) {
  const Complex jx(0.0, x);
  const Complex a(model.linear[frf][2 * r], model.linear[frf][2 * r + 1]);
  const Complex mu = model.poles[r];
  return Form(x, d) * (a / (jx - mu) + std::conj(a) / (jx - std::conj(mu)));
}

Complex ModelValue(const ModalModel& model, std::size_t frf, double x, int d) {
  const std::vector<double>& linear = model.linear[frf];
  const std::size_t m = model.poles.size();
  Complex value = Form(x, d) * (-linear[2 * m] / (x * x) + linear[2 * m + 1]);
  for (std::size_t r = 0; r < m; ++r) value += ModeTerm(model, frf, r, x, d);
  return value;
}

void FitLinear(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d, ModalModel* model) {
  const int lines = static_cast<int>(x.size());
  const int m = static_cast<int>(model->poles.size());
  const int unknowns = 2 * m + 2;
  Eigen::MatrixXcd basis(lines, unknowns);
  for (int k = 0; k < lines; ++k) {
    const Complex jx(0.0, x[k]);
    const Complex form = Form(x[k], d);
    for (int r = 0; r < m; ++r) {
      const Complex g1 = form / (jx - model->poles[r]);
      const Complex g2 = form / (jx - std::conj(model->poles[r]));
      basis(k, 2 * r) = g1 + g2;
      basis(k, 2 * r + 1) = kJ * (g1 - g2);
    }
    basis(k, unknowns - 2) = -form / (x[k] * x[k]);
    basis(k, unknowns - 1) = form;
  }
  Eigen::MatrixXd rows(2 * lines, unknowns);
  rows << basis.real(), basis.imag();
  Eigen::VectorXd norms = rows.colwise().norm().transpose();
  for (int c = 0; c < unknowns; ++c) {
    if (!(norms(c) > 0.0)) norms(c) = 1.0;
    rows.col(c) /= norms(c);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(rows);
  model->linear.assign(data.size(), std::vector<double>(unknowns, 0.0));
  for (std::size_t o = 0; o < data.size(); ++o) {
    Eigen::VectorXd measured(2 * lines);
    for (int k = 0; k < lines; ++k) measured(k) = data[o][k].real(), measured(lines + k) = data[o][k].imag();
    Eigen::VectorXd solution = qr.solve(measured).cwiseQuotient(norms);
    if (!solution.allFinite()) solution.setZero();
    for (int c = 0; c < unknowns; ++c) model->linear[o][c] = solution(c);
  }
}

double SquaredError(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                    const ModalModel& model) {
  double sum = 0.0;
  for (std::size_t o = 0; o < data.size(); ++o) {
    for (std::size_t k = 0; k < x.size(); ++k) sum += std::norm(ModelValue(model, o, x[k], d) - data[o][k]);
  }
  return sum;
}

double Prominence(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                  const ModalModel& model, std::size_t r) {
  const Complex mu = model.poles[r];
  const double xr = std::abs(mu);
  const double spacing = x.size() > 1 ? (x.back() - x.front()) / static_cast<double>(x.size() - 1) : xr;
  const double half_width = std::max(2.0 * (-mu.real()), 2.0 * spacing);
  double best = 0.0;
  for (std::size_t o = 0; o < data.size(); ++o) {
    double largest = 0.0, squares = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (std::abs(x[k] - xr) > half_width) continue;
      largest = std::max(largest, std::abs(ModeTerm(model, o, r, x[k], d)));
      squares += std::norm(data[o][k]);
      ++count;
    }
    if (count > 0 && squares > 0.0) best = std::max(best, largest / std::sqrt(squares / count));
  }
  return best;
}

bool RefineModalModel(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                      double max_damping_ratio, double x_lo, double x_hi, ModalModel* model) {
  if (model->poles.empty()) return false;
  ModalModel refined = *model;
  const int m = static_cast<int>(refined.poles.size());
  std::vector<std::array<double, 2>> poles(m);
  for (int r = 0; r < m; ++r) poles[r] = {refined.poles[r].real(), refined.poles[r].imag()};
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (std::size_t o = 0; o < data.size(); ++o) {
    std::vector<double*> blocks;
    for (int r = 0; r < m; ++r) blocks.push_back(poles[r].data());
    blocks.push_back(refined.linear[o].data());
    problem.AddResidualBlock(new FrfResidual(x, data[o], d, m), nullptr, blocks);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  options.gradient_tolerance = 1e-16;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return false;
  for (int r = 0; r < m; ++r) refined.poles[r] = {poles[r][0], poles[r][1]};
  const double before = SquaredError(x, data, d, *model);
  const double after = SquaredError(x, data, d, refined);
  if (!(after <= before) || !Physical(refined, max_damping_ratio, x_lo, x_hi)) return false;
  *model = std::move(refined);
  return true;
}

namespace {

// `model` with `poles` as its poles, fitted; its squared error, or infinity when a pole is
// not physical or does not show in the data.
// Two poles closer than two lines: the data cannot tell them apart (a lightly damped mode
// narrower than a line is fitted by a pair straddling it).
double MinimumGap(const std::vector<double>& x) {
  return x.size() > 1 ? 2.0 * (x.back() - x.front()) / static_cast<double>(x.size() - 1) : 0.0;
}

bool TooClose(const std::vector<Complex>& poles, double gap) {
  for (std::size_t a = 0; a < poles.size(); ++a) {
    for (std::size_t b = a + 1; b < poles.size(); ++b) {
      if (std::abs(std::abs(poles[a]) - std::abs(poles[b])) < gap) return true;
    }
  }
  return false;
}

double Candidate(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                 double max_damping_ratio, double min_prominence, std::vector<Complex> poles, ModalModel* model) {
  if (TooClose(poles, MinimumGap(x))) return std::numeric_limits<double>::infinity();
  std::sort(poles.begin(), poles.end(), [](Complex a, Complex b) { return std::abs(a) < std::abs(b); });
  model->poles = std::move(poles);
  FitLinear(x, data, d, model);
  RefineModalModel(x, data, d, max_damping_ratio, x.front(), x.back(), model);
  // After the fit, a line apart at least (a pair between one and two lines apart may part
  // when the next pole is added).
  if (TooClose(model->poles, 0.5 * MinimumGap(x))) return std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r < model->poles.size(); ++r) {
    if (Prominence(x, data, d, *model, r) < min_prominence) return std::numeric_limits<double>::infinity();
  }
  return Physical(*model, max_damping_ratio, x.front(), x.back()) ? SquaredError(x, data, d, *model)
                                                                  : std::numeric_limits<double>::infinity();
}

Complex PoleAt(double x, double zeta) { return {-zeta * x, x * std::sqrt(1.0 - zeta * zeta)}; }

}  // namespace

std::vector<double> AddMissedPoles(const std::vector<double>& x, const std::vector<std::vector<Complex>>& data, int d,
                                   double max_damping_ratio, double min_prominence, double min_drop, int max_added,
                                   ModalModel* model, WorkBudget* budget) {
  std::vector<double> drops(model->poles.size(), 0.0);
  double energy = 0.0;
  for (const auto& frf : data) {
    for (const Complex& h : frf) energy += std::norm(h);
  }
  for (int added = 0; added < max_added; ++added) {
    const double error = SquaredError(x, data, d, *model);
    if (!(error > 1e-8 * energy)) break;  // fitted to 0.01 %: nothing is missing
    std::vector<std::vector<Complex>> candidates;
    for (std::size_t r = 0; r < model->poles.size(); ++r) {
      const Complex mu = model->poles[r];
      const double zeta = -mu.real() / std::abs(mu);
      const double delta = std::max({zeta, 0.005, MinimumGap(x) / std::abs(mu)});
      std::vector<Complex> poles = model->poles;
      poles[r] = PoleAt(std::abs(mu) * (1.0 - delta), zeta);
      poles.push_back(PoleAt(std::abs(mu) * (1.0 + delta), zeta));
      candidates.push_back(poles);
    }
    std::size_t worst = 0;
    double largest = -1.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      double misfit = 0.0;
      for (std::size_t o = 0; o < data.size(); ++o) misfit += std::norm(ModelValue(*model, o, x[k], d) - data[o][k]);
      if (misfit > largest) largest = misfit, worst = k;
    }
    // At the largest residual, or two gaps beside the pole it is too close to.
    double at = x[worst];
    for (const Complex& mu : model->poles) {
      if (std::abs(std::abs(mu) - at) < MinimumGap(x)) at = std::abs(mu) + (at < std::abs(mu) ? -2.0 : 2.0) * MinimumGap(x);
    }
    candidates.push_back(model->poles);
    candidates.back().push_back(PoleAt(at, 0.01));
    ModalModel best;
    double best_error = std::numeric_limits<double>::infinity();
    const int lines = static_cast<int>(x.size()), frfs = static_cast<int>(data.size());
    const int trial_modes = static_cast<int>(model->poles.size()) + 1;
    budget->Charge(static_cast<double>(candidates.size()) *
                       (RefinementWork(lines, frfs, trial_modes) + LsfdWork(lines, frfs, trial_modes)),
                   "trying " + std::to_string(candidates.size()) + " candidates for a pole the diagram missed (" +
                       std::to_string(trial_modes) + " modes refined over " + std::to_string(lines) + " lines each)");
    for (const std::vector<Complex>& poles : candidates) {
      ModalModel trial = *model;
      const double trial_error = Candidate(x, data, d, max_damping_ratio, min_prominence, poles, &trial);
      if (trial_error < best_error) best_error = trial_error, best = std::move(trial);
    }
    if (!(best_error < (1.0 - min_drop) * error)) break;
    // The new pole is the one of `best` farthest from every pole of `model`.
    std::size_t fresh = 0;
    double farthest = -1.0;
    for (std::size_t r = 0; r < best.poles.size(); ++r) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const Complex& old : model->poles) nearest = std::min(nearest, std::abs(best.poles[r] - old));
      if (nearest > farthest) farthest = nearest, fresh = r;
    }
    std::vector<double> new_drops;
    for (std::size_t r = 0; r < best.poles.size(); ++r) {
      std::size_t closest = 0;
      for (std::size_t q = 0; q < model->poles.size(); ++q) {
        if (std::abs(best.poles[r] - model->poles[q]) < std::abs(best.poles[r] - model->poles[closest])) closest = q;
      }
      new_drops.push_back(r == fresh ? 1.0 - best_error / error : (model->poles.empty() ? 0.0 : drops[closest]));
    }
    drops = new_drops;
    *model = std::move(best);
  }
  return drops;
}

}  // namespace shapebench::model
