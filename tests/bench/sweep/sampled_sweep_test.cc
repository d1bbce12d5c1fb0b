// Sampled grids (bench/sweep/sampling.h) and the statistics of their gates
// (common/sample_math.h): the samples' moments and strata against the distributions asked
// for, the inverse CDF and Sobol points against independent properties, the Wilson and
// order-statistic intervals against textbook values and simulated coverage, and errors
// located at FILE:LINE:COL.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/sweep/sampling.h"
#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/sweep_file.h"
#include "common/sample_math.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ErrorOf;
using testing::ExpectError;
using testing::ScratchDir;

using SampledSweep = testing::SweepFile;

// The values of the sampled key `key` of a loaded sweep, as the points run them (their text).
std::vector<double> Samples(const Sweep& sweep, const std::string& key) {
  for (const SweepAxis& axis : sweep.axes) {
    for (const SweepValues& values : axis.keys) {
      if (values.key != key) continue;
      std::vector<double> xs;
      for (std::uint64_t i = 0; i < values.size(); ++i) xs.push_back(std::stod(values.Text(i)));
      return xs;
    }
  }
  ADD_FAILURE() << "no key " << key;
  return {};
}

double Mean(const std::vector<double>& xs) {
  double sum = 0.0;
  for (const double x : xs) sum += x;
  return sum / static_cast<double>(xs.size());
}

double Sd(const std::vector<double>& xs) {
  const double mean = Mean(xs);
  double sum = 0.0;
  for (const double x : xs) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(xs.size() - 1));
}

std::string Grid(const std::string& distribution, const std::string& design, int samples) {
  return "grid:\n  machine.modes[0].frequency_hz: " + distribution + "\nsamples: " + std::to_string(samples) +
         "\nseed: 42\ndesign: " + design + "\n";
}

// Tests that Phi^-1 (AS241) inverts Phi (from std::erfc, an independent formula) to 1e-14
// over the centre and both tails, and gives the textbook 97.5% point 1.959963984540054.
TEST(SampleMath, InverseNormalCdfInvertsTheCdf) {
  EXPECT_NEAR(InverseNormalCdf(0.975), 1.959963984540054, 1e-15);
  EXPECT_NEAR(InverseNormalCdf(0.5), 0.0, 1e-16);
  for (const double p : {1e-300, 1e-20, 1e-8, 0.001, 0.02, 0.0749, 0.3, 0.5001, 0.9, 0.99, 0.999999}) {
    const double z = InverseNormalCdf(p);
    EXPECT_NEAR(NormalCdf(z) / p, 1.0, 1e-13) << p;  // relative: the tails are tiny
    if (p >= 1e-3) {  // 1 - p exact enough
      EXPECT_NEAR(InverseNormalCdf(1.0 - p), -z, 1e-12) << p;
    }
  }
}

// Tests that every one of the 16 Sobol dimensions puts exactly one of its first 2^m points
// in each of 2^m equal bins (m = 1..12), and dimensions 0 and 1 form a (0, m, 2)-net:
// every elementary box 2^-k x 2^-(m-k) holds exactly one of the first 2^m points.
TEST(SampleMath, SobolPointsStratify) {
  for (int d = 0; d < kSobolDimensions; ++d) {
    for (int m = 1; m <= 12; ++m) {
      std::vector<int> bins(1u << m, 0);
      for (std::uint64_t i = 0; i < (1u << m); ++i) ++bins[SobolPoint(d, i) >> (32 - m)];
      EXPECT_EQ(*std::min_element(bins.begin(), bins.end()), 1) << "dimension " << d << ", m " << m;
      EXPECT_EQ(*std::max_element(bins.begin(), bins.end()), 1) << "dimension " << d << ", m " << m;
    }
  }
  constexpr int m = 8;
  for (int k = 0; k <= m; ++k) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> boxes;
    for (std::uint64_t i = 0; i < (1u << m); ++i) {
      const std::uint32_t x = k == 0 ? 0 : SobolPoint(0, i) >> (32 - k);
      const std::uint32_t y = k == m ? 0 : SobolPoint(1, i) >> (32 - (m - k));
      boxes.insert({x, y});
    }
    EXPECT_EQ(boxes.size(), 1u << m) << "k " << k;
  }
}

