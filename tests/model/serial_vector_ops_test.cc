// shapebench's serial vector kernels against SUNDIALS' own (N_V*_Serial), bit for bit: the
// replacement changes the speed of CVODE's steps, never a result.
#include "model/serial_vector_ops.h"

#include <cstring>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sundials/sundials_context.h>

namespace shapebench::model {
namespace {

struct ContextFree {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorDestroy {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
using Vector = std::unique_ptr<_generic_N_Vector, VectorDestroy>;

// The same numbers in two vectors: one with SUNDIALS' kernels, one with shapebench's.
class SerialVectorOps : public testing::TestWithParam<int> {
 protected:
  SerialVectorOps() {
    SUNContext raw = nullptr;
    if (SUNContext_Create(nullptr, &raw) != 0) throw std::runtime_error("SUNContext_Create");
    context_.reset(raw);
  }
  // `count` vectors of length GetParam() holding random numbers (and a 0 and a -0 for the
  // lengths that have room), with fused operations enabled; `optimized`: our kernels.
  std::vector<Vector> Make(int count, bool optimized) {
    std::mt19937_64 random(42);  // the same numbers for both sets
    std::uniform_real_distribution<double> uniform(-3.0, 3.0);
    std::vector<Vector> vectors;
    for (int v = 0; v < count; ++v) {
      Vector vector(N_VNew_Serial(GetParam(), context_.get()));
      N_VEnableFusedOps_Serial(vector.get(), SUNTRUE);
      if (optimized) UseOptimizedSerialOps(vector.get());
      double* data = N_VGetArrayPointer(vector.get());
      for (int i = 0; i < GetParam(); ++i) data[i] = uniform(random);
      if (GetParam() > 2 && v == 1) {
        data[0] = 0.0;
        data[1] = -0.0;
      }
      vectors.push_back(std::move(vector));
    }
    return vectors;
  }
  static std::vector<N_Vector> Raw(const std::vector<Vector>& vectors) {
    std::vector<N_Vector> raw;
    for (const Vector& v : vectors) raw.push_back(v.get());
    return raw;
  }
  // Bit-for-bit equality of every element of every vector.
  static void ExpectSameBits(const std::vector<Vector>& a, const std::vector<Vector>& b,
                             const std::string& what) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t v = 0; v < a.size(); ++v) {
      const double* x = N_VGetArrayPointer(a[v].get());
      const double* y = N_VGetArrayPointer(b[v].get());
      for (sunindextype i = 0; i < N_VGetLength(a[v].get()); ++i) {
        EXPECT_EQ(std::memcmp(&x[i], &y[i], sizeof(double)), 0)
            << what << ": vector " << v << "[" << i << "] " << x[i] << " vs " << y[i];
      }
    }
  }
  static bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

