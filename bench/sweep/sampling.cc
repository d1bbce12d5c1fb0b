// Sampled grid keys (bench/sweep/sampling.h).
#include "bench/sweep/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "common/csv.h"
#include "common/decimal.h"
#include "common/sample_math.h"

namespace shapebench::bench {
namespace {

constexpr double kMinKeptMass = 1e-3;
constexpr std::uint64_t kPermutationStream = 1ULL << 32;
constexpr std::uint64_t kShiftStream = 1ULL << 33;

// A standard normal truncated to [za, zb] at level u. In the upper tail the CDF's levels
// crowd against 1 and lose digits: there the mirror image is drawn from the lower tail.
double TruncatedStandardNormal(double za, double zb, double u) {
  if (za > 0.0) return -TruncatedStandardNormal(-zb, -za, 1.0 - u);
  const double pa = NormalCdf(za);
  const double pb = NormalCdf(zb);
  const double z = InverseNormalCdf(pa + u * (pb - pa));
  return std::min(std::max(z, za), zb);
}

double Positive(const NodeReader& node, const char* what) {
  const double value = node.AsNumber();
  if (!(value > 0.0)) throw node.Error(std::string(what) + " must be above 0, got " + node.node().Scalar());
  return value;
}

double Param(const NodeReader& params, const char* name, const std::string& example) {
  const auto child = params.Child(name);
  if (!child) throw params.Error(std::string("missing '") + name + "'; expected " + example);
  return child->AsNumber();
}

}  // namespace

double Distribution::Quantile(double u) const {
  const double low = min.value_or(-INFINITY);
  const double high = max.value_or(INFINITY);
  switch (kind) {
    case Kind::kUniform: {
      const double from = std::max(a, low);
      const double to = std::min(b, high);
      return from + u * (to - from);
    }
    case Kind::kNormal:
      return a + b * TruncatedStandardNormal((low - a) / b, (high - a) / b, u);
    case Kind::kLogNormal: {
      const double za = low > 0.0 ? std::log(low / a) / b : -INFINITY;
      return a * std::exp(b * TruncatedStandardNormal(za, std::log(high / a) / b, u));
    }
  }
  return NAN;
}

double Distribution::KeptMass() const {
  const double low = min.value_or(-INFINITY);
  const double high = max.value_or(INFINITY);
  if (!(low < high)) return 0.0;
  switch (kind) {
    case Kind::kUniform:
      return std::max(0.0, std::min(b, high) - std::max(a, low)) / (b - a);
    case Kind::kNormal:
      return NormalCdf((high - a) / b) - NormalCdf((low - a) / b);
    case Kind::kLogNormal: {
      const double za = low > 0.0 ? std::log(low / a) / b : -INFINITY;
      return high <= 0.0 ? 0.0 : NormalCdf(std::log(high / a) / b) - NormalCdf(za);
    }
  }
  return 0.0;
}

// Numbers as ShortestDouble: the shortest text that reads back as exactly the value (the
// hash stays exact).
std::string Distribution::Describe() const {
  std::string text;
  switch (kind) {
    case Kind::kNormal: text = "normal{mean=" + ShortestDouble(a) + ",sd=" + ShortestDouble(b) + "}"; break;
    case Kind::kUniform: text = "uniform{from=" + ShortestDouble(a) + ",to=" + ShortestDouble(b) + "}"; break;
    case Kind::kLogNormal: text = "lognormal{median=" + ShortestDouble(a) + ",sigma=" + ShortestDouble(b) + "}"; break;
  }
  if (min || max) {
    text += "truncated{";
    if (min) text += "min=" + ShortestDouble(*min);
    if (max) text += std::string(min ? "," : "") + "max=" + ShortestDouble(*max);
    text += "}";
  }
  return text;
}

const char* DesignName(SampleDesign design) {
  switch (design) {
    case SampleDesign::kRandom: return "random";
    case SampleDesign::kLatinHypercube: return "latin_hypercube";
    case SampleDesign::kSobol: return "sobol";
  }
  return "?";
}

bool IsDistributionNode(const NodeReader& node) {
  if (!node.IsMap()) return false;
  for (const char* key : {"normal", "uniform", "lognormal", "truncated"}) {
    if (node.Has(key)) return true;
  }
  return false;
}

Distribution ReadDistribution(const NodeReader& node) {
  node.ExpectMap({"normal", "uniform", "lognormal", "truncated"});
  Distribution dist;
  int given = 0;
  for (const char* name : {"normal", "uniform", "lognormal"}) {
    const auto params = node.Child(name);
    if (!params) continue;
    if (++given > 1) throw params->Error("a key has one distribution; give normal:, uniform: or lognormal:, not two");
    if (!params->IsMap()) throw params->Error("expected a mapping of the distribution's parameters");
    const std::string kind = name;
    if (kind == "normal") {
      params->ExpectMap({"mean", "sd"});
      dist.kind = Distribution::Kind::kNormal;
      dist.a = Param(*params, "mean", "{mean: M, sd: S}");
      Param(*params, "sd", "{mean: M, sd: S}");
      dist.b = Positive(*params->Child("sd"), "sd");
    } else if (kind == "uniform") {
      params->ExpectMap({"from", "to"});
      dist.kind = Distribution::Kind::kUniform;
      dist.a = Param(*params, "from", "{from: A, to: B}");
      dist.b = Param(*params, "to", "{from: A, to: B}");
      if (!(dist.a < dist.b)) {
        throw params->Child("to")->Error("must be above from (" + ShortestDouble(dist.a) + "), got " +
                                         ShortestDouble(dist.b));
      }
    } else {
      params->ExpectMap({"median", "sigma"});
      dist.kind = Distribution::Kind::kLogNormal;
      Param(*params, "median", "{median: M, sigma: S} (ln X normal, mean ln M, sd S)");
      dist.a = Positive(*params->Child("median"), "median");
      Param(*params, "sigma", "{median: M, sigma: S} (ln X normal, mean ln M, sd S)");
      dist.b = Positive(*params->Child("sigma"), "sigma");
    }
  }
  if (given == 0) {
    throw node.Error("truncated: bounds a distribution; add normal: {mean, sd}, uniform: {from, to} or "
                     "lognormal: {median, sigma}");
  }
  if (const auto bounds = node.Child("truncated")) {
    if (!bounds->IsMap()) throw bounds->Error("expected {min: A, max: B} (either or both)");
    bounds->ExpectMap({"min", "max"});
    if (const auto low = bounds->Child("min")) dist.min = low->AsNumber();
    if (const auto high = bounds->Child("max")) dist.max = high->AsNumber();
    if (!dist.min && !dist.max) throw bounds->Error("expected min: and/or max:");
    if (dist.min && dist.max && !(*dist.min < *dist.max)) {
      throw bounds->Child("max")->Error("must be above min (" + ShortestDouble(*dist.min) + "), got " +
                                        ShortestDouble(*dist.max));
    }
    const double kept = dist.KeptMass();
    if (!(kept >= kMinKeptMass)) {
      char text[64];
      std::snprintf(text, sizeof text, "%.3g", kept);
      throw bounds->Error(std::string("the bounds keep ") + text + " of the distribution's mass (" +
                          dist.Describe() + "); at least 0.001 must stay (are min and max in the key's units, around the "
                          "distribution's centre?)");
    }
  }
  return dist;
}

std::optional<SweepSampling> ReadSampling(const NodeReader& top) {
  const auto samples = top.Child("samples");
  if (!samples) {
    for (const char* key : {"seed", "design"}) {
      if (const auto child = top.Child(key)) {
        throw child->Error(std::string(key) + ": belongs to a sampled sweep; add samples: N and a distribution "
                           "key to grid:, e.g. machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}}");
      }
    }
    return std::nullopt;
  }
  SweepSampling sampling;
  const long count = samples->AsInteger();
  if (count < 1) throw samples->Error("must be at least 1, got " + samples->node().Scalar());
  sampling.samples = static_cast<std::uint64_t>(count);
  if (const auto seed = top.Child("seed")) {
    const long value = seed->AsInteger();
    if (value < 0) throw seed->Error("must be a whole number >= 0, got " + seed->node().Scalar());
    sampling.seed = static_cast<std::uint64_t>(value);
  }
  top.Read<SampleDesign>("design",
                         {{"random", SampleDesign::kRandom},
                          {"latin_hypercube", SampleDesign::kLatinHypercube},
                          {"sobol", SampleDesign::kSobol}},
                         &sampling.design);
  return sampling;
}

void CheckSampleDesign(const SweepSampling& sampling, std::size_t dimensions) {
  const std::uint64_t n = sampling.samples;
  if (sampling.design == SampleDesign::kSobol &&
      (dimensions > static_cast<std::size_t>(kSobolDimensions) || n > (1ULL << 32))) {
    throw std::invalid_argument("a sobol design takes at most " + std::to_string(kSobolDimensions) +
                                " distribution keys and 2^32 samples");
  }
  if (sampling.design == SampleDesign::kLatinHypercube && n > (1ULL << 32)) {
    throw std::invalid_argument("a latin_hypercube design takes at most 2^32 samples");
  }
}

SampleDraw::SampleDraw(const SweepSampling& sampling, std::size_t dimension, const Distribution& distribution)
    : sampling_(sampling),
      dimension_(dimension),
      distribution_(distribution),
      shift_(static_cast<std::uint32_t>(CounterWord(sampling.seed, kShiftStream + dimension, 0) >> 32)) {}

// Fisher-Yates, exactly specified: the permutation every process draws alike. Strata
// below 2^32 fit 4 bytes (CheckSampleDesign).
const std::vector<std::uint32_t>& SampleDraw::Strata() const {
  std::call_once(strata_once_, [this] {
    const std::uint64_t n = sampling_.samples;
    strata_.resize(n);
    for (std::uint64_t i = 0; i < n; ++i) strata_[i] = static_cast<std::uint32_t>(i);
    for (std::uint64_t i = n; i-- > 1;) {
      std::swap(strata_[i], strata_[CounterWord(sampling_.seed, kPermutationStream + dimension_, i) % (i + 1)]);
    }
  });
  return strata_;
}

double SampleDraw::Uniform(std::uint64_t i) const {
  switch (sampling_.design) {
    case SampleDesign::kRandom:
      return CounterUniform(sampling_.seed, dimension_, i);
    case SampleDesign::kLatinHypercube:
      // (N - 1 + v) / N may round to 1: kept inside the open interval.
      return std::min((static_cast<double>(Strata()[i]) + CounterUniform(sampling_.seed, dimension_, i)) /
                          static_cast<double>(sampling_.samples),
                      std::nextafter(1.0, 0.0));
    case SampleDesign::kSobol:
      return (static_cast<double>(SobolPoint(static_cast<int>(dimension_), i) ^ shift_) + 0.5) * 0x1.0p-32;
  }
  return NAN;
}

std::vector<std::vector<double>> SampleUniforms(const SweepSampling& sampling, std::size_t dimensions) {
  CheckSampleDesign(sampling, dimensions);
  std::vector<std::vector<double>> u(dimensions, std::vector<double>(sampling.samples));
  for (std::size_t d = 0; d < dimensions; ++d) {
    const SampleDraw draw(sampling, d, Distribution{});
    for (std::uint64_t i = 0; i < sampling.samples; ++i) u[d][i] = draw.Uniform(i);
  }
  return u;
}

namespace {

// "name{k=v,k=v}" groups of a Describe() text, in order.
std::vector<std::pair<std::string, std::map<std::string, double>>> DescribedGroups(const std::string& text) {
  std::vector<std::pair<std::string, std::map<std::string, double>>> groups;
  std::size_t at = 0;
  while (at < text.size() && groups.size() < 2) {
    const std::size_t open = text.find('{', at);
    const std::size_t close = text.find('}', at);
    if (open == std::string::npos || close == std::string::npos || close < open) {
      throw std::runtime_error("expected name{key=value,...} groups");
    }
    std::map<std::string, double> params;
    for (std::size_t p = open + 1; p < close;) {
      const std::size_t end = std::min(text.find(',', p), close);
      const std::size_t equals = text.find('=', p);
      double value = 0.0;
      if (equals >= end || !ParseDecimal(std::string_view(text).substr(equals + 1, end - equals - 1), &value) ||
          !params.emplace(text.substr(p, equals - p), value).second) {
        throw std::runtime_error("expected key=number pairs, each key once");
      }
      p = end + 1;
    }
    groups.emplace_back(text.substr(at, open - at), std::move(params));
    at = close + 1;
  }
  if (at < text.size()) throw std::runtime_error("expected at most a distribution and truncated{...}");
  return groups;
}

}  // namespace

Distribution ParseDistribution(const std::string& text) {
  const std::string where = "distribution '" + text.substr(0, 80) + "': ";
  try {
    const auto groups = DescribedGroups(text);
    if (groups.empty()) throw std::runtime_error("empty");
    Distribution dist;
    const auto param = [&](std::size_t g, const char* key) {
      const auto found = groups[g].second.find(key);
      if (found == groups[g].second.end()) throw std::runtime_error(std::string("missing ") + key);
      return found->second;
    };
    const std::string& kind = groups[0].first;
    const char* names[2] = {nullptr, nullptr};
    if (kind == "normal") {
      dist.kind = Distribution::Kind::kNormal;
      names[0] = "mean", names[1] = "sd";
    } else if (kind == "uniform") {
      dist.kind = Distribution::Kind::kUniform;
      names[0] = "from", names[1] = "to";
    } else if (kind == "lognormal") {
      dist.kind = Distribution::Kind::kLogNormal;
      names[0] = "median", names[1] = "sigma";
    } else {
      throw std::runtime_error("expected normal, uniform or lognormal first");
    }
    dist.a = param(0, names[0]);
    dist.b = param(0, names[1]);
    if (groups.size() == 2) {
      if (groups[1].first != "truncated") throw std::runtime_error("expected truncated{...} second");
      if (groups[1].second.count("min") != 0) dist.min = param(1, "min");
      if (groups[1].second.count("max") != 0) dist.max = param(1, "max");
    }
    // What ReadDistribution refuses, and a text that is not Describe()'s own spelling.
    const bool positive = dist.kind == Distribution::Kind::kUniform ? dist.a < dist.b
                          : dist.kind == Distribution::Kind::kNormal ? dist.b > 0.0
                                                                      : dist.a > 0.0 && dist.b > 0.0;
    if (!positive || !(dist.KeptMass() >= kMinKeptMass)) throw std::runtime_error("parameters out of range");
    if (dist.Describe() != text) throw std::runtime_error("not as shapebench writes it");
    return dist;
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(where + error.what());
  }
}

}  // namespace shapebench::bench