// Tests the Wilson interval against Newcombe's worked example (Statistics in Medicine 17
// (1998) 857-872, table I: 81 of 263, score interval 0.2553 to 0.3662) and the closed form
// computed here, including the ends 0 of n and n of n.
TEST(SampleMath, WilsonIntervalMatchesTheTextbook) {
  const auto [low, high] = WilsonInterval(81, 263);
  EXPECT_NEAR(low, 0.2553, 5e-5);
  EXPECT_NEAR(high, 0.3662, 5e-5);
  const double z = 1.959963984540054;
  for (const auto& [k, n] : std::vector<std::pair<int, int>>{{0, 10}, {10, 10}, {7, 40}, {999, 1000}}) {
    const double p = static_cast<double>(k) / n;
    const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
    const double half = z * std::sqrt(p * (1 - p) / n + z * z / (4.0 * n * n)) / (1 + z * z / n);
    const auto interval = WilsonInterval(k, n);
    EXPECT_NEAR(interval.first, std::max(0.0, centre - half), 1e-12) << k << "/" << n;
    EXPECT_NEAR(interval.second, std::min(1.0, centre + half), 1e-12) << k << "/" << n;
  }
}

// P(B <= k) for B ~ Bin(n, q), by adding the n trials one at a time (independent of the
// code's log-gamma sum).
double BinomialCdf(int n, double q, int k) {
  std::vector<double> pmf(n + 1, 0.0);
  pmf[0] = 1.0;
  for (int trial = 1; trial <= n; ++trial) {
    for (int j = trial; j >= 1; --j) pmf[j] = pmf[j] * (1.0 - q) + pmf[j - 1] * q;
    pmf[0] *= 1.0 - q;
  }
  double sum = 0.0;
  for (int j = 0; j <= k; ++j) sum += pmf[j];
  return sum;
}

// Tests that the order-statistic interval's ranks leave at most 2.5% in each tail and that
// moving either rank inwards would exceed it (the interval is as short as allowed), and
// that on simulated uniform samples (true quantile q) it covers q in at least 94% of 4000
// trials (95% nominal; 3 binomial standard errors of 4000 trials are 1%).
TEST(SampleMath, QuantileIntervalCoversTheQuantile) {
  for (const auto& [n, q] : std::vector<std::pair<int, double>>{{50, 0.5}, {100, 0.95}, {400, 0.95}, {300, 0.1}}) {
    const QuantileRanks ranks = QuantileInterval(n, q);
    ASSERT_GE(ranks.lower, 1u);
    ASSERT_LE(ranks.upper, static_cast<std::uint64_t>(n));
    const int l = static_cast<int>(ranks.lower);
    const int u = static_cast<int>(ranks.upper);
    EXPECT_LE(BinomialCdf(n, q, l - 1), 0.025 + 1e-12);
    EXPECT_GT(BinomialCdf(n, q, l), 0.025);
    EXPECT_LE(1.0 - BinomialCdf(n, q, u - 1), 0.025 + 1e-12);
    EXPECT_GT(1.0 - BinomialCdf(n, q, u - 2), 0.025);
    EXPECT_NEAR(ranks.coverage, BinomialCdf(n, q, u - 1) - BinomialCdf(n, q, l - 1), 1e-9);
    EXPECT_LE(ranks.lower, QuantileRank(n, q));
    EXPECT_GE(ranks.upper, QuantileRank(n, q));
  }
  // Too few samples for a 0.95-quantile's upper end: open above.
  EXPECT_EQ(QuantileInterval(20, 0.95).upper, 21u);
  const int n = 60;
  const double q = 0.9;
  const QuantileRanks ranks = QuantileInterval(n, q);
  int covered = 0;
  constexpr int kTrials = 4000;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<double> xs;
    for (int i = 0; i < n; ++i) xs.push_back(CounterUniform(7, t, i));
    std::sort(xs.begin(), xs.end());
    covered += xs[ranks.lower - 1] <= q && q <= xs[ranks.upper - 1];
  }
  EXPECT_GE(covered / static_cast<double>(kTrials), 0.94);
}

