#include "model/serial_vector_ops.h"

#include <cmath>
#include <stdexcept>

namespace shapebench::model {
namespace {

// The serial vector's content, without the (unoptimised) accessor functions.
inline sunindextype Length(N_Vector v) { return NV_LENGTH_S(v); }
inline realtype* Data(N_Vector v) { return NV_DATA_S(v); }

// z = a x + b y. SUNDIALS factors equal or opposite coefficients out (a (x + y),
// a (x - y)); every other case of its special-casing (a or b of +-1) is the plain formula
// bit for bit, as multiplying by +-1 is exact and rounding is symmetric.
void LinearSum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  const realtype* yd = Data(y);
  realtype* zd = Data(z);
  if (a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}

void Const(realtype c, N_Vector z) {
  const sunindextype n = Length(z);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

void Prod(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  const realtype* yd = Data(y);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

void Scale(realtype c, N_Vector x, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
}

void Abs(N_Vector x, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]);
}

void Inv(N_Vector x, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

void AddConst(N_Vector x, realtype b, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

realtype MaxNorm(N_Vector x) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype max = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    if (std::fabs(xd[i]) > max) max = std::fabs(xd[i]);
  }
  return max;
}

realtype WSqrSumLocal(N_Vector x, N_Vector w) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  const realtype* wd = Data(w);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const realtype product = xd[i] * wd[i];
    sum += product * product;
  }
  return sum;
}

realtype WrmsNorm(N_Vector x, N_Vector w) {
  return std::sqrt(WSqrSumLocal(x, w) / static_cast<realtype>(Length(x)));
}

realtype Min(N_Vector x) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype min = xd[0];
  for (sunindextype i = 1; i < n; ++i) {
    if (xd[i] < min) min = xd[i];
  }
  return min;
}

void Compare(realtype c, N_Vector x, N_Vector z) {
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  realtype* zd = Data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]) >= c ? 1.0 : 0.0;
}

// z = sum_j c_j X_j, accumulated term by term in j's order (j outer, as SUNDIALS does, so
// a z that is also some X_j reads what SUNDIALS' loop reads).
int LinearCombination(int nvec, realtype* c, N_Vector* X, N_Vector z) {
  if (nvec < 1) return -1;
  if (nvec == 1) {
    Scale(c[0], X[0], z);
    return 0;
  }
  if (nvec == 2) {
    LinearSum(c[0], X[0], c[1], X[1], z);
    return 0;
  }
  const sunindextype n = Length(z);
  realtype* zd = Data(z);
  if (X[0] == z) {
    if (c[0] != 1.0) {
      for (sunindextype i = 0; i < n; ++i) zd[i] *= c[0];
    }
  } else {
    const realtype* xd = Data(X[0]);
    for (sunindextype i = 0; i < n; ++i) zd[i] = c[0] * xd[i];
  }
  for (int j = 1; j < nvec; ++j) {
    const realtype* xd = Data(X[j]);
    for (sunindextype i = 0; i < n; ++i) zd[i] += c[j] * xd[i];
  }
  return 0;
}

// Z_j = a_j x + Y_j.
int ScaleAddMulti(int nvec, realtype* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return -1;
  const sunindextype n = Length(x);
  const realtype* xd = Data(x);
  for (int j = 0; j < nvec; ++j) {
    const realtype* yd = Data(Y[j]);
    realtype* zd = Data(Z[j]);
    for (sunindextype i = 0; i < n; ++i) zd[i] = a[j] * xd[i] + yd[i];
  }
  return 0;
}

// Z_j = c_j X_j.
int ScaleVectorArray(int nvec, realtype* c, N_Vector* X, N_Vector* Z) {
  if (nvec < 1) return -1;
  for (int j = 0; j < nvec; ++j) Scale(c[j], X[j], Z[j]);
  return 0;
}

realtype* ArrayPointer(N_Vector v) { return Data(v); }

}  // namespace

void UseOptimizedSerialOps(N_Vector v) {
  if (v == nullptr || v->ops == nullptr || N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL) {
    throw std::invalid_argument("UseOptimizedSerialOps: not a serial N_Vector");
  }
  N_Vector_Ops ops = v->ops;
  ops->nvgetarraypointer = ArrayPointer;
  ops->nvlinearsum = LinearSum;
  ops->nvconst = Const;
  ops->nvprod = Prod;
  ops->nvscale = Scale;
  ops->nvabs = Abs;
  ops->nvinv = Inv;
  ops->nvaddconst = AddConst;
  ops->nvmaxnorm = MaxNorm;
  ops->nvwrmsnorm = WrmsNorm;
  ops->nvmin = Min;
  ops->nvcompare = Compare;
  ops->nvwsqrsumlocal = WSqrSumLocal;
  ops->nvmaxnormlocal = MaxNorm;
  ops->nvminlocal = Min;
  // The fused operations only where the vector has them enabled: CVODE falls back to
  // single operations (ours) when they are null.
  if (ops->nvlinearcombination != nullptr) ops->nvlinearcombination = LinearCombination;
  if (ops->nvscaleaddmulti != nullptr) ops->nvscaleaddmulti = ScaleAddMulti;
  if (ops->nvscalevectorarray != nullptr) ops->nvscalevectorarray = ScaleVectorArray;
}

}  // namespace shapebench::model
