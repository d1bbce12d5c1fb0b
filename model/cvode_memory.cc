#include "model/cvode_memory.h"

#include <cstdlib>
#include <new>
#include <sstream>
#include <stdexcept>

#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "model/block_lu_solver.h"
#include "model/integrator.h"
#include "model/serial_vector_ops.h"

namespace shapebench::model {
namespace {

std::string PlainWords(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return "integrator.max_num_steps internal steps were not enough to reach the next "
             "output time; raise integrator.max_num_steps or loosen integrator.rtol";
    case CV_TOO_MUCH_ACC:
      return "the accuracy asked for is below what double precision can deliver; loosen "
             "integrator.rtol or raise integrator.atol_scale";
    case CV_ERR_FAILURE:
      return "the local error test failed repeatedly (step size hit its minimum)";
    case CV_CONV_FAILURE:
      return "the corrector iteration failed to converge repeatedly";
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
      return "the dense linear solver failed (singular iteration matrix)";
    case CV_ILL_INPUT:
      return "CVODE rejected an input (see its message)";
    default:
      return "see the CVODE documentation for this flag";
  }
}

}  // namespace

CvodeContext::CvodeContext() {
  if (SUNContext_Create(nullptr, &context_) != 0 || context_ == nullptr) throw std::bad_alloc();
}

CvodeContext::~CvodeContext() { SUNContext_Free(&context_); }

CvodeMemory::CvodeMemory(std::shared_ptr<CvodeContext> context, CvodeProblem problem, CVRhsFn rhs)
    : context_(std::move(context)), problem_(std::move(problem)) {
  // The members made so far are freed if a later step throws (no destructor runs then).
  try {
    SUNContext ctx = context_->get();
    const int n = problem_.size;
    y_ = N_VNew_Serial(n, ctx);
    step_ = N_VNew_Serial(n, ctx);
    atol_ = N_VNew_Serial(n, ctx);
    cvode_ = CVodeCreate(problem_.bdf ? CV_BDF : CV_ADAMS, ctx);
    if (y_ == nullptr || step_ == nullptr || atol_ == nullptr || cvode_ == nullptr) {
      throw std::bad_alloc();
    }
    N_VConst(0.0, y_);
    // Fused vector operations (one pass for a linear combination instead of one call per
    // term): CVODE clones its vectors from y, so they all get them. Its interpolation
    // (CVodeGetDky, a combination of q + 1 history vectors) and its history updates use them.
    if (N_VEnableFusedOps_Serial(y_, SUNTRUE) != 0) throw std::runtime_error("N_VEnableFusedOps failed");
    // Before CVodeInit, which clones its vectors from y.
    if (problem_.optimized_ops) {
      UseOptimizedSerialOps(y_);
      UseOptimizedSerialOps(step_);
    }
    if (CVodeInit(cvode_, rhs, 0.0, y_) != CV_SUCCESS) throw std::runtime_error("CVodeInit failed");
    if (problem_.solver == CvodeSolver::kFixedPoint) {
      fixed_point_ = SUNNonlinSol_FixedPoint(y_, 0, ctx);
      if (fixed_point_ == nullptr || CVodeSetNonlinearSolver(cvode_, fixed_point_) != CV_SUCCESS) {
        throw std::runtime_error("CVodeSetNonlinearSolver failed");
      }
      return;
    }
    matrix_ = SUNDenseMatrix(n, n, ctx);
    if (matrix_ == nullptr) throw std::bad_alloc();
    SUNLinearSolver solver = nullptr;
    if (problem_.solver == CvodeSolver::kBlockLu) {
      block_solver_ = std::make_unique<BlockLuSolver>(ctx, problem_.blocks);
      solver = block_solver_->get();
    } else {
      solver = dense_solver_ = SUNLinSol_Dense(y_, matrix_, ctx);
    }
    if (solver == nullptr || CVodeSetLinearSolver(cvode_, solver, matrix_) != CVLS_SUCCESS) {
      throw std::runtime_error("CVodeSetLinearSolver failed");
    }
  } catch (...) {
    Free();
    throw;
  }
}

CvodeMemory::~CvodeMemory() { Free(); }

// CVODE's memory first: it refers to the solvers and vectors.
void CvodeMemory::Free() {
  CVodeFree(&cvode_);
  if (fixed_point_ != nullptr) SUNNonlinSolFree(fixed_point_);
  fixed_point_ = nullptr;
  block_solver_.reset();
  if (dense_solver_ != nullptr) SUNLinSolFree(dense_solver_);
  dense_solver_ = nullptr;
  if (matrix_ != nullptr) SUNMatDestroy(matrix_);
  matrix_ = nullptr;
  for (N_Vector* v : {&atol_, &step_, &y_}) {
    if (*v != nullptr) N_VDestroy(*v);
    *v = nullptr;
  }
}

std::string CvodeFlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by CVODE
  std::string result = name != nullptr ? name : "CV_UNKNOWN";
  std::free(name);
  return result;
}

void ThrowCvodeFailure(int flag, const char* call, double t_s, const std::string& cvode_message,
                       bool nonlinear_plant) {
  std::ostringstream what;
  const std::string name = CvodeFlagName(flag);
  what << "CVODE failed at t = " << t_s << " s";
  if (nonlinear_plant) what << " on a plant with nonlinear elements (docs/nonlinear.md)";
  what << ": " << name << ": " << PlainWords(flag) << " (" << call;
  if (!cvode_message.empty()) what << ": " << cvode_message;
  what << ")";
  throw SolverError(name, what.str());
}

}  // namespace shapebench::model
