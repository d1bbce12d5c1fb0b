#include "model/exact_integrator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
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

std::shared_ptr<const ExactDiscretization> DiscretizeExactly(const LinearPlant& plant, double h) {
  const Eigen::MatrixXd a_z = plant.AugmentedA();
  const Eigen::MatrixXd b_z = plant.AugmentedB();
  struct Entry {
    Eigen::MatrixXd a_z;
    Eigen::MatrixXd b_z;
    double h;
    std::shared_ptr<const ExactDiscretization> result;
  };
  constexpr std::size_t kKept = 8;
  thread_local std::vector<Entry> cache;  // most recent first
  for (std::size_t i = 0; i < cache.size(); ++i) {
    const Entry& e = cache[i];
    if (e.h == h && e.a_z.rows() == a_z.rows() && e.b_z.cols() == b_z.cols() && e.a_z == a_z &&
        e.b_z == b_z) {
      std::rotate(cache.begin(), cache.begin() + static_cast<std::ptrdiff_t>(i),
                  cache.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      return cache.front().result;
    }
  }
  const Eigen::Index nz = a_z.rows();
  const Eigen::Index m = b_z.cols();
  // z' = A_z z + B_z a (LinearPlant::AugmentedA/B). Van Loan:
  // exp([[A_z, B_z], [0, 0]] h) = [[Phi, Gamma], [0, I]], Gamma = int_0^h e^{A_z s} ds B_z.
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(nz + m, nz + m);
  block.topLeftCorner(nz, nz) = a_z;
  block.topRightCorner(nz, m) = b_z;
  block *= h;
  const Eigen::VectorXd d = BalancingScales(block);
  const Eigen::MatrixXd balanced = d.cwiseInverse().asDiagonal() * block * d.asDiagonal();
  const Eigen::MatrixXd exp_block = d.asDiagonal() * balanced.exp() * d.cwiseInverse().asDiagonal();
  auto result = std::make_shared<ExactDiscretization>();
  result->phi = exp_block.topLeftCorner(nz, nz);
  result->gamma = exp_block.topRightCorner(nz, m);
  if (cache.size() == kKept) cache.pop_back();
  cache.insert(cache.begin(), Entry{a_z, b_z, h, result});
  return result;
}

namespace {

// The augmented states that reach an output: read by C, or (transitively) by such a state
// through phi. Exact zeros only (block structure: other axes, an unused drive velocity),
// so the outputs are those of the full recursion.
std::vector<int> StatesReachingOutputs(const Eigen::MatrixXd& c, const Eigen::MatrixXd& phi,
                                       int num_states) {
  const int nz = static_cast<int>(phi.rows());
  std::vector<bool> needed(nz, false);
  for (int j = 0; j < num_states; ++j) needed[j] = c.col(j).cwiseAbs().maxCoeff() > 0.0;
  for (bool grew = true; grew;) {
    grew = false;
    for (int i = 0; i < nz; ++i) {
      if (!needed[i]) continue;
      for (int j = 0; j < nz; ++j) {
        if (!needed[j] && phi(i, j) != 0.0) needed[j] = grew = true;
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

ExactIntegrator::ExactIntegrator(const LinearPlant& plant, double period_s, int substeps)
    : num_states_(plant.num_states()),
      num_inputs_(plant.num_inputs()),
      num_outputs_(plant.num_outputs()),
      period_s_(period_s),
      substeps_(substeps),
      discretization_(DiscretizeExactly(plant, period_s / substeps)) {
  kept_index_ = StatesReachingOutputs(plant.C, discretization_->phi, num_states_);
  kept_ = static_cast<int>(kept_index_.size());
  const Eigen::MatrixXd a_z = plant.AugmentedA();
  const Eigen::MatrixXd b_z = plant.AugmentedB();
  a_kept_.resize(kept_, kept_);
  b_kept_.resize(kept_, num_inputs_);
  for (int r = 0; r < kept_; ++r) {
    for (int c = 0; c < kept_; ++c) a_kept_(r, c) = a_z(kept_index_[r], kept_index_[c]);
    b_kept_.row(r) = b_z.row(kept_index_[r]);
  }
  KeepPhiAndGamma();
  KeepC(plant.C);
  if (kept_ <= kMaxBlock && num_outputs_ <= kMaxRows) {  // AdvanceBlock: a period at once
    FindDistinctOutputRows();
    PrecomputePeriodProducts();
    block_kernel_ = true;
  }
  z_.assign(kept_, 0.0);
  g_.assign(kept_, 0.0);
  next_.assign(kept_, 0.0);
  accel_.assign(num_inputs_, 0.0);
  Reset(Eigen::VectorXd::Zero(num_inputs_));
}

// phi and gamma over the kept states, dense and row-major; phi also without its zeros.
void ExactIntegrator::KeepPhiAndGamma() {
  const Eigen::MatrixXd& phi = discretization_->phi;
  const Eigen::MatrixXd& gamma = discretization_->gamma;
  phi_.resize(static_cast<std::size_t>(kept_) * kept_);
  gamma_.resize(static_cast<std::size_t>(kept_) * num_inputs_);
  row_start_.push_back(0);
  for (int r = 0; r < kept_; ++r) {
    for (int c = 0; c < kept_; ++c) {
      const double value = phi(kept_index_[r], kept_index_[c]);
      phi_[static_cast<std::size_t>(r) * kept_ + c] = value;
      if (value != 0.0) {
        col_.push_back(c);
        value_.push_back(value);
      }
    }
    row_start_.push_back(static_cast<int>(col_.size()));
    for (int c = 0; c < num_inputs_; ++c) {
      gamma_[static_cast<std::size_t>(r) * num_inputs_ + c] = gamma(kept_index_[r], c);
    }
  }
}

// C over the kept states (the drive velocities have no column in C: 0), dense and
// without its zeros.
void ExactIntegrator::KeepC(const Eigen::MatrixXd& c_full) {
  c_.assign(static_cast<std::size_t>(num_outputs_) * kept_, 0.0);
  for (int o = 0; o < num_outputs_; ++o) {
    for (int c = 0; c < kept_; ++c) {
      if (kept_index_[c] < num_states_) {
        c_[static_cast<std::size_t>(o) * kept_ + c] = c_full(o, kept_index_[c]);
      }
    }
  }
  c_row_start_.push_back(0);
  for (int o = 0; o < num_outputs_; ++o) {
    for (int c = 0; c < kept_; ++c) {
      const double value = c_[static_cast<std::size_t>(o) * kept_ + c];
      if (value != 0.0) {
        c_col_.push_back(c);
        c_value_.push_back(value);
      }
    }
    c_row_start_.push_back(static_cast<int>(c_col_.size()));
  }
}

// The distinct non-zero rows of C (a kinematic axis has the same row for deflection and
// tool error): the block kernel computes each once per substep.
void ExactIntegrator::FindDistinctOutputRows() {
  block_row_of_.assign(num_outputs_, -1);
  for (int o = 0; o < num_outputs_; ++o) {
    if (c_row_start_[o] == c_row_start_[o + 1]) continue;
    for (std::size_t d = 0; d < block_rows_.size() && block_row_of_[o] < 0; ++d) {
      const int first = block_rows_[d];
      if (std::equal(c_.begin() + static_cast<std::ptrdiff_t>(o) * kept_,
                     c_.begin() + static_cast<std::ptrdiff_t>(o + 1) * kept_,
                     c_.begin() + static_cast<std::ptrdiff_t>(first) * kept_)) {
        block_row_of_[o] = static_cast<int>(d);
      }
    }
    if (block_row_of_[o] < 0) {
      block_row_of_[o] = static_cast<int>(block_rows_.size());
      block_rows_.push_back(o);
    }
  }
  block_value_of_ = block_row_of_;
  for (int& d : block_value_of_) {
    if (d < 0) d = static_cast<int>(block_rows_.size());  // the 0 after the rows
  }
  block_selected_value_of_ = block_value_of_;
}

// The period's products for AdvanceBlock: C phi^(j+1) and C gamma_(j+1) per substep j
// over the distinct rows, phi^S and gamma_S; and its scratch.
void ExactIntegrator::PrecomputePeriodProducts() {
  const Eigen::Index k = kept_;
  const Eigen::Index m = num_inputs_;
  const Eigen::Index rows = static_cast<Eigen::Index>(block_rows_.size());
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor phi_k = Eigen::Map<const RowMajor>(phi_.data(), k, k);
  const RowMajor gamma_k = Eigen::Map<const RowMajor>(gamma_.data(), k, m);
  RowMajor c_k(rows, k);
  for (Eigen::Index d = 0; d < rows; ++d) {
    c_k.row(d) = Eigen::Map<const RowMajor>(c_.data() + block_rows_[d] * kept_, 1, k);
  }
  RowMajor power = phi_k;    // phi^j
  RowMajor forced = gamma_k;  // gamma_j
  for (int j = 0; j < substeps_; ++j) {
    if (j > 0) {
      forced = (phi_k * forced + gamma_k).eval();
      power = (phi_k * power).eval();
    }
    const RowMajor c_power = c_k * power;
    const RowMajor c_forced = c_k * forced;
    block_c_phi_.insert(block_c_phi_.end(), c_power.data(), c_power.data() + rows * k);
    block_c_gamma_.insert(block_c_gamma_.end(), c_forced.data(), c_forced.data() + rows * m);
  }
  block_phi_.assign(power.data(), power.data() + k * k);
  block_gamma_.assign(forced.data(), forced.data() + k * m);
  block_forced_.assign(static_cast<std::size_t>(substeps_) * rows, 0.0);
  block_g_.assign(kept_, 0.0);
  block_accel_.assign(num_inputs_, 0.0);
}

void ExactIntegrator::TakeFullInputs(std::vector<int> used, int full_inputs) {
  if (static_cast<int>(used.size()) != num_inputs_) {
    throw std::invalid_argument("ExactIntegrator::TakeFullInputs: one index per plant input");
  }
  input_map_ = std::move(used);
  full_inputs_ = full_inputs;
  picked_.assign(num_inputs_, 0.0);
}

void ExactIntegrator::Reset(const Eigen::VectorXd& drive_velocity) {
  if (drive_velocity.size() != num_inputs()) {
    throw std::invalid_argument("ExactIntegrator::Reset: wrong drive velocity size");
  }
  for (int r = 0; r < kept_; ++r) {
    const int i = kept_index_[r];
    const int input = i - num_states_;
    z_[r] = i < num_states_ ? 0.0
                            : drive_velocity(input_map_.empty() ? input : input_map_[input]);
  }
  std::fill(accel_.begin(), accel_.end(), 0.0);
  std::fill(g_.begin(), g_.end(), 0.0);
  count_ = 0;
  tick_count_ = 0;
  extremum_work_ = 0;
}

void ExactIntegrator::SetAccel(const double* drive_accel) {
  std::copy(drive_accel, drive_accel + num_inputs_, accel_.begin());
  for (int r = 0; r < kept_; ++r) {
    const double* row = gamma_.data() + static_cast<std::size_t>(r) * num_inputs_;
    double sum = 0.0;
    for (int c = 0; c < num_inputs_; ++c) sum += row[c] * drive_accel[c];
    g_[r] = sum;
  }
}

void ExactIntegrator::SetInput(const Eigen::VectorXd& drive_accel) {
  if (drive_accel.size() != num_inputs()) {
    throw std::invalid_argument("ExactIntegrator::SetInput: wrong drive acceleration size");
  }
  SetAccel(Picked(drive_accel.data()));
}

const double* ExactIntegrator::Picked(const double* drive_accel) {
  if (input_map_.empty()) return drive_accel;
  for (int i = 0; i < num_inputs_; ++i) picked_[i] = drive_accel[input_map_[i]];
  return picked_.data();
}

namespace {

// z <- phi z + g for a dense kept_ x kept_ phi of a size known at compile time (a single
// mode: 2 states), summed in column order like the general case.
template <int K>
void StepDense(const double* phi, const double* g, double* z) {
  double next[K];
  for (int i = 0; i < K; ++i) {
    double sum = 0.0;
    for (int j = 0; j < K; ++j) sum += phi[i * K + j] * z[j];
    next[i] = sum + g[i];
  }
  for (int i = 0; i < K; ++i) z[i] = next[i];
}

}  // namespace

void ExactIntegrator::StepState() {
  switch (kept_) {
    case 1: StepDense<1>(phi_.data(), g_.data(), z_.data()); break;
    case 2: StepDense<2>(phi_.data(), g_.data(), z_.data()); break;
    case 3: StepDense<3>(phi_.data(), g_.data(), z_.data()); break;
    case 4: StepDense<4>(phi_.data(), g_.data(), z_.data()); break;
    default:
      // The zeros left out, the same column order (adding exact zeros changes no sum).
      for (int i = 0; i < kept_; ++i) {
        double sum = 0.0;
        for (int e = row_start_[i]; e < row_start_[i + 1]; ++e) sum += value_[e] * z_[col_[e]];
        next_[i] = sum + g_[i];
      }
      z_.swap(next_);
  }
  ++count_;
}

// C z over C's non-zero entries, in column order (the zeros left out change no sum).
void ExactIntegrator::WriteOutputs(double* outputs) const {
  for (int o = 0; o < num_outputs_; ++o) {
    double sum = 0.0;
    for (int e = c_row_start_[o]; e < c_row_start_[o + 1]; ++e) sum += c_value_[e] * z_[c_col_[e]];
    outputs[o] = sum;
  }
}

// The forced part of a small plant's period, once per held acceleration (it changes a
// few times a move).
void ExactIntegrator::ComputeBlockInput(const double* drive_accel) {
  const int m = num_inputs_;
  std::copy(drive_accel, drive_accel + m, block_accel_.begin());
  for (std::size_t i = 0; i < block_forced_.size(); ++i) {
    double sum = 0.0;
    for (int c = 0; c < m; ++c) sum += block_c_gamma_[i * m + c] * drive_accel[c];
    block_forced_[i] = sum;
  }
  for (int i = 0; i < kept_; ++i) {
    double sum = 0.0;
    for (int c = 0; c < m; ++c) sum += block_gamma_[static_cast<std::size_t>(i) * m + c] * drive_accel[c];
    block_g_[i] = sum;
  }
  if (extremum_) block_forced_rate_ = extremum_->ForcedRate(drive_accel);
  block_ready_ = true;
}

// Substep j's outputs are (C phi^(j+1)) z + (C gamma_(j+1)) a, each from the period's
// start state z alone: any range of them, in any order, gives the same bits.
template <int K>
inline void ExactIntegrator::WriteBlockOutputs(const double* z_start, int from, int to, double* outputs) const {
  const int rows = static_cast<int>(block_rows_.size());
  double z[K];
  for (int i = 0; i < K; ++i) z[i] = z_start[i];
  const double* __restrict forced = block_forced_.data() + static_cast<std::ptrdiff_t>(from) * rows;
  const double* __restrict c_phi = block_c_phi_.data() + static_cast<std::ptrdiff_t>(from) * rows * K;
  const int width = output_width();
  const int* __restrict row_of = block_selected_value_of_.data();
  if (block_twin_) {
    // One distinct row asked for twice (a kinematic axis: deflection = tool error).
    double* __restrict out = outputs;
    for (int j = from; j < to; ++j) {
      const double* __restrict row = c_phi + (j - from) * K;
      double sum = 0.0;
      for (int i = 0; i < K; ++i) sum += row[i] * z[i];
      const double value = sum + forced[j - from];
      out[2 * j] = value;
      out[2 * j + 1] = value;
    }
    return;
  }
  for (int j = from; j < to; ++j) {
    double values[kMaxRows + 1];  // the distinct rows of this substep, then a 0
    values[rows] = 0.0;
    for (int d = 0; d < rows; ++d) {
      double sum = 0.0;
      for (int i = 0; i < K; ++i) sum += c_phi[i] * z[i];
      values[d] = sum + forced[d];
      c_phi += K;
    }
    forced += rows;
    double* __restrict out = outputs + static_cast<std::ptrdiff_t>(j) * width;
    if (width == 2) {  // a single axis' deflection and tool error (single_axis_sampler.cc)
      out[0] = values[row_of[0]];
      out[1] = values[row_of[1]];
    } else if (width == 6) {  // a machine's rows (multi_axis_machine.h), unrolled
      out[0] = values[row_of[0]];
      out[1] = values[row_of[1]];
      out[2] = values[row_of[2]];
      out[3] = values[row_of[3]];
      out[4] = values[row_of[4]];
      out[5] = values[row_of[5]];
    } else {
      for (int o = 0; o < width; ++o) out[o] = values[row_of[o]];
    }
  }
}

// The state at the period's end: phi^S z + gamma_S a.
template <int K>
inline void ExactIntegrator::AdvanceBlockState(const double* z) {
  double next[K];
  for (int i = 0; i < K; ++i) {
    double sum = 0.0;
    for (int c = 0; c < K; ++c) sum += block_phi_[i * K + c] * z[c];
    next[i] = sum + block_g_[i];
  }
  for (int i = 0; i < K; ++i) z_[i] = next[i];
  count_ += substeps_;
  tick_count_ = count_;
}

// AdvancePeriod for a small plant of K states: the period from its start state
// (block_* members).
template <int K>
void ExactIntegrator::AdvanceBlock(const double* drive_accel, double* outputs) {
  PrepareBlockInput(drive_accel);
  double z[K];
  for (int i = 0; i < K; ++i) z[i] = z_[i];
  WriteBlockOutputs<K>(z, 0, substeps_, outputs);
  AdvanceBlockState<K>(z);
}

// The extremum's rates at the period's ends from the states in registers (as
// TickExtremum::LargestInside sums them), not reloaded from memory just written.
template <int K>
void ExactIntegrator::AdvanceToEnd(const double* drive_accel, double* outputs) {
  PrepareBlockInput(drive_accel);
  double z[K];
  for (int i = 0; i < K; ++i) z_start_[i] = z[i] = z_[i];
  WriteBlockOutputs<K>(z, substeps_ - 1, substeps_, outputs);
  AdvanceBlockState<K>(z);
  double d0 = 0.0;
  double d1 = 0.0;
  for (int j = 0; j < K; ++j) {
    d0 += extremum_rate_[j] * z[j];
    d1 += extremum_rate_[j] * z_[j];
  }
  d0 += block_forced_rate_;
  d1 += block_forced_rate_;
  period_extremum_ = extremum_->LargestInsideWithRates(z_start_.data(), drive_accel, d0, d1);
  extremum_work_ += extremum_->last_work();
}

void ExactIntegrator::AdvancePeriodToEnd(const double* full_accel, double* outputs) {
  const double* drive_accel = Picked(full_accel);
  switch (kept_) {
    case 1: AdvanceToEnd<1>(drive_accel, outputs); break;
    case 2: AdvanceToEnd<2>(drive_accel, outputs); break;
    case 3: AdvanceToEnd<3>(drive_accel, outputs); break;
    default: AdvanceToEnd<4>(drive_accel, outputs); break;
  }
}

void ExactIntegrator::WriteDeferredSubsteps(double* outputs) const {
  const double* z = z_start_.data();
  switch (kept_) {
    case 1: WriteBlockOutputs<1>(z, 0, substeps_ - 1, outputs); break;
    case 2: WriteBlockOutputs<2>(z, 0, substeps_ - 1, outputs); break;
    case 3: WriteBlockOutputs<3>(z, 0, substeps_ - 1, outputs); break;
    default: WriteBlockOutputs<4>(z, 0, substeps_ - 1, outputs); break;
  }
}

void ExactIntegrator::AdvancePeriod(const double* full_accel, long /*same_input_periods*/,
                                    double* outputs) {
  const double* drive_accel = Picked(full_accel);
  if (!extremum_) {
    AdvanceStates(drive_accel, outputs);
    return;
  }
  std::copy(z_.begin(), z_.end(), z_start_.begin());
  AdvanceStates(drive_accel, outputs);
  period_extremum_ = extremum_->LargestInside(z_start_.data(), z_.data(), drive_accel);
  extremum_work_ += extremum_->last_work();
}

bool ExactIntegrator::WatchExtremum(int row) {
  extremum_.reset();
  if (row < 0 || row >= num_outputs_ || kept_ == 0) return false;
  const Eigen::RowVectorXd c =
      Eigen::Map<const Eigen::RowVectorXd>(c_.data() + static_cast<std::ptrdiff_t>(row) * kept_, kept_);
  extremum_ = TickExtremum::Make(a_kept_, b_kept_, c, period_s_);
  z_start_.assign(kept_, 0.0);
  block_ready_ = false;  // block_forced_rate_ is the watcher's
  if (extremum_) {
    const Eigen::RowVectorXd& rate = extremum_->rate_row();
    extremum_rate_.assign(rate.data(), rate.data() + rate.size());
  }
  period_extremum_ = 0.0;
  return extremum_ != nullptr;
}

// z <- phi^(substeps periods) z (the input 0: no forced part), by squaring.
void ExactIntegrator::AdvanceAtRest(long periods) {
  if (periods < 0) throw std::invalid_argument("ExactIntegrator::AdvanceAtRest: periods < 0");
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor power = Eigen::Map<const RowMajor>(phi_.data(), kept_, kept_);
  Eigen::VectorXd z = Eigen::Map<const Eigen::VectorXd>(z_.data(), kept_);
  for (long e = periods * substeps_; e > 0; e >>= 1) {
    if (e & 1) z = (power * z).eval();
    if (e > 1) power = (power * power).eval();
  }
  std::copy(z.data(), z.data() + kept_, z_.begin());
  count_ += periods * substeps_;
  tick_count_ = count_;
  std::fill(accel_.begin(), accel_.end(), 0.0);
  std::fill(g_.begin(), g_.end(), 0.0);
}

void ExactIntegrator::AdvanceStates(const double* drive_accel, double* outputs) {
  if (block_kernel_ && count_ == tick_count_) {  // at a tick: the period at once
    switch (kept_) {
      case 1: AdvanceBlock<1>(drive_accel, outputs); return;
      case 2: AdvanceBlock<2>(drive_accel, outputs); return;
      case 3: AdvanceBlock<3>(drive_accel, outputs); return;
      case 4: AdvanceBlock<4>(drive_accel, outputs); return;
      default: break;
    }
  }
  SetAccel(drive_accel);
  const int width = output_width();
  std::vector<double>& all = next_outputs_;
  all.resize(num_outputs_);
  for (int j = 0; j < substeps_; ++j) {
    StepState();
    WriteOutputs(all.data());
    WriteSelected(all.data(), outputs + static_cast<std::ptrdiff_t>(j) * width);
  }
}

void ExactIntegrator::SelectOutputs(const std::vector<int>& rows) {
  PlantIntegrator::SelectOutputs(rows);
  if (block_value_of_.empty()) return;
  block_selected_value_of_.clear();
  if (rows.empty()) {
    block_selected_value_of_ = block_value_of_;
  } else {
    for (int r : rows) block_selected_value_of_.push_back(block_value_of_[r]);
  }
  // One distinct row asked for twice (a kinematic axis: deflection = tool error).
  block_twin_ = block_rows_.size() == 1 && block_selected_value_of_.size() == 2 &&
                block_selected_value_of_[0] == 0 && block_selected_value_of_[1] == 0;
}

void ExactIntegrator::Step() { StepState(); }

Eigen::VectorXd ExactIntegrator::Output() const {
  Eigen::VectorXd y(num_outputs_);
  WriteOutputs(y.data());
  return y;
}

Eigen::VectorXd ExactIntegrator::PlantState() const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(num_states_);
  for (int r = 0; r < kept_; ++r) {
    if (kept_index_[r] < num_states_) x(kept_index_[r]) = z_[r];
  }
  return x;
}

double ExactIntegrator::Time() const { return static_cast<double>(count_) * period_s_ / substeps_; }

IntegratorStats ExactIntegrator::Stats() const { return {count_, 0, 0}; }

// Each period with an extremum grid of g steps evaluates y' at its g - 1 inner points at
// least (TickExtremum::Inside); one step costs nothing where no sign change is seen.
long ExactIntegrator::PeriodWorkAtLeast() const {
  return extremum_ ? std::max(0, extremum_->grid_intervals() - 1) : 0;
}

}  // namespace shapebench::model
