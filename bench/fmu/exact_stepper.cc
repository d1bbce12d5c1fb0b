#include "bench/fmu/exact_stepper.h"

#include <algorithm>
#include <cmath>

namespace shapebench::bench::fmu {
namespace {

// The augmented states output `row` reads: through C, then through A_z (exact zeros only).
// The extremum search takes these alone: the others (another axis, an unread drive
// velocity with its pole at 0) would make A_z singular for it.
std::vector<int> StatesRead(const Eigen::MatrixXd& c, int row, const Eigen::MatrixXd& a_z, int n) {
  const int nz = static_cast<int>(a_z.rows());
  std::vector<bool> needed(static_cast<std::size_t>(nz), false);
  for (int j = 0; j < n; ++j) needed[j] = c(row, j) != 0.0;
  for (bool grew = true; grew;) {
    grew = false;
    for (int i = 0; i < nz; ++i) {
      if (!needed[i]) continue;
      for (int j = 0; j < nz; ++j) {
        if (!needed[j] && a_z(i, j) != 0.0) needed[j] = grew = true;
      }
    }
  }
  std::vector<int> kept;
  for (int j = 0; j < nz; ++j) {
    if (needed[j]) kept.push_back(j);
  }
  return kept;
}

}  // namespace

ExactStepper::ExactStepper(const model::LinearPlant& plant, double period_s, int substeps)
    : plant_(plant), n_(plant.num_states()), m_(plant.num_inputs()), period_s_(period_s), substeps_(substeps) {
  if (n_ > 0) {
    a_z_ = plant.AugmentedA();
    b_z_ = plant.AugmentedB();
  }
  const int rows = static_cast<int>(plant.C.rows());
  for (int r = 0; r < rows && n_ > 0; ++r) kept_.push_back(StatesRead(plant.C, r, a_z_, n_));
  z_ = Eigen::VectorXd::Zero(n_ + m_);
  z_next_ = z_;
  y_ = Eigen::VectorXd::Zero(rows);
  y_next_ = y_;
  peak_.assign(static_cast<std::size_t>(rows), 0.0);
}

ExactStepper::Grid& ExactStepper::GridFor(double h) {
  for (std::size_t i = 0; i < grids_.size(); ++i) {
    if (grids_[i].h == h) {
      std::rotate(grids_.begin(), grids_.begin() + static_cast<std::ptrdiff_t>(i),
                  grids_.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      return grids_.front();
    }
  }
  Grid grid;
  grid.h = h;
  grid.discretization = model::DiscretizeExactly(plant_, h);
  for (const std::vector<int>& kept : kept_) {
    const int k = static_cast<int>(kept.size());
    std::unique_ptr<model::TickExtremum> watcher;
    if (k > 0) {
      Eigen::MatrixXd a(k, k), b(k, m_);
      Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(k);
      const int row = static_cast<int>(grid.extremum.size());
      for (int r = 0; r < k; ++r) {
        for (int col = 0; col < k; ++col) a(r, col) = a_z_(kept[r], kept[col]);
        b.row(r) = b_z_.row(kept[r]);
        if (kept[r] < n_) c(r) = plant_.C(row, kept[r]);
      }
      watcher = model::TickExtremum::Make(a, b, c, h);
    }
    grid.sampled = grid.sampled || (k > 0 && !watcher);
    grid.extremum.push_back(std::move(watcher));
  }
  if (grid.sampled) {
    grid.inner = std::max(1, static_cast<int>(std::ceil(substeps_ * h / period_s_ - 1e-9)));
    grid.inner_discretization = model::DiscretizeExactly(plant_, h / grid.inner);
  }
  if (grids_.size() == 4) grids_.pop_back();  // a master varies its step rarely
  grids_.insert(grids_.begin(), std::move(grid));
  return grids_.front();
}

void ExactStepper::Step(const double* accel, double h) {
  if (n_ == 0) return;  // no state: every output stays 0
  Grid& grid = GridFor(h);
  const Eigen::Map<const Eigen::VectorXd> a(accel, m_);
  z_next_.noalias() = grid.discretization->phi * z_;
  z_next_.noalias() += grid.discretization->gamma * a;
  y_next_.noalias() = plant_.C * z_next_.head(n_);
  for (std::size_t row = 0; row < peak_.size(); ++row) {
    double peak = std::max(std::abs(y_(row)), std::abs(y_next_(row)));
    if (model::TickExtremum* watcher = grid.extremum[row].get()) {
      const std::vector<int>& kept = kept_[row];
      z0_kept_.resize(kept.size());
      z1_kept_.resize(kept.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        z0_kept_[i] = z_(kept[i]);
        z1_kept_[i] = z_next_(kept[i]);
      }
      peak = std::max(peak, watcher->LargestInside(z0_kept_.data(), z1_kept_.data(), accel));
    }
    peak_[row] = peak;
  }
  if (grid.sampled) SampleInside(grid, accel);
  z_.swap(z_next_);
  y_.swap(y_next_);
}

// The rows without an exact search, at the inner samples of the step (its end excluded:
// the step's own end is exact).
void ExactStepper::SampleInside(const Grid& grid, const double* accel) {
  const Eigen::Map<const Eigen::VectorXd> a(accel, m_);
  Eigen::VectorXd z = z_;
  for (int j = 1; j < grid.inner; ++j) {
    z = (grid.inner_discretization->phi * z + grid.inner_discretization->gamma * a).eval();
    for (std::size_t row = 0; row < peak_.size(); ++row) {
      if (grid.extremum[row] || kept_[row].empty()) continue;
      peak_[row] = std::max(peak_[row], std::abs(plant_.C.row(static_cast<Eigen::Index>(row)).dot(z.head(n_))));
    }
  }
}

}  // namespace shapebench::bench::fmu
