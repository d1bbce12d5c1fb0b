// HeldInputResponse: the linear part's exact response under held inputs, its probes as
// Chebyshev series over each tick (model/held_input_response.h).
#include "model/held_input_response.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "common/math_constants.h"
#include "model/exact_integrator.h"

namespace shapebench::model {
namespace {

constexpr int kNodes = HeldInputResponse::kDegree + 1;

// Chebyshev points of the first kind on [-1, 1] (no end points: the series is read at the
// piece's ends by evaluation, the same from both sides to rounding).
double Node(int j) { return std::cos(kPi * (j + 0.5) / kNodes); }

// b_k from the values at the nodes: f = sum_k b_k T_k, b_0 the halved c_0.
Eigen::MatrixXd ChebyshevTransform() {
  Eigen::MatrixXd t(kNodes, kNodes);
  for (int k = 0; k < kNodes; ++k) {
    for (int j = 0; j < kNodes; ++j) t(k, j) = (k == 0 ? 1.0 : 2.0) / kNodes * std::cos(kPi * k * (j + 0.5) / kNodes);
  }
  return t;
}

// sum_k b_k T_k(s) by Clenshaw's recurrence.
double Clenshaw(const double* b, double s) {
  double y1 = 0.0;
  double y2 = 0.0;
  for (int k = kNodes - 1; k >= 1; --k) {
    const double y = b[k] + 2.0 * s * y1 - y2;
    y2 = y1;
    y1 = y;
  }
  return b[0] + s * y1 - y2;
}

}  // namespace

HeldInputResponse::Rows::Rows(const Eigen::MatrixXd& z, const Eigen::MatrixXd& a) : over_a(a) {
  for (Eigen::Index c = 0; c < z.cols(); ++c) {
    if (z.col(c).cwiseAbs().maxCoeff() > 0.0) columns.push_back(static_cast<int>(c));
  }
  over_z.resize(z.rows(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) over_z.col(static_cast<Eigen::Index>(c)) = z.col(columns[c]);
}

void HeldInputResponse::Rows::Apply(const Eigen::VectorXd& state, const Eigen::VectorXd& accel,
                                    Eigen::VectorXd* gathered, double* out) const {
  gathered->resize(static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) (*gathered)(static_cast<Eigen::Index>(c)) = state(columns[c]);
  Eigen::Map<Eigen::VectorXd> result(out, over_z.rows());
  result.noalias() = over_z * *gathered;
  result.noalias() += over_a * accel;
}

HeldInputResponse::HeldInputResponse(const LinearPlant& plant, double period_s, int substeps,
                                     const Eigen::MatrixXd& probes)
    : plant_(plant),
      substeps_(substeps),
      nz_(plant.num_states() + plant.num_inputs()),
      probes_(probes) {
  const Eigen::MatrixXd a_z = plant.AugmentedA();
  double rho = 0.0;
  if (nz_ > 0) rho = Eigen::EigenSolver<Eigen::MatrixXd>(a_z, false).eigenvalues().cwiseAbs().maxCoeff();
  pieces_ = std::max(1, static_cast<int>(std::ceil(rho * period_s / kMaxRhoPiece)));
  piece_s_ = period_s / pieces_;
  const Eigen::MatrixXd transform = ChebyshevTransform();
  const int m = plant.num_inputs();
  for (int p = 0; p < pieces_; ++p) {
    std::vector<Eigen::MatrixXd> values_z(num_probes(), Eigen::MatrixXd(kNodes, nz_));
    std::vector<Eigen::MatrixXd> values_a(num_probes(), Eigen::MatrixXd(kNodes, m));
    for (int j = 0; j < kNodes; ++j) {
      const double tau = piece_s_ * (p + 0.5 * (1.0 + Node(j)));
      const auto exact = DiscretizeExactly(plant, tau);
      for (int i = 0; i < num_probes(); ++i) {
        values_z[i].row(j) = probes_.row(i) * exact->phi;
        values_a[i].row(j) = probes_.row(i) * exact->gamma;
      }
    }
    for (int i = 0; i < num_probes(); ++i) series_rows_.emplace_back(transform * values_z[i], transform * values_a[i]);
  }
  const int rows = plant.num_outputs();
  Eigen::MatrixXd c_z = Eigen::MatrixXd::Zero(rows, nz_);
  c_z.leftCols(plant.num_states()) = plant.C;
  std::vector<Eigen::MatrixXd> out_z(rows, Eigen::MatrixXd(substeps, nz_));
  std::vector<Eigen::MatrixXd> out_a(rows, Eigen::MatrixXd(substeps, m));
  for (int j = 1; j <= substeps; ++j) {
    const auto exact = DiscretizeExactly(plant, period_s * j / substeps);
    for (int r = 0; r < rows; ++r) {
      out_z[r].row(j - 1) = c_z.row(r) * exact->phi;
      out_a[r].row(j - 1) = c_z.row(r) * exact->gamma;
    }
  }
  output_of_row_.assign(rows, -1);
  for (int r = 0; r < rows; ++r) {
    if (c_z.row(r).cwiseAbs().maxCoeff() == 0.0) continue;  // reaches no state: 0 throughout
    // A row equal to an earlier one (the kinematic drive's tool error and deflection) is
    // that row's values.
    for (int q = 0; q < r && output_of_row_[r] < 0; ++q) {
      if (output_of_row_[q] >= 0 && c_z.row(q) == c_z.row(r)) output_of_row_[r] = output_of_row_[q];
    }
    if (output_of_row_[r] >= 0) continue;
    output_of_row_[r] = static_cast<int>(outputs_rows_.size());
    outputs_rows_.emplace_back(out_z[r], out_a[r]);
  }
  const auto tick = DiscretizeExactly(plant, period_s);
  tick_phi_ = tick->phi;
  tick_gamma_ = tick->gamma;
  series_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(pieces_) * num_probes() * kNodes);
  slopes_ = series_;
  tick_outputs_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(outputs_rows_.size()) * substeps);
  Reset(Eigen::VectorXd::Zero(nz_));
}