// Tests the empirical quantile's rank ceil(q n), with q n a whole number up to rounding.
TEST(SampleMath, QuantileRankIsTheCeiling) {
  EXPECT_EQ(QuantileRank(100, 0.07), 7u);  // 0.07 * 100 = 7.000000000000001 in doubles
  EXPECT_EQ(QuantileRank(100, 0.071), 8u);
  EXPECT_EQ(QuantileRank(400, 0.95), 380u);
  EXPECT_EQ(QuantileRank(10, 0.01), 1u);
}

// Tests that the sample mean and sd of a normal key (seed 42) are within 3 standard
// errors of the requested ones (SE of the mean sd/sqrt(N), of the sd sd/sqrt(2(N-1))),
// for each design.
TEST(SampledGrid, NormalKeyHasTheRequestedMoments) {
  constexpr int n = 2000;
  for (const char* design : {"random", "latin_hypercube", "sobol"}) {
    const SampledSweep file(Grid("{normal: {mean: 25, sd: 0.625}}", design, n));
    const std::vector<double> xs = Samples(file.Load(), "machine.modes[0].frequency_hz");
    ASSERT_EQ(xs.size(), static_cast<std::size_t>(n));
    EXPECT_NEAR(Mean(xs), 25.0, 3 * 0.625 / std::sqrt(n)) << design;
    EXPECT_NEAR(Sd(xs), 0.625, 3 * 0.625 / std::sqrt(2.0 * (n - 1))) << design;
  }
}

// Tests that a latin hypercube puts exactly one of its N points in each of the N strata
// of every key (the strata of equal probability: the CDF level in [k/N, (k+1)/N)).
TEST(SampledGrid, LatinHypercubeStrataHoldOnePointEach) {
  constexpr int n = 500;
  const SampledSweep file(
      "grid:\n  machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}}\n"
      "  machine.modes[0].damping_ratio: {uniform: {from: 0.01, to: 0.05}}\n"
      "samples: 500\nseed: 42\ndesign: latin_hypercube\n");
  const Sweep sweep = file.Load();
  ASSERT_EQ(sweep.points, static_cast<std::uint64_t>(n));
  ASSERT_EQ(sweep.axes.size(), 1u);  // both keys move with the one axis of samples
  const auto strata = [&](const std::vector<double>& levels) {
    std::vector<int> count(n, 0);
    for (const double level : levels) ++count[static_cast<int>(std::floor(level * n))];
    return count;
  };
  std::vector<double> normal_levels;
  std::vector<double> uniform_levels;
  for (const SweepValues& values : sweep.axes[0].keys) {
    for (std::uint64_t i = 0; i < values.size(); ++i) {
      const double x = values.draw->Value(i);
      if (values.distribution->kind == Distribution::Kind::kNormal) {
        normal_levels.push_back(NormalCdf((x - 25.0) / 0.625));
      } else {
        uniform_levels.push_back((x - 0.01) / 0.04);
      }
    }
  }
  EXPECT_EQ(strata(normal_levels), std::vector<int>(n, 1));
  EXPECT_EQ(strata(uniform_levels), std::vector<int>(n, 1));
}

