// CVODE on a plant with nonlinear elements (model/nonlinear_plant.h, docs/nonlinear.md):
// BDF with Newton's method on the plant's own Jacobian (the friction laws are stiff:
// LuGre's bristles, a stuck element's holding force), solved by blocks (BlockLuSolver: the
// axes are uncoupled), root finding (CVodeRootInit) at the
// elements' switching points (stick and slip, the gap's edges, the force limit), each
// event a restart from the state there with the new modes. Output substeps come from
// CVODE's interpolation (CV_NORMAL). By default (CvodeTuning::split_linear_part) CVODE
// integrates e = z - z_p, z_p the linear part's exact response to the held inputs
// (model/held_input_response.h): the input's jump at every tick stays in z_p, so CVODE's
// history runs on across ticks instead of restarting at each. A separate class from CvodeIntegrator, whose tuned path
// for linear plants (Hermite output, Adams) it leaves as it is.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>

#include "model/cvode_memory.h"
#include "model/held_input_response.h"
#include "model/integrator.h"
#include "model/nonlinear_dynamics.h"
#include "model/nonlinear_plant.h"

namespace shapebench::model {

class NonlinearCvodeIntegrator final : public PlantIntegrator {
 public:
  // As CvodeIntegrator (the tolerances per state from the linear part's static magnitudes,
  // the bristle deflections' from F_s / sigma0); config.lmm and config.tuning are not read:
  // always BDF, the plant's Jacobian, CVODE's interpolation.
  NonlinearCvodeIntegrator(const NonlinearPlant& plant, const IntegratorConfig& config, double period_s,
                           int substeps, double scale_accel_m_s2, double scale_velocity_m_s = 0.0);
  ~NonlinearCvodeIntegrator() override;
  NonlinearCvodeIntegrator(const NonlinearCvodeIntegrator&) = delete;
  NonlinearCvodeIntegrator& operator=(const NonlinearCvodeIntegrator&) = delete;

  void Reset(const Eigen::VectorXd& drive_velocity) override;
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  Eigen::VectorXd PlantState() const override;
  double Time() const override { return TimeAt(count_); }
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
    caps.input_holds = true;
    return caps;
  }
  bool OutputRowIsZero(int row) const override { return C_.row(row).cwiseAbs().maxCoeff() == 0.0; }
  void AdvancePeriod(const double* drive_accel, long same_input_periods, double* outputs) override;

  // The events (root returns) since the last Reset.
  long events() const { return events_; }

 private:
  static int Rhs(double t, N_Vector y, N_Vector ydot, void* user_data);
  static int RootFn(double t, N_Vector y, double* gout, void* user_data);
  static int ErrorWeights(N_Vector y, N_Vector ewt, void* user_data);
  static int LinSys(double t, N_Vector y, N_Vector fy, SUNMatrix a, booleantype jok, booleantype* jcur,
                    double gamma, void* user_data, N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
  static void RecordError(int code, const char* module, const char* function, char* msg, void* user_data);
  double TimeAt(long count) const { return static_cast<double>(count) * period_s_ / substeps_; }
  void ApplyInput(const double* drive_accel);
  // Split mode: z_p to the start of `tick`; the elements' offsets at time t (of that tick).
  void SyncParticular(long tick);
  // Rates only where a stuck element reads them, or `with_rates` (the modes may change).
  void OffsetsAt(double t, bool with_rates = false);
  double TickStart() const { return TimeAt(particular_tick_ * substeps_); }
  // z_p at Time() (split mode).
  Eigen::VectorXd ParticularState() const;
  void Reinit();
  void RestartAt(double t);
  void Advance(long count);
  void AdvanceOneStep(long count);
  void ApplyEvent(N_Vector state, long* events);
  int CallCvode(double t_out, N_Vector out, int mode, double* t_reached);
  static bool OnSubstepEnd(double t_out, double t);
  void Check(int flag, const char* call) const;
  // The motor-position states (NonlinearPlant::following_error_axis): the commanded
  // position at t (the held input integrated exactly from the last change), and CVODE's
  // state y turned into the plant's (e = s - u) in place, or back (`sign` -1, +1).
  double CommandAt(int axis, double t) const;
  void ShiftFollowingErrors(double t, double sign, double* y) const;
  // CVODE's state at t as the plant's (a scratch copy; y itself without such states).
  const double* PlantY(double t, const double* y);
  Eigen::VectorXd AbsoluteTolerances(const NonlinearPlant& plant, const IntegratorConfig& config,
                                     double scale_accel_m_s2, double scale_velocity_m_s) const;

  int num_states_;
  int num_inputs_;
  double period_s_;
  int substeps_;
  Eigen::MatrixXd C_;
  struct OutputEntry {
    int row;
    int column;
    double value;
  };
  std::vector<OutputEntry> c_entries_;  // C_'s entries that are not 0, column by column
  Eigen::MatrixXd B_z_;
  Eigen::VectorXd accel_;
  Eigen::VectorXd all_outputs_;  // scratch: every output of a substep
  NonlinearDynamics dynamics_;
  Eigen::MatrixXd jacobian_;  // the last Jacobian (LinSys), dense, column-major
  std::vector<int> roots_found_;
  bool need_reinit_ = false;
  bool pending_event_ = false;  // a root CVODE found beyond the last output time
  double event_s_ = 0.0;
  bool stop_set_ = false;
  double stop_s_ = 0.0;
  long count_ = 0;
  long events_ = 0;
  IntegratorStats finished_;
  std::string last_message_;
  std::unique_ptr<CvodeMemory> memory_;
  // Split mode (null without it): the linear part's response and the tick it starts.
  std::unique_ptr<HeldInputResponse> particular_;
  long particular_tick_ = 0;

  // Integrated as motor positions: (state, axis) per following error (whole state only).
  std::vector<std::pair<int, int>> lags_;
  std::vector<std::pair<int, int>> velocity_lags_;  // (e' state, axis): integrated as e' + v
  double command_t_ = 0.0;              // when the held input last changed
  Eigen::VectorXd command_position_;    // per axis u then
  Eigen::VectorXd command_velocity_;    // per axis u' then
  std::vector<double> plant_y_;         // scratch: PlantY
  double rtol_ = 0.0;                   // ErrorWeights
  Eigen::VectorXd atol_;

  std::vector<double> probe_values_;
  std::vector<double> probe_rates_;
};

// The integrator of a plant that may have nonlinear elements: MakeIntegrator for a linear
// one; for one with elements CVODE (method cvode or auto), and a ValidationError for
// method exact ("method": the first element named, e.g. machine.axes.y.elements[1]
// (y_guides_friction), and what to use instead).
std::unique_ptr<PlantIntegrator> MakePlantIntegrator(const NonlinearPlant& plant, const IntegratorConfig& config,
                                                     double period_s, int substeps, double scale_accel_m_s2,
                                                     double scale_velocity_m_s = 0.0);

// Throws the ValidationError above when `method` cannot integrate `elements` (exact).
void CheckMethodFitsPlant(IntegratorMethod method, const std::vector<NonlinearElement>& elements);

}  // namespace shapebench::model
