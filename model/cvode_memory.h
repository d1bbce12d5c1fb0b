// CVODE's memory for one problem, owned in one place for both CVODE integrators (linear:
// cvode_integrator.h, with events: nonlinear_integrator.h): the context, the vectors, the
// corrector's solver and CVODE's own memory, made in the order CVodeInit needs and freed in
// reverse. Also the one spelling of a failed CVODE call (ThrowCvodeFailure).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

namespace shapebench::model {

class BlockLuSolver;

// A SUNContext (used by one thread at a time; a thread's pooled memories share one).
class CvodeContext {
 public:
  CvodeContext();
  ~CvodeContext();
  CvodeContext(const CvodeContext&) = delete;
  CvodeContext& operator=(const CvodeContext&) = delete;

  SUNContext get() const { return context_; }

 private:
  SUNContext context_ = nullptr;
};

// How CVODE solves its corrector equation.
enum class CvodeSolver {
  kDense,       // Newton with SUNDIALS' dense LU (the integrator sets the Jacobian)
  kFixedPoint,  // fixed-point iteration, no matrix
  kBlockLu,     // Newton with BlockLuSolver (the integrator's LinSys fills the matrix)
};

// What a memory is made for; two equal problems may share one memory in turn.
struct CvodeProblem {
  int size = 0;
  bool bdf = true;  // else Adams
  bool optimized_ops = true;  // shapebench's vector kernels (model/serial_vector_ops.h)
  CvodeSolver solver = CvodeSolver::kDense;
  std::vector<std::vector<int>> blocks;  // kBlockLu: the state groups the Jacobian couples

  bool operator==(const CvodeProblem& o) const {
    return size == o.size && bdf == o.bdf && optimized_ops == o.optimized_ops &&
           solver == o.solver && blocks == o.blocks;
  }
};

class CvodeMemory {
 public:
  // CVodeCreate and CVodeInit with `rhs`, the solver attached; user data, tolerances and
  // limits are the integrator's to set.
  CvodeMemory(std::shared_ptr<CvodeContext> context, CvodeProblem problem, CVRhsFn rhs);
  ~CvodeMemory();
  CvodeMemory(const CvodeMemory&) = delete;
  CvodeMemory& operator=(const CvodeMemory&) = delete;

  const CvodeProblem& problem() const { return problem_; }
  void* cvode() const { return cvode_; }
  N_Vector y() const { return y_; }        // the state at the last output time
  N_Vector step() const { return step_; }  // CVode's output in CV_ONE_STEP mode
  N_Vector atol() const { return atol_; }

 private:
  void Free();

  std::shared_ptr<CvodeContext> context_;  // outlives everything below
  CvodeProblem problem_;
  N_Vector y_ = nullptr;
  N_Vector step_ = nullptr;
  N_Vector atol_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver dense_solver_ = nullptr;
  std::unique_ptr<BlockLuSolver> block_solver_;
  SUNNonlinearSolver fixed_point_ = nullptr;
  void* cvode_ = nullptr;
};

// CVODE's own name of a return flag (CV_TOO_MUCH_WORK...).
std::string CvodeFlagName(int flag);

// Throws the SolverError of CVODE's `call` that returned `flag` (< 0) at `t_s`:
// "CVODE failed at t = T s[ on a plant with nonlinear elements (docs/nonlinear.md)]: FLAG:
// what it means and what to change (call: CVODE's own message)".
[[noreturn]] void ThrowCvodeFailure(int flag, const char* call, double t_s,
                                    const std::string& cvode_message, bool nonlinear_plant);

}  // namespace shapebench::model
