// BlockLuSolver: CVODE calls Setup with I - gamma J whenever it refreshes its Newton matrix
// and Solve at each Newton iteration.
#include "model/block_lu_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace shapebench::model {

// (A named namespace, not the anonymous one: Factors below holds it.)
namespace block_lu_detail {

// Factor's result without its zeros, in Substitute's order: the nonzero multipliers of L
// column by column, the nonzero entries of U above its diagonal row by row. The Newton
// matrix of a lumped machine stays sparse through its LU (a position row is I and -gamma I;
// a body's velocity row reaches its neighbours only), and CVODE solves several times per
// factorisation.
struct Compact {
  std::vector<int> l_start;  // per column k: its multipliers l_index/l_value[l_start[k]..l_start[k+1])
  std::vector<int> l_index;
  std::vector<double> l_value;
  std::vector<int> u_start;  // per row k, the same for U
  std::vector<int> u_index;
  std::vector<double> u_value;
  std::vector<double> inverse_diagonal;
  std::vector<int> pivot;

  explicit Compact(int n)
      : l_start(static_cast<std::size_t>(n + 1)),
        l_index(static_cast<std::size_t>(n * n)),
        l_value(static_cast<std::size_t>(n * n)),
        u_start(static_cast<std::size_t>(n + 1)),
        u_index(static_cast<std::size_t>(n * n)),
        u_value(static_cast<std::size_t>(n * n)),
        inverse_diagonal(static_cast<std::size_t>(n)),
        pivot(static_cast<std::size_t>(n)) {}
};

}  // namespace block_lu_detail

using block_lu_detail::Compact;

namespace {

// LU with partial pivoting of the n x n row-major `a` in place (L unit lower, U upper
// with its diagonal stored as reciprocals), rows swapped as `pivot` records. Plain loops: on the small blocks here (about 10 x 10)
// they beat a general dynamic-size routine's set-up. False on a zero pivot.
bool Factor(double* a, int* pivot, int n) {
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i) {
      if (std::abs(a[i * n + k]) > std::abs(a[p * n + k])) p = i;
    }
    pivot[k] = p;
    if (a[p * n + k] == 0.0) return false;
    if (p != k) {
      for (int j = 0; j < n; ++j) std::swap(a[k * n + j], a[p * n + j]);
    }
    const double inv = 1.0 / a[k * n + k];
    a[k * n + k] = inv;  // kept as its reciprocal: Substitute multiplies
    for (int i = k + 1; i < n; ++i) {
      const double l = a[i * n + k] * inv;
      a[i * n + k] = l;
      if (l == 0.0) continue;
      for (int j = k + 1; j < n; ++j) a[i * n + j] -= l * a[k * n + j];
    }
  }
  return true;
}


void Compress(const double* a, int n, Compact& c) {
  int l = 0;
  int u = 0;
  c.l_start[0] = 0;
  c.u_start[0] = 0;
  for (int k = 0; k < n; ++k) {
    for (int i = k + 1; i < n; ++i) {
      const double value = a[i * n + k];
      if (value != 0.0) {
        c.l_index[l] = i;
        c.l_value[l++] = value;
      }
    }
    c.l_start[k + 1] = l;
    for (int j = k + 1; j < n; ++j) {
      const double value = a[k * n + j];
      if (value != 0.0) {
        c.u_index[u] = j;
        c.u_value[u++] = value;
      }
    }
    c.u_start[k + 1] = u;
    c.inverse_diagonal[k] = a[k * n + k];
  }
}

// Solves with Factor's result (compressed), x in place. The terms left out are exact zeros:
// the dense loops' values (x - 0 y is x for finite y; a zero result may differ in sign).
void Substitute(const Compact& c, int n, double* x) {
  // The rows were swapped whole (L's multipliers with them): P first, then L, then U.
  for (int k = 0; k < n; ++k) {
    if (c.pivot[k] != k) std::swap(x[k], x[c.pivot[k]]);
  }
  for (int k = 0; k < n; ++k) {
    const double xk = x[k];
    for (int p = c.l_start[k]; p < c.l_start[k + 1]; ++p) x[c.l_index[p]] -= c.l_value[p] * xk;
  }
  for (int k = n - 1; k >= 0; --k) {
    double sum = x[k];
    for (int p = c.u_start[k]; p < c.u_start[k + 1]; ++p) sum -= c.u_value[p] * x[c.u_index[p]];
    x[k] = sum * c.inverse_diagonal[k];
  }
}

}  // namespace

struct BlockLuSolver::Factors {
  std::vector<std::vector<int>> blocks;
  std::vector<std::vector<double>> lu;  // each block's matrix, row-major, then its LU in place
  std::vector<Compact> compact;         // each block's LU without its zeros (Solve's)
  std::vector<double> scratch;
};

BlockLuSolver::BlockLuSolver(SUNContext context, std::vector<std::vector<int>> blocks)
    : factors_(std::make_unique<Factors>()) {
  std::size_t largest = 0;
  for (const std::vector<int>& block : blocks) {
    factors_->lu.emplace_back(block.size() * block.size());
    factors_->compact.emplace_back(static_cast<int>(block.size()));
    largest = std::max(largest, block.size());
  }
  factors_->scratch.resize(largest);
  factors_->blocks = std::move(blocks);
  solver_ = SUNLinSolNewEmpty(context);
  if (solver_ == nullptr) throw std::bad_alloc();
  solver_->content = factors_.get();
  solver_->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  solver_->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  solver_->ops->setup = Setup;
  solver_->ops->solve = Solve;
}

BlockLuSolver::~BlockLuSolver() { SUNLinSolFreeEmpty(solver_); }

int BlockLuSolver::Setup(SUNLinearSolver solver, SUNMatrix matrix) {
  Factors& f = *static_cast<Factors*>(solver->content);
  const double* a = SUNDenseMatrix_Data(matrix);  // column-major
  const sunindextype rows = SUNDenseMatrix_Rows(matrix);
  for (std::size_t k = 0; k < f.blocks.size(); ++k) {
    const std::vector<int>& block = f.blocks[k];
    const int n = static_cast<int>(block.size());
    double* m = f.lu[k].data();
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) m[r * n + c] = a[block[c] * rows + block[r]];
    }
    // A singular block fails the setup: CVODE then shrinks the step.
    if (!Factor(m, f.compact[k].pivot.data(), n)) return SUNLS_LUFACT_FAIL;
    Compress(m, n, f.compact[k]);
  }
  return SUNLS_SUCCESS;
}

int BlockLuSolver::Solve(SUNLinearSolver solver, SUNMatrix /*matrix*/, N_Vector x, N_Vector b, double /*tol*/) {
  Factors& f = *static_cast<Factors*>(solver->content);
  const double* in = N_VGetArrayPointer(b);
  double* out = N_VGetArrayPointer(x);
  double* v = f.scratch.data();
  for (std::size_t k = 0; k < f.blocks.size(); ++k) {
    const std::vector<int>& block = f.blocks[k];
    const int n = static_cast<int>(block.size());
    for (int i = 0; i < n; ++i) v[i] = in[block[i]];
    Substitute(f.compact[k], n, v);
    for (int i = 0; i < n; ++i) out[block[i]] = v[i];
  }
  return SUNLS_SUCCESS;
}

}  // namespace shapebench::model