// Tests a uniform key's bounds and mean, a lognormal's ln-moments (ln X normal with mean
// ln(median), sd sigma) and a truncated normal's bounds and mean (the closed form
// mu + sd (phi(a) - phi(b)) / (Phi(b) - Phi(a))), each within 3 standard errors.
TEST(SampledGrid, UniformLognormalAndTruncatedKeys) {
  constexpr int n = 3000;
  const std::vector<double> u = Samples(SampledSweep(Grid("{uniform: {from: 20, to: 30}}", "random", n)).Load(),
                                        "machine.modes[0].frequency_hz");
  EXPECT_GE(*std::min_element(u.begin(), u.end()), 20.0);
  EXPECT_LE(*std::max_element(u.begin(), u.end()), 30.0);
  EXPECT_NEAR(Mean(u), 25.0, 3 * 10.0 / std::sqrt(12.0 * n));

  std::vector<double> logs;
  for (const double x : Samples(SampledSweep(Grid("{lognormal: {median: 25, sigma: 0.1}}", "random", n)).Load(),
                                "machine.modes[0].frequency_hz")) {
    logs.push_back(std::log(x));
  }
  EXPECT_NEAR(Mean(logs), std::log(25.0), 3 * 0.1 / std::sqrt(n));
  EXPECT_NEAR(Sd(logs), 0.1, 3 * 0.1 / std::sqrt(2.0 * (n - 1)));

  const std::vector<double> t = Samples(
      SampledSweep(Grid("{normal: {mean: 25, sd: 1}, truncated: {min: 24.5, max: 27}}", "random", n)).Load(),
      "machine.modes[0].frequency_hz");
  EXPECT_GE(*std::min_element(t.begin(), t.end()), 24.5);
  EXPECT_LE(*std::max_element(t.begin(), t.end()), 27.0);
  const double a = -0.5;
  const double b = 2.0;
  const auto phi = [](double z) { return std::exp(-z * z / 2) / std::sqrt(2 * M_PI); };
  const double mean = 25.0 + (phi(a) - phi(b)) / (0.5 * std::erfc(-b / std::sqrt(2.0)) - 0.5 * std::erfc(-a / std::sqrt(2.0)));
  EXPECT_NEAR(Mean(t), mean, 3 * Sd(t) / std::sqrt(n));
}

// Tests that the samples are a pure function of seed, design and N: two loads agree,
// another seed or design differs, and the first point does not depend on the fixed keys
// crossed with the samples (each value of them sees the same samples).
TEST(SampledGrid, SamplesDependOnSeedAndDesignOnly) {
  const std::string normal = "{normal: {mean: 25, sd: 0.625}}";
  const auto texts = [](const Sweep& sweep) {
    std::vector<std::string> all;
    for (std::uint64_t p = 0; p < sweep.points; ++p) all.push_back(MakePoint(sweep, p, {}).Label());
    return all;
  };
  const SampledSweep a(Grid(normal, "latin_hypercube", 64));
  EXPECT_EQ(texts(a.Load()), texts(a.Load()));
  std::string other = Grid(normal, "latin_hypercube", 64);
  other.replace(other.find("seed: 42"), 8, "seed: 43");
  EXPECT_NE(texts(SampledSweep(other).Load()), texts(a.Load()));
  EXPECT_NE(texts(SampledSweep(Grid(normal, "sobol", 64)).Load()), texts(a.Load()));
  const SampledSweep crossed("grid:\n  controller.pattern.method: [\"1\", zvd]\n  machine.modes[0].frequency_hz: " +
                             normal + "\nsamples: 64\nseed: 42\ndesign: latin_hypercube\n");
  const Sweep sweep = crossed.Load();
  ASSERT_EQ(sweep.points, 128u);
  const std::vector<double> xs = Samples(sweep, "machine.modes[0].frequency_hz");
  EXPECT_EQ(xs, Samples(a.Load(), "machine.modes[0].frequency_hz"));
  EXPECT_EQ(MakePoint(sweep, 64 + 5, {}).texts[1], MakePoint(sweep, 5, {}).texts[1]);
}

