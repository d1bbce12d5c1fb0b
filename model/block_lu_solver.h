// A direct SUNLinearSolver for CVODE's Newton matrix I - gamma J that factors it by blocks:
// the groups of states the Jacobian couples (a machine's axes are uncoupled, so each axis
// with its drive velocity and its elements is a block of its own), each an LU with partial
// pivoting compiled with shapebench's flags. Debian's SUNDIALS 6.4.1 is built
// without optimisation (docs/performance.md): its dense LU of the whole matrix was half of
// a nonlinear run's time.
#pragma once

#include <memory>
#include <vector>

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace shapebench::model {

// Owns the SUNLinearSolver; `blocks` (state indices, disjoint, covering 0..size-1) must hold
// every coupling of the matrices it will be given: entries outside them are ignored.
class BlockLuSolver {
 public:
  BlockLuSolver(SUNContext context, std::vector<std::vector<int>> blocks);
  ~BlockLuSolver();
  BlockLuSolver(const BlockLuSolver&) = delete;
  BlockLuSolver& operator=(const BlockLuSolver&) = delete;

  SUNLinearSolver get() const { return solver_; }

 private:
  struct Factors;
  static int Setup(SUNLinearSolver solver, SUNMatrix matrix);
  static int Solve(SUNLinearSolver solver, SUNMatrix matrix, N_Vector x, N_Vector b, double tol);

  SUNLinearSolver solver_ = nullptr;
  std::unique_ptr<Factors> factors_;
};

}  // namespace shapebench::model