void HeldInputResponse::Reset(const Eigen::VectorXd& z0) {
  start_ = z0;
  accel_ = Eigen::VectorXd::Zero(plant_.num_inputs());
  UpdateSeries();
}

void HeldInputResponse::SetInput(const double* accel) {
  accel_ = Eigen::Map<const Eigen::VectorXd>(accel, plant_.num_inputs());
  UpdateSeries();
}

void HeldInputResponse::NextTick() {
  next_.noalias() = tick_phi_ * start_;
  next_.noalias() += tick_gamma_ * accel_;
  start_.swap(next_);
  UpdateSeries();
}

// The series of this tick and their derivatives: for f = sum_k b_k T_k,
// f' = d_0 / 2 + sum_{k>=1} d_k T_k with d_{k-1} = d_{k+1} + 2 k b_k.
void HeldInputResponse::UpdateSeries() {
  for (std::size_t r = 0; r < series_rows_.size(); ++r) {
    double* b = series_.data() + static_cast<std::ptrdiff_t>(r) * kNodes;
    series_rows_[r].Apply(start_, accel_, &gathered_, b);
    double* d = slopes_.data() + static_cast<std::ptrdiff_t>(r) * kNodes;
    double next = 0.0;   // d_{k+1}
    double after = 0.0;  // d_{k+2}
    d[kNodes - 1] = 0.0;
    for (int k = kNodes - 1; k >= 1; --k) {
      const double value = after + 2.0 * k * b[k];
      d[k - 1] = value;
      after = next;
      next = value;
    }
    d[0] *= 0.5;
  }
  for (std::size_t r = 0; r < outputs_rows_.size(); ++r) {
    outputs_rows_[r].Apply(start_, accel_, &gathered_, tick_outputs_.data() + static_cast<std::ptrdiff_t>(r) * substeps_);
  }
}

void HeldInputResponse::Probe(double tau, double* values, double* rates) const {
  const int p = std::clamp(static_cast<int>(tau / piece_s_), 0, pieces_ - 1);
  const double s = 2.0 * (tau - p * piece_s_) / piece_s_ - 1.0;
  const double ds_dt = 2.0 / piece_s_;
  for (int i = 0; i < num_probes(); ++i) {
    const std::ptrdiff_t at = (static_cast<std::ptrdiff_t>(p) * num_probes() + i) * kNodes;
    values[i] = Clenshaw(series_.data() + at, s);
    if (rates != nullptr) rates[i] = ds_dt * Clenshaw(slopes_.data() + at, s);
  }
}

void HeldInputResponse::OutputsAt(int j, double* outputs) const {
  for (std::size_t r = 0; r < output_of_row_.size(); ++r) {
    const int at = output_of_row_[r];
    outputs[r] = at < 0 ? 0.0 : tick_outputs_(static_cast<Eigen::Index>(at) * substeps_ + j - 1);
  }
}

Eigen::VectorXd HeldInputResponse::StateAt(double tau) const {
  if (tau <= 0.0) return start_;
  const auto exact = DiscretizeExactly(plant_, tau);
  return exact->phi * start_ + exact->gamma * accel_;
}

}  // namespace shapebench::model
