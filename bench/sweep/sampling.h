// Sampled grid keys (docs/sweeps.md, "Sampled grids"): a key of a sweep's grid may be a
// distribution instead of values,
//   grid:
//     controller.pattern.method: ["1", zvd]
//     machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}, truncated: {min: 23.75, max: 26.25}}
//   samples: 400                 # N, required with a distribution
//   seed: 42                     # default 0
//   design: latin_hypercube      # random (default) | latin_hypercube | sobol
// with normal: {mean, sd}, uniform: {from, to} or lognormal: {median, sigma} (ln X is
// normal with mean ln(median) and sd sigma), and optional truncated: {min, max} (either or
// both): the distribution restricted to [min, max], drawn by its inverse CDF on the
// restricted interval. Every distribution key of the grid moves with one axis of N samples
// (at the place of the first of them), crossed with the other keys like any axis.
//
// Sample i of key d is a pure function of (seed, design, N, i, d): every process computes
// the same values, whatever its rank, thread or shard. The uniforms u in (0, 1):
//   random           CounterUniform(seed, d, i) (common/sample_math.h);
//   latin_hypercube  (pi_d(i) + CounterUniform(seed, d, i)) / N, pi_d a permutation of the
//                    N strata drawn by Fisher-Yates from CounterWord(seed, 2^32 + d, .)
//                    (at most 2^32 samples: the permutation is the one thing held, 4 bytes
//                    a sample);
//   sobol            Sobol dimension d (at most kSobolDimensions keys), point i, XORed
//                    with a digital shift CounterWord(seed, 2^33 + d, 0) (a random digital
//                    shift keeps the sequence's net property), at the centre of its 2^-32 cell.
// Each value is written in 15 significant digits and the point runs with that text. A value
// is computed when a point asks for it (SampleDraw): a sweep of 20,000,000 samples starts
// its first point at once and holds no list of them.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bench/config/node_reader.h"

namespace shapebench::bench {

struct Distribution {
  enum class Kind { kNormal, kUniform, kLogNormal };
  Kind kind = Kind::kNormal;
  double a = 0.0;  // normal: mean; uniform: from; lognormal: median
  double b = 1.0;  // normal: sd;   uniform: to;   lognormal: sigma
  std::optional<double> min;  // truncated:
  std::optional<double> max;

  // The value at the CDF level u in (0, 1) of the (truncated) distribution.
  double Quantile(double u) const;
  // "normal{mean=25,sd=0.625}truncated{min=23.75,max=26.25}": the manifest's and hash's text.
  std::string Describe() const;
  // The fraction of the untruncated distribution inside [min, max].
  double KeptMass() const;
};

enum class SampleDesign { kRandom, kLatinHypercube, kSobol };

const char* DesignName(SampleDesign design);

struct SweepSampling {
  std::uint64_t samples = 0;
  std::uint64_t seed = 0;
  SampleDesign design = SampleDesign::kRandom;
};

// A gate of `check` on the samples of a sampled sweep (docs/sweeps.md, "Yield and
// quantiles"), evaluated for each combination of the other grid keys' values over its N
// samples; the gate takes the point estimate, the report a 95% interval:
//   checks:
//     residual_ratio: {quantile: 0.95, max: 0.05}  # the empirical 0.95-quantile (rank ceil(0.95 N))
//     yield: {min: 0.99}   # the fraction of samples that run and pass every min/max check
// With a yield gate the min/max checks only define passing (a failing sample fails no run
// by itself); without one they apply to every point as in a plain sweep.
struct SampleGate {
  enum class Kind { kQuantile, kYield };
  Kind kind = Kind::kYield;
  std::string metric;    // kQuantile: the metric; kYield: "yield"
  double quantile = 0.0;  // kQuantile: in (0, 1)
  std::optional<double> min;
  std::optional<double> max;
};

// True when a grid value is a distribution (a mapping with normal:, uniform:, lognormal:
// or truncated:).
bool IsDistributionNode(const NodeReader& node);

// Reads {normal|uniform|lognormal: {...}, truncated: {min, max}}; errors (ConfigError at
// the offending node) for a bad parameter, a missing or second distribution, and bounds
// that keep less than 0.1% of the distribution's mass.
Distribution ReadDistribution(const NodeReader& node);

// The top-level samples:, seed:, design: of a sweep (nullopt when samples: is absent).
std::optional<SweepSampling> ReadSampling(const NodeReader& top);

// Throws std::invalid_argument when the design cannot draw `dimensions` keys of its N
// samples: a Sobol design beyond kSobolDimensions keys or 2^32 samples, a Latin hypercube
// beyond 2^32 samples.
void CheckSampleDesign(const SweepSampling& sampling, std::size_t dimensions);

// The samples of one distribution key, dimension d of the sampling: sample i computed when
// asked, the same value whichever thread, process or order asks. A Latin hypercube's
// permutation is drawn at the first request (not by a reader that only checks a manifest).
// Shared between threads (const, the permutation drawn once under a std::once_flag).
class SampleDraw {
 public:
  // CheckSampleDesign(sampling, dimension + 1) must hold.
  SampleDraw(const SweepSampling& sampling, std::size_t dimension, const Distribution& distribution);
  SampleDraw(const SampleDraw&) = delete;
  SampleDraw& operator=(const SampleDraw&) = delete;

  std::uint64_t size() const { return sampling_.samples; }
  // The CDF level in (0, 1) of sample i < size().
  double Uniform(std::uint64_t i) const;
  double Value(std::uint64_t i) const { return distribution_.Quantile(Uniform(i)); }
  const Distribution& distribution() const { return distribution_; }

 private:
  const std::vector<std::uint32_t>& Strata() const;

  SweepSampling sampling_;
  std::uint64_t dimension_;
  Distribution distribution_;
  std::uint32_t shift_;  // sobol's digital shift
  mutable std::once_flag strata_once_;
  mutable std::vector<std::uint32_t> strata_;  // latin_hypercube's pi_d
};

// The uniforms of every dimension: result[d][i] in (0, 1) for d < dimensions, i < samples
// (SampleDraw::Uniform of each; for tests). Throws as CheckSampleDesign.
std::vector<std::vector<double>> SampleUniforms(const SweepSampling& sampling, std::size_t dimensions);

// The Distribution whose Describe() is `text` (a manifest's); std::runtime_error naming
// what is wrong for any other text or parameters ReadDistribution would refuse.
Distribution ParseDistribution(const std::string& text);

}  // namespace shapebench::bench