  std::unique_ptr<_SUNContext, ContextFree> context_;
};

// The coefficient pairs SUNDIALS' linear sum special-cases (+-1, equal, opposite, 0) and
// plain ones.
const std::vector<std::pair<double, double>>& CoefficientPairs() {
  static const std::vector<std::pair<double, double>> pairs = {
      {1.0, 1.0},  {1.0, -1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, 0.37}, {0.37, 1.0},
      {-1.0, 0.37}, {0.37, -1.0}, {2.5, 2.5}, {2.5, -2.5}, {0.0, 0.0},  {0.3, -1.7}};
  return pairs;
}

// Tests that the linear sum gives SUNDIALS' bits for every special case of coefficients and
// for each aliasing CVODE uses (z is x, z is y, z apart).
TEST_P(SerialVectorOps, LinearSumMatchesSundials) {
  for (const auto& [a, b] : CoefficientPairs()) {
    for (int alias = 0; alias < 3; ++alias) {
      std::vector<Vector> ours = Make(3, true);
      std::vector<Vector> theirs = Make(3, false);
      auto run = [&](std::vector<Vector>& v) {
        N_Vector z = alias == 0 ? v[2].get() : alias == 1 ? v[0].get() : v[1].get();
        N_VLinearSum(a, v[0].get(), b, v[1].get(), z);
      };
      run(ours);
      run(theirs);
      ExpectSameBits(ours, theirs, "N_VLinearSum(" + std::to_string(a) + ", " +
                                       std::to_string(b) + ") alias " + std::to_string(alias));
    }
  }
}

// Tests the element-wise operations and the reductions against SUNDIALS' bits.
TEST_P(SerialVectorOps, ElementwiseAndReductionsMatchSundials) {
  std::vector<Vector> ours = Make(4, true);
  std::vector<Vector> theirs = Make(4, false);
  auto both = [&](const std::string& what, auto op) {
    op(ours);
    op(theirs);
    ExpectSameBits(ours, theirs, what);
  };
  both("N_VScale", [](auto& v) { N_VScale(-0.7, v[0].get(), v[3].get()); });
  both("N_VScale in place", [](auto& v) { N_VScale(1.3, v[3].get(), v[3].get()); });
  both("N_VScale by 1", [](auto& v) { N_VScale(1.0, v[1].get(), v[3].get()); });
  both("N_VScale by -1", [](auto& v) { N_VScale(-1.0, v[1].get(), v[3].get()); });
  both("N_VProd", [](auto& v) { N_VProd(v[0].get(), v[1].get(), v[3].get()); });
  both("N_VAbs", [](auto& v) { N_VAbs(v[1].get(), v[3].get()); });
  both("N_VInv", [](auto& v) { N_VInv(v[0].get(), v[3].get()); });
  both("N_VAddConst", [](auto& v) { N_VAddConst(v[0].get(), 0.125, v[3].get()); });
  both("N_VCompare", [](auto& v) { N_VCompare(1.1, v[0].get(), v[3].get()); });
  both("N_VConst", [](auto& v) { N_VConst(2.75, v[3].get()); });
  EXPECT_TRUE(SameBits(N_VWrmsNorm(ours[0].get(), ours[1].get()),
                       N_VWrmsNorm(theirs[0].get(), theirs[1].get())));
  EXPECT_TRUE(SameBits(N_VWSqrSumLocal(ours[0].get(), ours[2].get()),
                       N_VWSqrSumLocal(theirs[0].get(), theirs[2].get())));
  EXPECT_TRUE(SameBits(N_VMaxNorm(ours[1].get()), N_VMaxNorm(theirs[1].get())));
  EXPECT_TRUE(SameBits(N_VMaxNormLocal(ours[1].get()), N_VMaxNormLocal(theirs[1].get())));
  EXPECT_TRUE(SameBits(N_VMin(ours[2].get()), N_VMin(theirs[2].get())));
  EXPECT_TRUE(SameBits(N_VMinLocal(ours[2].get()), N_VMinLocal(theirs[2].get())));
  EXPECT_EQ(N_VGetArrayPointer(ours[0].get()), NV_DATA_S(ours[0].get()));
}

// Tests the fused operations CVODE uses (the interpolation's linear combination, the
// history update's scale-add, the rescaling's scaled array), in place and apart, for 1 to
// 4 terms.
TEST_P(SerialVectorOps, FusedOperationsMatchSundials) {
  double c[4] = {1.0, -0.3, 2.0, -1.0};
  for (int terms = 1; terms <= 4; ++terms) {
    for (bool in_place : {false, true}) {
      for (double first : {1.0, 0.6}) {
        c[0] = first;
        // v0 (x), v1..v4 (Y, or the combined terms), v5..v8 (Z, apart from Y).
        std::vector<Vector> ours = Make(9, true);
        std::vector<Vector> theirs = Make(9, false);
        auto combine = [&](std::vector<Vector>& v) {
          std::vector<N_Vector> x = Raw(v);
          N_Vector z = in_place ? x[0] : x[8];
          EXPECT_EQ(N_VLinearCombination(terms, c, x.data(), z), 0);
        };
        combine(ours);
        combine(theirs);
        ExpectSameBits(ours, theirs, "N_VLinearCombination of " + std::to_string(terms));
        auto scale_add = [&](std::vector<Vector>& v) {
          std::vector<N_Vector> x = Raw(v);
          std::vector<N_Vector> y(x.begin() + 1, x.begin() + 1 + terms);
          std::vector<N_Vector> z(x.begin() + 5, x.begin() + 5 + terms);
          EXPECT_EQ(N_VScaleAddMulti(terms, c, x[0], y.data(), in_place ? y.data() : z.data()), 0);
        };
        scale_add(ours);
        scale_add(theirs);
        ExpectSameBits(ours, theirs, "N_VScaleAddMulti of " + std::to_string(terms));
        auto scale_array = [&](std::vector<Vector>& v) {
          std::vector<N_Vector> x = Raw(v);
          std::vector<N_Vector> in(x.begin(), x.begin() + terms);
          std::vector<N_Vector> out = in;
          if (!in_place) out.assign(x.begin() + 5, x.begin() + 5 + terms);
          EXPECT_EQ(N_VScaleVectorArray(terms, c, in.data(), out.data()), 0);
        };
        scale_array(ours);
        scale_array(theirs);
        ExpectSameBits(ours, theirs, "N_VScaleVectorArray of " + std::to_string(terms));
      }
    }
  }
}

// Tests that CVODE's vectors, cloned from a vector with our kernels, have them too, and that
// a vector other than a serial one is refused.
TEST_P(SerialVectorOps, ClonesInheritTheKernels) {
  std::vector<Vector> ours = Make(1, true);
  const Vector clone(N_VClone(ours[0].get()));
  EXPECT_EQ(clone->ops->nvlinearsum, ours[0]->ops->nvlinearsum);
  std::vector<Vector> theirs = Make(1, false);
  EXPECT_NE(clone->ops->nvlinearsum, theirs[0]->ops->nvlinearsum);
  EXPECT_THROW(UseOptimizedSerialOps(nullptr), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Lengths, SerialVectorOps, testing::Values(1, 2, 3, 7, 31),
                         [](const testing::TestParamInfo<int>& info) {
                           return "N" + std::to_string(info.param);
                         });

}  // namespace
}  // namespace shapebench::model
