// The oracle integrator: exact discretisation of the linear plant under an acceleration
// held over each substep (zero-order hold on a, so the drive velocity v is a ramp).
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "model/integrator.h"
#include "model/tick_extremum.h"

namespace shapebench::model {

// z+ = phi z + gamma a over one substep h, z = [x; v] (LinearPlant::AugmentedA/B).
struct ExactDiscretization {
  Eigen::MatrixXd phi;
  Eigen::MatrixXd gamma;
};

// Van Loan's block exponential, balanced. The last few results are kept per thread and
// handed out again for the same (AugmentedA, AugmentedB, h), exactly equal: the runs of a
// sweep whose plant does not change (feed, pattern, acc/dec time...) compute it once.
std::shared_ptr<const ExactDiscretization> DiscretizeExactly(const LinearPlant& plant, double h);

class ExactIntegrator final : public PlantIntegrator {
 public:
  ExactIntegrator(const LinearPlant& plant, double period_s, int substeps);

  void Reset(const Eigen::VectorXd& drive_velocity) override;
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  // States it does not step (they reach no output) are given as 0: they change no output.
  Eigen::VectorXd PlantState() const override;
  double Time() const override;
  IntegratorStats Stats() const override;
  long Work() const override { return extremum_work_; }
  long PeriodWorkAtLeast() const override;
  int num_inputs() const override { return input_map_.empty() ? num_inputs_ : full_inputs_; }
  int num_outputs() const override { return num_outputs_; }
  int substeps() const override { return substeps_; }
  void AdvancePeriod(const double* drive_accel, long same_input_periods,
                     double* outputs) override;
  void SelectOutputs(const std::vector<int>& rows) override;
  // Deferred substeps on a small plant (the block kernel computes each substep from the
  // period's start state, so the inner ones can come later, the same bits).
  IntegratorCapabilities Capabilities() const override {
    IntegratorCapabilities caps;
    caps.period_extremum = true;
    caps.advance_at_rest = true;
    caps.deferred_substeps = block_kernel_;
    return caps;
  }
  bool WatchExtremum(int row) override;
  double PeriodExtremum() const override { return period_extremum_; }
  void AdvanceAtRest(long periods) override;
  void AdvancePeriodToEnd(const double* drive_accel, double* outputs) override;
  void WriteDeferredSubsteps(double* outputs) const override;

  // Built on a plant reduced to the inputs `used` (MakeIntegrator), it takes the full
  // input vectors (`full_inputs` values) and picks those itself: no wrapper per call.
  void TakeFullInputs(std::vector<int> used, int full_inputs);

  bool OutputRowIsZero(int row) const override {
    return c_row_start_[row] == c_row_start_[row + 1];
  }

  // How many of the augmented states the integrator steps: those that reach an output
  // (through C or through other such states); the rest (e.g. the drive velocity of a plant
  // with B_vel = 0) are left out, which changes no output.
  int num_stepped_states() const { return kept_; }

 private:
  // Construction, in this order.
  void KeepPhiAndGamma();
  void KeepC(const Eigen::MatrixXd& c_full);
  void FindDistinctOutputRows();    // a small plant only
  void PrecomputePeriodProducts();  // a small plant only

  void SetAccel(const double* drive_accel);
  const double* Picked(const double* drive_accel);  // the plant's inputs of a full vector
  void StepState();
  void WriteOutputs(double* outputs) const;
  template <int K>
  void AdvanceBlock(const double* drive_accel, double* outputs);
  // The forced part for drive_accel, unless it is the one held already.
  void PrepareBlockInput(const double* drive_accel) {
    if (!block_ready_ || !std::equal(drive_accel, drive_accel + num_inputs_, block_accel_.begin())) {
      ComputeBlockInput(drive_accel);
    }
  }
  void ComputeBlockInput(const double* drive_accel);
  // Substeps [from, to) of the period that starts at z, written to outputs + j * width.
  template <int K>
  [[gnu::always_inline]] void WriteBlockOutputs(const double* z, int from, int to, double* outputs) const;
  template <int K>
  [[gnu::always_inline]] void AdvanceBlockState(const double* z);
  template <int K>
  void AdvanceToEnd(const double* drive_accel, double* outputs);
  void AdvanceStates(const double* drive_accel, double* outputs);