// The uniforms of dimension d as the sweep drew them before SampleDraw: the whole list at
// once, the Latin hypercube's strata as 64-bit numbers (SampleDraw must give these bits).
std::vector<double> WholeListUniforms(const SweepSampling& s, std::uint64_t d) {
  const std::uint64_t n = s.samples;
  std::vector<std::uint64_t> strata(n);
  for (std::uint64_t i = 0; i < n; ++i) strata[i] = i;
  for (std::uint64_t i = n; i-- > 1;) std::swap(strata[i], strata[CounterWord(s.seed, (1ULL << 32) + d, i) % (i + 1)]);
  const auto shift = static_cast<std::uint32_t>(CounterWord(s.seed, (1ULL << 33) + d, 0) >> 32);
  std::vector<double> u(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    if (s.design == SampleDesign::kRandom) u[i] = CounterUniform(s.seed, d, i);
    if (s.design == SampleDesign::kLatinHypercube) {
      u[i] = std::min((static_cast<double>(strata[i]) + CounterUniform(s.seed, d, i)) / static_cast<double>(n),
                      std::nextafter(1.0, 0.0));
    }
    if (s.design == SampleDesign::kSobol) {
      u[i] = (static_cast<double>(SobolPoint(static_cast<int>(d), i) ^ shift) + 0.5) * 0x1.0p-32;
    }
  }
  return u;
}

// Tests that a sample computed when asked (SampleDraw, asked last index first) has the
// bits of the whole-list draw the sweep made before, for every design and three keys, and
// its value is the distribution's quantile of it.
TEST(SampledGrid, DrawPerIndexMatchesTheWholeListDraw) {
  const Distribution normal{Distribution::Kind::kNormal, 25.0, 0.625, 23.75, 26.25};
  for (const SampleDesign design : {SampleDesign::kRandom, SampleDesign::kLatinHypercube, SampleDesign::kSobol}) {
    const SweepSampling sampling{1000, 42, design};
    for (std::uint64_t d = 0; d < 3; ++d) {
      const std::vector<double> expected = WholeListUniforms(sampling, d);
      const SampleDraw draw(sampling, d, normal);
      ASSERT_EQ(draw.size(), 1000u);
      for (std::uint64_t i = 1000; i-- > 0;) {
        ASSERT_EQ(draw.Uniform(i), expected[i]) << DesignName(design) << " key " << d << " sample " << i;
        ASSERT_EQ(draw.Value(i), normal.Quantile(expected[i]));
      }
    }
  }
}

