#include "model/exact_integrator.h"

#include <cmath>
#include <stdexcept>

#include <unsupported/Eigen/MatrixFunctions>

namespace shapebench::model {
namespace {

// Parlett-Reinsch balancing by powers of two (exact in floating point): returns d with
// D^{-1} M D of comparable row and column norms, D = diag(d). Plant blocks mix entries like
// w^2 h and h; unbalanced, the exponential's absolute error of ~eps * |w^2 h| would swamp
// the small entries and grow, step after step, into the response.
Eigen::VectorXd BalancingScales(const Eigen::MatrixXd& m) {
  const Eigen::Index n = m.rows();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  Eigen::MatrixXd b = m;
  for (bool changed = true; changed;) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double col = b.col(i).cwiseAbs().sum() - std::abs(b(i, i));
      const double row = b.row(i).cwiseAbs().sum() - std::abs(b(i, i));
      if (col == 0.0 || row == 0.0) continue;
      double f = 1.0;
      double c = col;
      while (c < row / 2.0) {
        c *= 2.0;
        f *= 2.0;
      }
      while (c >= row * 2.0) {
        c /= 2.0;
        f /= 2.0;
      }
      if ((c + row / f) < 0.95 * (col + row)) {
        d(i) *= f;
        b.col(i) *= f;
        b.row(i) /= f;
        changed = true;
      }
    }
  }
  return d;
}

}  // namespace

ExactIntegrator::ExactIntegrator(const LinearPlant& plant, double period_s, int substeps)
    : num_states_(plant.num_states()),
      num_inputs_(plant.num_inputs()),
      period_s_(period_s),
      substeps_(substeps),
      C_(plant.C) {
  const int n = num_states_;
  const int m = num_inputs_;
  const int nz = n + m;
  // z' = A_z z + B_z a (LinearPlant::AugmentedA/B). Van Loan:
  // exp([[A_z, B_z], [0, 0]] h) = [[Phi, Gamma], [0, I]], Gamma = int_0^h e^{A_z s} ds B_z.
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(nz + m, nz + m);
  block.topLeftCorner(nz, nz) = plant.AugmentedA();
  block.topRightCorner(nz, m) = plant.AugmentedB();
  const double h = period_s / substeps;
  block *= h;
  const Eigen::VectorXd d = BalancingScales(block);
  const Eigen::MatrixXd balanced = d.cwiseInverse().asDiagonal() * block * d.asDiagonal();
  const Eigen::MatrixXd exp_block = d.asDiagonal() * balanced.exp() * d.cwiseInverse().asDiagonal();
  phi_ = exp_block.topLeftCorner(nz, nz);
  gamma_ = exp_block.topRightCorner(nz, m);
  Reset(Eigen::VectorXd::Zero(m));
}

void ExactIntegrator::Reset(const Eigen::VectorXd& drive_velocity) {
  if (drive_velocity.size() != num_inputs_) {
    throw std::invalid_argument("ExactIntegrator::Reset: wrong drive velocity size");
  }
  z_ = Eigen::VectorXd::Zero(num_states_ + num_inputs_);
  z_.tail(num_inputs_) = drive_velocity;
  accel_ = Eigen::VectorXd::Zero(num_inputs_);
  count_ = 0;
}

void ExactIntegrator::SetInput(const Eigen::VectorXd& drive_accel) {
  if (drive_accel.size() != num_inputs_) {
    throw std::invalid_argument("ExactIntegrator::SetInput: wrong drive acceleration size");
  }
  accel_ = drive_accel;
}

void ExactIntegrator::Step() {
  z_ = phi_ * z_ + gamma_ * accel_;
  ++count_;
}

Eigen::VectorXd ExactIntegrator::Output() const { return C_ * z_.head(num_states_); }

double ExactIntegrator::Time() const { return static_cast<double>(count_) * period_s_ / substeps_; }

IntegratorStats ExactIntegrator::Stats() const { return {count_, 0, 0}; }

}  // namespace shapebench::model
