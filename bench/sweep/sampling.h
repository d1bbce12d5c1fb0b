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
//                    N strata drawn by Fisher-Yates from CounterWord(seed, 2^32 + d, .);
//   sobol            Sobol dimension d (at most kSobolDimensions keys), point i, XORed
//                    with a digital shift CounterWord(seed, 2^33 + d, 0) (a random digital
//                    shift keeps the sequence's net property), at the centre of its 2^-32 cell.
// Each value is written in 15 significant digits and the point runs with that text.
#pragma once

#include <cstdint>
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

// The uniforms of every dimension: result[d][i] in (0, 1) for d < dimensions, i < samples.
// Throws std::invalid_argument for a Sobol design beyond kSobolDimensions or 2^32 samples.
std::vector<std::vector<double>> SampleUniforms(const SweepSampling& sampling, std::size_t dimensions);

}  // namespace shapebench::bench