  int num_states_;
  int num_inputs_;
  int num_outputs_;
  double period_s_;
  int substeps_;
  std::shared_ptr<const ExactDiscretization> discretization_;
  // The stepped states: indices into z, and row-major blocks of phi, gamma and C over them.
  int kept_ = 0;
  std::vector<int> kept_index_;
  std::vector<double> phi_;    // kept_ x kept_
  std::vector<double> gamma_;  // kept_ x num_inputs_
  std::vector<double> c_;      // num_outputs_ x kept_
  // C without its zeros: per output row, its (column, value) entries; rows without any
  // are written as 0.
  std::vector<int> c_row_start_;
  std::vector<int> c_col_;
  std::vector<double> c_value_;
  // phi_ without its zeros (CSR), for the larger, block-diagonal plants of several axes.
  std::vector<int> row_start_;
  std::vector<int> col_;
  std::vector<double> value_;
  // A small plant (kept_ <= kMaxBlock) advances a whole period from its start state: the
  // outputs of substep j are (C phi^j) z + (C gamma_j) a with gamma_j = sum_{i<j} phi^i
  // gamma, the state at its end phi^S z + gamma_S a. Independent products instead of a
  // chain of S dependent steps (the same discretisation; rounding differs from Step's).
  static constexpr int kMaxBlock = 4;
  static constexpr int kMaxRows = 8;  // and at most this many outputs
  std::vector<int> block_rows_;      // the distinct non-zero output rows (their first row)
  std::vector<int> block_row_of_;    // per output row: its index in block_rows_, or -1
  std::vector<int> block_value_of_;  // the same, with block_rows_.size() (a 0) for -1
  std::vector<int> block_selected_value_of_;  // block_value_of_ of the selected rows
  std::vector<double> next_outputs_;  // scratch: all outputs of a substep
  std::vector<double> block_c_phi_;  // [j][row][kept_]: C phi^(j+1)
  std::vector<double> block_c_gamma_;  // [j][row][num_inputs_]: C gamma_(j+1)
  std::vector<double> block_phi_;    // phi^S, kept_ x kept_
  std::vector<double> block_gamma_;  // gamma_S, kept_ x num_inputs_
  std::vector<double> block_forced_;  // [j][row]: C gamma_(j+1) a for the last a
  std::vector<double> block_g_;       // gamma_S a for the last a
  std::vector<double> block_accel_;   // that a
  bool block_ready_ = false;          // block_forced_ and block_g_ hold block_accel_'s
  std::vector<double> z_;      // kept_
  std::vector<double> g_;      // gamma a, for the held a
  std::vector<double> next_;   // scratch
  std::vector<double> accel_;  // num_inputs_
  std::vector<int> input_map_;     // TakeFullInputs: plant input i is full input input_map_[i]
  int full_inputs_ = 0;
  std::vector<double> picked_;     // scratch: the picked inputs
  // WatchExtremum: the kept states' augmented a and b, the watcher, the period's start.
  Eigen::MatrixXd a_kept_;
  Eigen::MatrixXd b_kept_;
  std::unique_ptr<TickExtremum> extremum_;
  std::vector<double> extremum_rate_;  // its rate_row(), for AdvanceToEnd
  double block_forced_rate_ = 0.0;     // its ForcedRate of block_accel_
  std::vector<double> z_start_;
  double period_extremum_ = 0.0;
  long count_ = 0;
  long extremum_work_ = 0;     // TickExtremum::last_work() summed (Work())
  long tick_count_ = 0;        // count_ at the last tick AdvanceBlock ended on
  bool block_kernel_ = false;  // the block_* members are set up (a small plant)
  bool block_twin_ = false;    // the selection is one distinct row, twice
};

}  // namespace shapebench::model
