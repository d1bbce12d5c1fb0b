// BlockLuSolver against Eigen's dense LU on block-diagonal, sparse matrices like CVODE's
// Newton matrix I - gamma J of a lumped machine (model/block_lu_solver.h).
#include "model/block_lu_solver.h"

#include <random>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace shapebench::model {
namespace {

// Tests that solving by blocks, with the factors' zeros left out of the substitution, gives
// the dense LU's solution (to 1e-12 of it: the two pivot and sum in different orders) on
// interleaved blocks with structural zeros that pivoting must swap rows past.
TEST(BlockLuSolver, SolvesLikeTheDenseLu) {
  SUNContext context = nullptr;
  ASSERT_EQ(SUNContext_Create(nullptr, &context), 0);
  const int n = 9;
  // Interleaved blocks, as the state order of two axes with their bristles.
  const std::vector<std::vector<int>> blocks = {{0, 2, 4, 6, 8}, {1, 3, 5, 7}};
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (const std::vector<int>& block : blocks) {
    for (int r : block) {
      for (int c : block) {
        // About half the couplings absent; a small diagonal, so partial pivoting swaps rows.
        if (r == c) a(r, c) = 1e-3 * uniform(random);
        else if (uniform(random) > 0.0) a(r, c) = uniform(random);
      }
    }
  }
  {
    BlockLuSolver solver(context, blocks);
    SUNMatrix matrix = SUNDenseMatrix(n, n, context);
    N_Vector x = N_VNew_Serial(n, context);
    N_Vector b = N_VNew_Serial(n, context);
    Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(matrix), n, n) = a;
    ASSERT_EQ(SUNLinSolSetup(solver.get(), matrix), SUNLS_SUCCESS);
    for (int trial = 0; trial < 3; ++trial) {
      Eigen::VectorXd rhs(n);
      for (int i = 0; i < n; ++i) rhs(i) = uniform(random);
      Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(b), n) = rhs;
      ASSERT_EQ(SUNLinSolSolve(solver.get(), matrix, x, b, 0.0), SUNLS_SUCCESS);
      const Eigen::VectorXd expected = a.partialPivLu().solve(rhs);
      const Eigen::VectorXd got = Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(x), n);
      EXPECT_LE((got - expected).norm(), 1e-12 * expected.norm()) << "trial " << trial;
    }
    N_VDestroy(b);
    N_VDestroy(x);
    SUNMatDestroy(matrix);
  }
  SUNContext_Free(&context);
}

}  // namespace
}  // namespace shapebench::model