// Tests that a manifest's distribution text reads back as the Distribution that wrote it,
// and that any other text, or parameters the sweep loader refuses, are refused by name.
TEST(SampledGrid, ParseDistributionReadsWhatDescribeWrites) {
  const std::vector<Distribution> written = {
      {Distribution::Kind::kNormal, 25.0, 0.625, 23.75, 26.25},
      {Distribution::Kind::kUniform, -1e-3, 2.5e20, std::nullopt, std::nullopt},
      {Distribution::Kind::kLogNormal, 0.03, 0.1, std::nullopt, 0.05},
      {Distribution::Kind::kNormal, 0.1 + 0.2, 1.0 / 3.0, 0.0, std::nullopt},
  };
  for (const Distribution& dist : written) {
    const Distribution read = ParseDistribution(dist.Describe());
    EXPECT_EQ(read.Describe(), dist.Describe());
    EXPECT_EQ(read.Quantile(0.3), dist.Quantile(0.3)) << dist.Describe();
  }
  for (const std::string bad : {"", "normal", "normal{mean=25,sd=0}", "normal{mean=25}", "gamma{k=1,theta=2}",
                                "normal{mean=0x10,sd=1}", "normal{mean=25.0,sd=1}", "normal{mean=25,sd=1}x",
                                "normal{mean=25,sd=1}truncated{min=90}", "uniform{from=2,to=1}",
                                "normal{mean=25,sd=1,sd=2}", "lognormal{median=-1,sigma=1}",
                                "normal{mean=25,sd=1}truncated{}", "normal{mean=nan,sd=1}"}) {
    try {
      ParseDistribution(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_EQ(std::string(error.what()).rfind("distribution '" + bad + "': ", 0), 0u) << error.what();
    }
  }
}

// Tests that a Sobol design refuses more keys than it has direction numbers for.
TEST(SampledGrid, SobolTakesAtMostSixteenKeys) {
  const SweepSampling sobol{8, 0, SampleDesign::kSobol};
  EXPECT_NO_THROW(SampleUniforms(sobol, kSobolDimensions));
  EXPECT_THROW(SampleUniforms(sobol, kSobolDimensions + 1), std::invalid_argument);
}

// Tests that bad sampling specs are refused at their FILE:LINE:COL naming what is allowed.
TEST(SampledGrid, BadSpecsAreLocated) {
  const std::string key = "grid.machine.modes[0].frequency_hz";
  struct Case {
    std::string body;
    int line;
    int column;
    std::string path;
    std::string message;
  };
  const std::vector<Case> cases = {
      {Grid("{normal: {mean: 25, sd: 0}}", "random", 10), 3, 58, key + ".normal.sd", "sd must be above 0"},
      {Grid("{uniform: {from: 30, to: 20}}", "random", 10), 3, 59, key + ".uniform.to", "must be above from"},
      {Grid("{lognormal: {median: -1, sigma: 0.1}}", "random", 10), 3, 55, key + ".lognormal.median",
       "median must be above 0"},
      {Grid("{normal: {mean: 25, sd: 0.6}, truncated: {min: 40, max: 41}}", "random", 10), 3, 75,
       key + ".truncated", "at least 0.001 must stay"},
      {Grid("{normal: {mean: 25, sd: 0.6}, truncated: {min: 26, max: 24}}", "random", 10), 3, 90,
       key + ".truncated.max", "must be above min"},
      {Grid("{truncated: {min: 1}}", "random", 10), 3, 34, key, "add normal:"},
      {Grid("{normal: {mean: 25, sd: 1}}", "random", 0), 4, 10, "samples", "at least 1"},
      {Grid("{normal: {mean: 25, sd: 1}}", "stratified", 10), 6, 9, "design",
       "expected one of random|latin_hypercube|sobol"},
      {"grid:\n  machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 1}}\n", 3, 34, key, "needs samples: N"},
      {"grid:\n  machine.modes[0].frequency_hz: [24, 25]\nsamples: 5\n", 4, 10, "samples",
       "needs a distribution key"},
      {"grid:\n  zip:\n    machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 1}}\n    "
       "machine.modes[0].damping_ratio: [0.1]\nsamples: 5\n",
       4, 36, "grid.zip.machine.modes[0].frequency_hz", "cannot be in a zip group"},
      {"grid:\n  machine.modes[0].frequency_hz: [24, 25]\nchecks:\n  yield: {min: 0.9}\n", 5, 10,
       "checks.yield", "needs a sampled sweep"},
      {Grid("{normal: {mean: 25, sd: 1}}", "random", 10) + "checks:\n  residual_ratio: {quantile: 1.5, max: 0.05}\n",
       8, 30, "checks.residual_ratio.quantile", "0 < quantile < 1"},
      {Grid("{normal: {mean: 25, sd: 1}}", "random", 10) + "checks:\n  yield: {min: 0.9}\n", 8, 10,
       "checks.yield", "add a min/max check"},
      {Grid("{normal: {mean: 25, sd: 1}}", "random", 10) + "checks:\n  yield: {min: 1.5}\n"
       "  residual_ratio: {max: 0.05}\n", 8, 16, "checks.yield.min", "0 < min <= 1"},
  };
  for (const Case& c : cases) {
    const SampledSweep file(c.body);
    ExpectError(ErrorOf([&] { file.Load(); }), file.path(), c.line, c.column, c.path, c.message);
  }
}

}  // namespace
}  // namespace shapebench::bench
