// CVODE (SUNDIALS 6.4.1) integrator of a LinearPlant, dense direct linear solver with the
// plant's constant Jacobian. The drive velocity v is integrated with the plant (v' = a) so
// the right-hand side stays smooth within a tick; CVODE is re-initialised only where the
// held acceleration changes. Through AdvancePeriod (the co-simulation master's path) it
// also integrates across the ticks where the acceleration stays the same
// (CvodeInputMode::kContinuous), the output substeps between its internal steps then
// interpolated (CvodeOutput).
//
// CVODE's memory (context, vectors, dense matrix and solver, CVODE's own) is taken from a
// pool of this thread and given back when the integrator is destroyed, so the runs of a
// sweep reuse it (CVodeReInit instead of CVodeCreate and CVodeInit); a run gives the same
// results, bit for bit, on fresh or reused memory (tests/model/cvode_integrator_test.cc).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "model/integrator.h"

namespace shapebench::model {

namespace cvode_detail {
struct Workspace;  // one problem size's CVODE memory (cvode_integrator.cc)
struct WorkspaceReturn {
  void operator()(Workspace* workspace) const;  // back to its pool, or freed
};
}  // namespace cvode_detail

// CVODE's absolute tolerance per state of the augmented state [x; v] (the comment of its
// definition in cvode_integrator.cc says how), shared with the nonlinear integrator.
Eigen::VectorXd CvodeAbsoluteTolerances(const LinearPlant& plant, const IntegratorConfig& config,
                                        double scale_accel_m_s2, double scale_velocity_m_s);

class CvodeIntegrator final : public PlantIntegrator {
 public:
  CvodeIntegrator(const LinearPlant& plant, const IntegratorConfig& config, double period_s,
                  int substeps, double scale_accel_m_s2, double scale_velocity_m_s = 0.0);
  ~CvodeIntegrator() override;
  CvodeIntegrator(const CvodeIntegrator&) = delete;  // CVODE holds a pointer to this
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  void Reset(const Eigen::VectorXd& drive_velocity) override;
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  Eigen::VectorXd PlantState() const override;
  double Time() const override;
  IntegratorStats Stats() const override;
  long Work() const override {
    const IntegratorStats stats = Stats();
    return stats.steps + stats.rhs_evals;
  }
  int num_inputs() const override { return num_inputs_; }
  int num_outputs() const override { return static_cast<int>(C_.rows()); }
  int substeps() const override { return substeps_; }
  IntegratorCapabilities Capabilities() const override {
    IntegratorCapabilities caps;
    caps.input_holds = tuning_.input_mode == CvodeInputMode::kContinuous;
    return caps;
  }
  bool OutputRowIsZero(int row) const override {
    return c_sparse_.row_start[row] == c_sparse_.row_start[row + 1];
  }
  void AdvancePeriod(const double* drive_accel, long same_input_periods,
                     double* outputs) override;

  // Whether this integrator's CVODE memory came from the thread's pool (used before).
  bool reused_memory() const { return reused_; }
  // Output substeps CvodeOutput::kHermite left to CVODE's interpolation (a step too long
  // for the Hermite bound), since construction.
  long cvode_interpolated_substeps() const { return cvode_interpolated_; }

 private:
  static int Rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data);
  static int Jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix jac, void* user_data,
                      N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
  static void RecordError(int code, const char* module, const char* function, char* msg,
                          void* user_data);
  double TimeAt(long count) const;
  void Reinit();
  void SetStopTime(double t_stop);
  void Advance(long count);  // one output substep, to TimeAt(count)
  void AdvanceByHermite(double t_out);
  void SetEnd(int end, double t, const double* y);
  void Check(int flag, const char* call) const;
  void* memory() const;
  Eigen::VectorXd AbsoluteTolerances(const LinearPlant& plant, const IntegratorConfig& config,
                                     double scale_accel_m_s2, double scale_velocity_m_s) const;

  int num_states_;
  int num_inputs_;
  double period_s_;
  int substeps_;
  CvodeTuning tuning_;
  Eigen::MatrixXd C_;
  Eigen::MatrixXd A_z_;  // [[A, B_vel], [0, 0]]: Jacobian of the augmented system
  Eigen::MatrixXd B_z_;  // [B_accel; I]
  Eigen::VectorXd accel_;
  Eigen::VectorXd forcing_;  // B_z accel_, updated where the acceleration changes
  // A_z and C without their zeros (row by row: column, value), for the right-hand side and
  // the outputs, which CVODE and every output substep call for (small: a loop beats a GEMV).
  struct Sparse {
    std::vector<int> row_start;
    std::vector<int> col;
    std::vector<double> value;
    void Assign(const Eigen::MatrixXd& m);
    void Multiply(const double* x, double* y) const;  // y = M x
  };
  Sparse a_sparse_;
  Sparse c_sparse_;
  std::vector<double> all_outputs_;  // scratch: every output of a substep
  bool need_reinit_ = false;  // the held acceleration changed since the last (re)init
  bool stop_set_ = false;     // a stop time is active in CVODE (cleared on reaching it, reinit)
  double stop_s_ = 0.0;
  long count_ = 0;
  // Counters of the runs before the last reinit (CVodeReInit zeroes CVODE's own); reinits
  // counts the restarts at changes of the held acceleration.
  IntegratorStats finished_;
  std::string last_message_;  // CVODE's own words for the last error
  bool reused_ = false;
  // CvodeOutput::kHermite: CVODE's last internal step, [t0, t1], as the state and its first
  // kHermiteOrders - 1 derivatives at either end (ends_: end-major, then derivative, then
  // state); have_step_ false after a (re)start, before the first step.
  static constexpr int kHermiteOrders = 4;
  std::vector<double> ends_;
  double end_time_s_[2] = {0.0, 0.0};
  bool have_step_ = false;
  double hermite_max_step_s_ = 0.0;  // longer steps: CVODE's interpolation
  long max_num_steps_ = 0;           // IntegratorConfig::max_num_steps
  long cvode_interpolated_ = 0;
  std::unique_ptr<cvode_detail::Workspace, cvode_detail::WorkspaceReturn> workspace_;
};

}  // namespace shapebench::model
