// CVODE (SUNDIALS 6.4.1) integrator of a LinearPlant, dense direct linear solver with the
// plant's constant Jacobian. The drive velocity v is integrated with the plant (v' = a) so
// the right-hand side stays smooth within a tick; CVODE is re-initialised only where the
// held acceleration changes.
#pragma once

#include <memory>
#include <string>
#include <type_traits>

#include <Eigen/Dense>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "model/integrator.h"

namespace shapebench::model {

namespace cvode_detail {
struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver ls) const { SUNLinSolFree(ls); }
};
struct MemoryDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
}  // namespace cvode_detail

class CvodeIntegrator final : public PlantIntegrator {
 public:
  CvodeIntegrator(const LinearPlant& plant, const IntegratorConfig& config, double period_s,
                  int substeps, double scale_accel_m_s2, double scale_velocity_m_s = 0.0);
  CvodeIntegrator(const CvodeIntegrator&) = delete;  // CVODE holds a pointer to this
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  void Reset(const Eigen::VectorXd& drive_velocity) override;
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  double Time() const override;
  IntegratorStats Stats() const override;

 private:
  static int Rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data);
  static int Jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix jac, void* user_data,
                      N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
  static void RecordError(int code, const char* module, const char* function, char* msg,
                          void* user_data);
  double TimeAt(long count) const;
  void Reinit();
  void Check(int flag, const char* call) const;
  Eigen::VectorXd AbsoluteTolerances(const LinearPlant& plant, const IntegratorConfig& config,
                                     double scale_accel_m_s2, double scale_velocity_m_s) const;

  int num_states_;
  int num_inputs_;
  double period_s_;
  int substeps_;
  Eigen::MatrixXd C_;
  Eigen::MatrixXd A_z_;  // [[A, B_vel], [0, 0]]: Jacobian of the augmented system
  Eigen::MatrixXd B_z_;  // [B_accel; I]
  Eigen::VectorXd accel_;
  bool need_reinit_ = false;  // the held acceleration changed since the last (re)init
  long count_ = 0;
  // Counters of the runs before the last reinit (CVodeReInit zeroes CVODE's own); reinits
  // counts the restarts at changes of the held acceleration.
  IntegratorStats finished_;
  std::string last_message_;  // CVODE's own words for the last error

  // Declaration order = reverse destruction order: the context outlives everything.
  std::unique_ptr<std::remove_pointer_t<SUNContext>, cvode_detail::ContextDeleter> context_;
  std::unique_ptr<std::remove_pointer_t<N_Vector>, cvode_detail::VectorDeleter> y_;
  std::unique_ptr<std::remove_pointer_t<N_Vector>, cvode_detail::VectorDeleter> atol_;
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, cvode_detail::MatrixDeleter> matrix_;
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, cvode_detail::LinearSolverDeleter>
      solver_;
  std::unique_ptr<void, cvode_detail::MemoryDeleter> memory_;
};

}  // namespace shapebench::model
