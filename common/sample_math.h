// Exactly specified arithmetic for sampled sweeps (docs/sweeps.md, "Sampled grids"): the
// same seed must give the same points on every platform, compiler, rank, thread or shard,
// so nothing here uses the std:: distributions (their algorithms are
// implementation-defined). Uniforms come from a counter-based generator (a pure function
// of seed, stream and index), transformed by inverse CDFs; Sobol points from Joe & Kuo's
// direction numbers. Also the binomial intervals `check` reports on samples.
#pragma once

#include <cstdint>
#include <utility>

namespace shapebench {

// SplitMix64's finaliser (Steele, Lea & Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014): a bijection of 64-bit words with full avalanche.
std::uint64_t Mix64(std::uint64_t z);

// A 64-bit word that depends on (seed, stream, index) only: Mix64 chained over the three.
std::uint64_t CounterWord(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

// A uniform in the open interval (0, 1) from CounterWord: its top 53 bits plus one half,
// over 2^53 (never 0 or 1, so an inverse CDF stays finite).
double CounterUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

// The standard normal's quantile Phi^-1(p) for p in (0, 1): Wichura's AS241 (PPND16,
// Applied Statistics 37 (1988) 477-484), relative error about 1e-16.
double InverseNormalCdf(double p);

// The standard normal's CDF Phi(z) = erfc(-z / sqrt 2) / 2.
double NormalCdf(double z);

// How many dimensions SobolPoint supports: dimension 0 is van der Corput's sequence, the
// others take the first primitive polynomials and direction numbers of Joe & Kuo's
// new-joe-kuo-6.21201 table (S. Joe, F. Y. Kuo, SIAM J. Sci. Comput. 30 (2008) 2635-2654).
constexpr int kSobolDimensions = 16;

// The `index`-th point (index < 2^32) of the Sobol sequence in `dimension`, as a 32-bit
// binary fraction: the XOR of the direction numbers of index's set bits (the sequence in
// natural order, not Gray-code order; every block of 2^m points is the same set).
std::uint32_t SobolPoint(int dimension, std::uint64_t index);

// The 95% Wilson score interval of a binomial proportion with `successes` of `trials`
// (E. B. Wilson, JASA 22 (1927) 209-212), z = 1.959963984540054.
std::pair<double, double> WilsonInterval(std::uint64_t successes, std::uint64_t trials);

// The distribution-free interval of the q-quantile from n samples: ranks (l, u), 1-based
// into the sorted sample, such that P(X_(l) <= x_q <= X_(u)) >= `confidence`, taking
// P(B < l) <= (1 - confidence)/2 and P(B >= u) <= (1 - confidence)/2 for B ~ Bin(n, q)
// (each tail as large as allowed). l = 0 means no lower order statistic is low enough
// (the interval is open below); u = n + 1 likewise above. `coverage` gets P(l <= B < u).
struct QuantileRanks {
  std::uint64_t lower = 0;
  std::uint64_t upper = 0;
  double coverage = 0.0;
};
QuantileRanks QuantileInterval(std::uint64_t n, double q, double confidence = 0.95);

// The empirical q-quantile's 1-based rank in a sorted sample of n: ceil(q n), at least 1
// (the inverse of the empirical CDF, Hyndman & Fan type 1).
std::uint64_t QuantileRank(std::uint64_t n, double q);

}  // namespace shapebench
