#include "common/sample_math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace shapebench {
namespace {

// Joe & Kuo's new-joe-kuo-6.21201, dimensions 2..16 (dimension 1 is van der Corput's): the
// primitive polynomial with its leading and trailing 1 bits (degree s = bit length - 1,
// the middle bits the coefficients a), then the initial direction numbers m_1..m_s.
struct SobolRow {
  std::uint32_t polynomial;
  std::array<std::uint32_t, 6> m;
};
constexpr SobolRow kSobolRows[kSobolDimensions - 1] = {
    {3, {1}},           {7, {1, 3}},           {11, {1, 3, 1}},        {13, {1, 1, 1}},
    {19, {1, 1, 3, 3}}, {25, {1, 3, 5, 13}},   {37, {1, 1, 5, 5, 17}}, {41, {1, 1, 5, 5, 5}},
    {47, {1, 1, 7, 11, 19}}, {55, {1, 1, 5, 1, 1}}, {59, {1, 1, 1, 3, 11}}, {61, {1, 3, 5, 5, 31}},
    {67, {1, 3, 3, 9, 7, 49}}, {91, {1, 1, 1, 15, 21, 21}}, {97, {1, 3, 1, 13, 27, 49}},
};

using Directions = std::array<std::uint32_t, 32>;

Directions MakeDirections(int dimension) {
  Directions v{};
  if (dimension == 0) {
    for (int k = 0; k < 32; ++k) v[k] = 1u << (31 - k);
    return v;
  }
  const SobolRow& row = kSobolRows[dimension - 1];
  int s = 0;
  while ((row.polynomial >> (s + 1)) != 0) ++s;
  const std::uint32_t a = (row.polynomial >> 1) & ((1u << (s - 1)) - 1u);
  for (int k = 0; k < 32; ++k) {
    if (k < s) {
      v[k] = row.m[k] << (31 - k);
      continue;
    }
    v[k] = v[k - s] ^ (v[k - s] >> s);
    for (int i = 1; i < s; ++i) {
      if ((a >> (s - 1 - i)) & 1u) v[k] ^= v[k - i];
    }
  }
  return v;
}

const std::vector<Directions>& AllDirections() {
  static const std::vector<Directions> all = [] {
    std::vector<Directions> table;
    for (int d = 0; d < kSobolDimensions; ++d) table.push_back(MakeDirections(d));
    return table;
  }();
  return all;
}

double Polynomial(const double* c, double r) {
  double sum = c[7];
  for (int i = 6; i >= 0; --i) sum = sum * r + c[i];
  return sum;
}

// log P(B = k) for B ~ Bin(n, q), 0 < q < 1.
double LogBinomialTerm(std::uint64_t n, std::uint64_t k, double q) {
  const double nd = static_cast<double>(n);
  const double kd = static_cast<double>(k);
  return std::lgamma(nd + 1.0) - std::lgamma(kd + 1.0) - std::lgamma(nd - kd + 1.0) + kd * std::log(q) +
         (nd - kd) * std::log1p(-q);
}

}  // namespace

std::uint64_t Mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t CounterWord(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return Mix64(Mix64(Mix64(seed) ^ stream) ^ index);
}

double CounterUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return (static_cast<double>(CounterWord(seed, stream, index) >> 11) + 0.5) * 0x1.0p-53;
}

double InverseNormalCdf(double p) {
  static const double a[8] = {3.3871328727963666080e0, 1.3314166789178437745e+2, 1.9715909503065514427e+3,
                              1.3731693765509461125e+4, 4.5921953931549871457e+4, 6.7265770927008700853e+4,
                              3.3430575583588128105e+4, 2.5090809287301226727e+3};
  static const double b[8] = {1.0, 4.2313330701600911252e+1, 6.8718700749205790830e+2,
                              5.3941960214247511077e+3, 2.1213794301586595867e+4, 3.9307895800092710610e+4,
                              2.8729085735721942674e+4, 5.2264952788528545610e+3};
  static const double c[8] = {1.42343711074968357734e0, 4.63033784615654529590e0, 5.76949722146069140550e0,
                              3.64784832476320460504e0, 1.27045825245236838258e0, 2.41780725177450611770e-1,
                              2.27238449892691845833e-2, 7.74545014278341407640e-4};
  static const double d[8] = {1.0, 2.05319162663775882187e0, 1.67638483018380384940e0,
                              6.89767334985100004550e-1, 1.48103976427480074590e-1, 1.51986665636164571966e-2,
                              5.47593808499534494600e-4, 1.05075007164441684324e-9};
  static const double e[8] = {6.65790464350110377720e0, 5.46378491116411436990e0, 1.78482653991729133580e0,
                              2.96560571828504891230e-1, 2.65321895265761230930e-2, 1.24266094738807843860e-3,
                              2.71155556874348757815e-5, 2.01033439929228813265e-7};
  static const double f[8] = {1.0, 5.99832206555887937690e-1, 1.36929880922735805310e-1,
                              1.48753612908506148525e-2, 7.86869131145613259100e-4, 1.84631831751005468180e-5,
                              1.42151175831644588870e-7, 2.04426310338993978564e-15};
  if (!(p > 0.0 && p < 1.0)) return p == 0.0 ? -INFINITY : p == 1.0 ? INFINITY : NAN;
  const double q = p - 0.5;
  if (std::fabs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    return q * Polynomial(a, r) / Polynomial(b, r);
  }
  double r = std::sqrt(-std::log(q < 0.0 ? p : 1.0 - p));
  const double x = r <= 5.0 ? (r -= 1.6, Polynomial(c, r) / Polynomial(d, r))
                            : (r -= 5.0, Polynomial(e, r) / Polynomial(f, r));
  return q < 0.0 ? -x : x;
}

double NormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

std::uint32_t SobolPoint(int dimension, std::uint64_t index) {
  const Directions& v = AllDirections()[static_cast<std::size_t>(dimension)];
  std::uint32_t x = 0;
  for (int k = 0; k < 32 && index != 0; ++k, index >>= 1) {
    if (index & 1u) x ^= v[k];
  }
  return x;
}

std::pair<double, double> WilsonInterval(std::uint64_t successes, std::uint64_t trials) {
  if (trials == 0) return {0.0, 1.0};
  constexpr double z = 1.959963984540054;
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
  const double half = z / (1.0 + z * z / n) * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

QuantileRanks QuantileInterval(std::uint64_t n, double q, double confidence) {
  const double tail = (1.0 - confidence) / 2.0;
  // P(B <= k) for k = 0..n, accumulated term by term (log space: no underflow for large n).
  std::vector<double> cdf(n + 1);
  double sum = 0.0;
  for (std::uint64_t k = 0; k <= n; ++k) {
    sum += std::exp(LogBinomialTerm(n, k, q));
    cdf[k] = sum;
  }
  QuantileRanks ranks;
  // Lower: the largest l with P(B < l) = P(B <= l - 1) <= tail (0: none qualifies).
  for (std::uint64_t l = n; l >= 1; --l) {
    if (cdf[l - 1] <= tail) {
      ranks.lower = l;
      break;
    }
  }
  // Upper: the smallest u with P(B >= u) = 1 - P(B <= u - 1) <= tail (n + 1: none).
  ranks.upper = n + 1;
  for (std::uint64_t u = 1; u <= n; ++u) {
    if (1.0 - cdf[u - 1] <= tail) {
      ranks.upper = u;
      break;
    }
  }
  const double below = ranks.lower == 0 ? 0.0 : cdf[ranks.lower - 1];
  const double above = ranks.upper == n + 1 ? 0.0 : 1.0 - cdf[ranks.upper - 1];
  ranks.coverage = 1.0 - below - above;
  return ranks;
}

std::uint64_t QuantileRank(std::uint64_t n, double q) {
  // q n within rounding of a whole number is that number: 0.07 * 100 is 7, not 8.
  const double exact = q * static_cast<double>(n);
  const double nearest = std::round(exact);
  const double rank = std::fabs(exact - nearest) <= 1e-9 * std::max(1.0, exact) ? nearest : std::ceil(exact);
  if (rank < 1.0) return 1;
  return std::min<std::uint64_t>(n, static_cast<std::uint64_t>(rank));
}

}  // namespace shapebench
