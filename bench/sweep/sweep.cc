#include "bench/sweep/sweep.h"

#include "common/field_list.h"

#include <algorithm>
#include <charconv>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>
#include <memory>
#include <set>
#include <stdexcept>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "bench/config/config_document.h"
#include "bench/run/run_scenario.h"
#include "common/csv.h"
#include "bench/config/key_path.h"
#include "bench/run/located_run.h"
#include "bench/config/node_reader.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/structure_numbers.h"
#include "bench/sweep/shared_command.h"
#include "controller/shaper_registry.h"
#include "common/validation_error.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kSweepKeys = {"name",   "base",    "grid", "metrics", "plots",
                                             "checks", "samples", "seed", "design"};
constexpr const char* kZip = "zip";
constexpr std::uint64_t kMaxSeriesLines = 30;

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& candidate : names) {
    if (candidate == name) return true;
  }
  return false;
}

std::pair<int, int> PositionOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return {1, 1};
  return {mark.line + 1, mark.column + 1};
}

// A value in flow style ({gain: 2}, [1, 2]); a quoted scalar stays quoted.
std::string FlowYaml(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter.SetMapFormat(YAML::Flow);
  emitter.SetSeqFormat(YAML::Flow);
  if (node.IsScalar() && node.Tag() == "!") {
    emitter << YAML::DoubleQuoted << node.Scalar();
  } else {
    emitter << node;
  }
  return emitter.c_str();
}

std::string WithThousands(std::uint64_t n) {
  std::string digits = std::to_string(n);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(at, ",");
  return digits;
}

SweepValues ReadRange(const NodeReader& node, const std::string& key) {
  node.ExpectMap({"from", "to", "steps", "spacing"});
  SweepValues values;
  values.key = key;
  values.kind = SweepValues::Kind::kLinear;
  for (const char* required : {"from", "to", "steps"}) {
    if (!node.Has(required)) {
      throw node.Error(std::string("a range needs from, to and steps; '") + required +
                       "' is missing (e.g. {from: 15, to: 35, steps: 201})");
    }
  }
  values.from = node.Child("from")->AsNumber();
  values.to = node.Child("to")->AsNumber();
  const NodeReader steps = *node.Child("steps");
  const long count = steps.AsInteger();
  if (count < 1) throw steps.Error("must be at least 1, got " + std::to_string(count));
  values.steps = static_cast<std::uint64_t>(count);
  if (values.steps == 1 && values.from != values.to) {
    throw steps.Error("steps 1 gives `from` only; make from and to equal, or steps >= 2");
  }
  node.Read<SweepValues::Kind>(
      "spacing", {{"linear", SweepValues::Kind::kLinear}, {"log", SweepValues::Kind::kLog}},
      &values.kind);
  if (values.log()) {
    for (const char* end : {"from", "to"}) {
      const NodeReader child = *node.Child(end);
      if (!(child.AsNumber() > 0.0)) {
        throw child.Error("log spacing needs from > 0 and to > 0, got " + child.node().Scalar());
      }
    }
  }
  return values;
}

// A list [a, b, ...] or a range {from, to, steps[, spacing]} for `key`.
SweepValues ReadValues(const NodeReader& node, const std::string& key) {
  SweepValues values;
  if (IsDistributionNode(node)) {
    values.key = key;
    values.kind = SweepValues::Kind::kSampled;
    values.distribution = ReadDistribution(node);
  } else if (node.node().IsMap()) {
    values = ReadRange(node, key);
  } else if (node.node().IsSequence()) {
    values.key = key;
    values.kind = SweepValues::Kind::kList;
    for (const NodeReader& element : node.Elements()) {
      const YAML::Node& value = element.node();
      const bool plain = value.IsScalar() && value.Tag() != "!";
      values.texts.push_back(value.IsScalar() ? value.Scalar() : FlowYaml(value));
      values.yamls.push_back(plain ? value.Scalar() : FlowYaml(value));
      values.positions.push_back(PositionOf(value));
    }
    if (values.texts.empty()) throw node.Error("expected at least one value");
  } else {
    throw node.Error(
        "expected a list of values [a, b, ...] or a range {from: A, to: B, steps: N}, or a distribution "
        "{normal: {mean: M, sd: S}} (uniform: {from, to}, lognormal: {median, sigma}; truncated: {min, max})");
  }
  std::tie(values.line, values.column) = PositionOf(node.node());
  return values;
}

// The (key node, value) entries of a mapping, in order; duplicate keys are errors.
std::vector<std::pair<YAML::Node, NodeReader>> MapEntries(const ConfigDocument& document,
                                                          const NodeReader& map) {
  if (!map.IsMap()) throw map.Error("expected a mapping");
  std::vector<std::pair<YAML::Node, NodeReader>> entries;
  std::set<std::string> seen;
  for (const auto& entry : map.node()) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
    const std::string path = ChildPath(map.path(), key);
    if (!entry.first.IsScalar()) {
      throw document.ErrorAt(entry.first, map.path(), "expected a plain key, got a complex key");
    }
    if (!seen.insert(key).second) throw document.ErrorAt(entry.first, path, "duplicate key '" + key + "'");
    entries.emplace_back(entry.first, NodeReader(document, entry.second, path));
  }
  return entries;
}

SweepValues ReadKeyValues(const ConfigDocument& document, const YAML::Node& key_node,
                          const NodeReader& value) {
  const std::string key = key_node.Scalar();
  if (!ParseKeyPath(key)) {
    throw document.ErrorAt(key_node, value.path(),
                           "not a key path; expected scenario keys joined by '.' with optional "
                           "[INDEX], e.g. machine.modes[0].frequency_hz");
  }
  return ReadValues(value, key);
}

SweepAxis ReadZipGroup(const ConfigDocument& document, const NodeReader& group) {
  SweepAxis axis;
  for (const auto& [key_node, value] : MapEntries(document, group)) {
    axis.keys.push_back(ReadKeyValues(document, key_node, value));
    if (axis.keys.back().kind == SweepValues::Kind::kSampled) {
      throw value.Error("a distribution cannot be in a zip group: every distribution key of the grid "
                        "already moves with the one axis of samples");
    }
    if (axis.keys.back().size() != axis.keys.front().size()) {
      throw value.Error("zip keys move together and need as many values each: '" +
                        axis.keys.front().key + "' has " +
                        std::to_string(axis.keys.front().size()) + ", this one " +
                        std::to_string(axis.keys.back().size()));
    }
  }
  if (axis.keys.empty()) throw group.Error("expected at least one key in a zip group");
  return axis;
}

std::vector<SweepAxis> ReadGrid(const ConfigDocument& document, const NodeReader& grid) {
  std::vector<SweepAxis> axes;
  for (const auto& [key_node, value] : MapEntries(document, grid)) {
    if (key_node.Scalar() != kZip) {
      axes.push_back(SweepAxis{{ReadKeyValues(document, key_node, value)}});
      continue;
    }
    if (value.node().IsSequence()) {
      for (const NodeReader& group : value.Elements()) axes.push_back(ReadZipGroup(document, group));
      if (value.node().size() == 0) throw value.Error("expected at least one zip group");
    } else if (value.IsMap()) {
      axes.push_back(ReadZipGroup(document, value));
    } else {
      throw value.Error("expected a mapping of keys to lists or ranges of equal length (or a "
                        "list of such mappings)");
    }
  }
  if (axes.empty()) {
    throw grid.Error("expected at least one key, e.g. machine.modes[0].frequency_hz: "
                     "{from: 15, to: 35, steps: 201}");
  }
  // The distribution keys become one axis (of samples) at the place of the first.
  std::vector<SweepAxis> merged;
  std::size_t sample_axis = axes.size();
  for (SweepAxis& axis : axes) {
    if (axis.keys.front().kind != SweepValues::Kind::kSampled) {
      merged.push_back(std::move(axis));
    } else if (sample_axis == axes.size()) {
      sample_axis = merged.size();
      merged.push_back(std::move(axis));
    } else {
      merged[sample_axis].keys.push_back(std::move(axis.keys.front()));
    }
  }
  axes = std::move(merged);
  // A key and a key inside it would overwrite each other.
  std::vector<const SweepValues*> all;
  for (const auto& axis : axes) {
    for (const auto& values : axis.keys) all.push_back(&values);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (IsPathPrefix(all[j]->key, all[i]->key) || IsPathPrefix(all[i]->key, all[j]->key)) {
        throw ConfigError(document.OriginOf("").file, all[i]->line, all[i]->column,
                          ChildPath("grid", all[i]->key),
                          all[i]->key == all[j]->key
                              ? "swept twice (also at line " + std::to_string(all[j]->line) + ")"
                              : "overlaps '" + all[j]->key + "' (line " +
                                    std::to_string(all[j]->line) +
                                    "): a key and a key inside it cannot both be swept");
      }
    }
  }
  return axes;
}

// samples:, seed:, design: and the samples of every distribution key (bench/sweep/sampling.h).
void DrawSamples(Sweep* sweep, const NodeReader& top, const SweepLoadOptions& options) {
  sweep->sampling = ReadSampling(top);
  std::vector<SweepValues*> sampled;
  for (std::size_t a = 0; a < sweep->axes.size(); ++a) {
    for (SweepValues& values : sweep->axes[a].keys) {
      if (values.kind != SweepValues::Kind::kSampled) continue;
      sampled.push_back(&values);
      sweep->sample_axis = a;
    }
  }
  if (sampled.empty()) {
    if (sweep->sampling) {
      throw top.Child("samples")->Error("samples: needs a distribution key in grid:, e.g. "
                                        "machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}}");
    }
    return;
  }
  if (!sweep->sampling) {
    const SweepValues& first = *sampled.front();
    throw ConfigError(sweep->file, first.line, first.column, ChildPath("grid", first.key),
                      "a distribution needs samples: N at the top of the sweep (and optionally seed: S, "
                      "design: random|latin_hypercube|sobol)");
  }
  // The grid's size before the samples are drawn: N values per key are held in memory.
  std::uint64_t others = 1;
  for (std::size_t a = 0; a < sweep->axes.size(); ++a) {
    if (a == sweep->sample_axis) continue;
    const std::uint64_t size = sweep->axes[a].size();
    others = others > std::numeric_limits<std::uint64_t>::max() / size ? std::numeric_limits<std::uint64_t>::max()
                                                                         : others * size;
  }
  const std::uint64_t n = sweep->sampling->samples;
  if (!options.force && (n > options.max_points || others > options.max_points / n)) {
    throw top.Child("samples")->Error("the grid has " + std::to_string(n) + " samples" +
                                      (others > 1 ? " times " + std::to_string(others) + " points" : "") +
                                      ", more than the " + std::to_string(options.max_points) +
                                      " points a sweep runs without --force; pass --force to run it anyway");
  }
  std::vector<std::vector<double>> uniforms;
  try {
    uniforms = SampleUniforms(*sweep->sampling, sampled.size());
  } catch (const std::invalid_argument& error) {
    const auto design = top.Child("design");
    throw (design ? *design : *top.Child("samples")).Error(
        error.what() + std::string("; this sweep has ") + std::to_string(sampled.size()) +
        " distribution keys and " + std::to_string(sweep->sampling->samples) + " samples");
  }
  for (std::size_t d = 0; d < sampled.size(); ++d) {
    std::vector<double> values(uniforms[d].size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = sampled[d]->distribution->Quantile(uniforms[d][i]);
    sampled[d]->samples = std::make_shared<const std::vector<double>>(std::move(values));
  }
}

// A sweep's checks: min/max checks of every point (ReadChecks) and, in a sampled sweep,
// quantile and yield gates (bench/sweep/sampling.h, SampleGate).
void ReadSweepChecks(const NodeReader& checks, Sweep* sweep) {
  bool gates = false;
  for (const auto& [name, bounds] : checks.Entries()) {
    gates = gates || name == "yield" || (bounds.IsMap() && bounds.Has("quantile"));
  }
  if (!gates) {
    sweep->checks = ReadChecks(checks);
    return;
  }
  std::vector<std::string> allowed = AllMetricNames();
  allowed.push_back("yield");
  checks.ExpectMap(allowed);
  for (const auto& [name, bounds] : checks.Entries()) {
    const bool yield = name == "yield";
    if (!bounds.IsMap()) throw bounds.Error(yield ? "expected {min: P}" : "expected {min: A, max: B} or {quantile: Q, max: B}");
    bounds.ExpectMap(yield ? std::vector<std::string>{"min"} : std::vector<std::string>{"min", "max", "quantile"});
    if (!sweep->sampling && (yield || bounds.Has("quantile"))) {
      throw (yield ? bounds : *bounds.Child("quantile")).Error(
          "a " + std::string(yield ? "yield" : "quantile") + " treats the points as samples; it needs a sampled "
          "sweep (samples: N and a distribution key in grid:)");
    }
    std::optional<double> min;
    std::optional<double> max;
    if (const auto low = bounds.Child("min")) min = low->AsNumber();
    if (const auto high = bounds.Child("max")) max = high->AsNumber();
    if (!min && !max) throw bounds.Error(yield ? "expected min: P, the least fraction of samples that pass" : "expected min and/or max");
    if (min && max && *min > *max) throw bounds.Child("max")->Error("must not be below min (" + ShortestDouble(*min) + ")");
    if (yield) {
      if (!(*min > 0.0 && *min <= 1.0)) throw bounds.Child("min")->Error("a yield is a fraction: expected 0 < min <= 1, got " + ShortestDouble(*min));
      sweep->gates.push_back(SampleGate{SampleGate::Kind::kYield, "yield", 0.0, min, std::nullopt});
    } else if (const auto quantile = bounds.Child("quantile")) {
      const double q = quantile->AsNumber();
      if (!(q > 0.0 && q < 1.0)) throw quantile->Error("expected a level 0 < quantile < 1, got " + quantile->node().Scalar());
      sweep->gates.push_back(SampleGate{SampleGate::Kind::kQuantile, name, q, min, max});
    } else {
      sweep->checks.push_back(Check{name, min, max});
    }
  }
  const bool yield = std::any_of(sweep->gates.begin(), sweep->gates.end(),
                                 [](const SampleGate& gate) { return gate.kind == SampleGate::Kind::kYield; });
  if (yield && sweep->checks.empty()) {
    throw checks.Child("yield")->Error("a yield is the fraction of samples passing the other checks; add a "
                                       "min/max check, e.g. residual_ratio: {max: 0.05}");
  }
}

std::uint64_t CountPoints(const std::vector<SweepAxis>& axes, const NodeReader& grid) {
  std::uint64_t points = 1;
  for (const auto& axis : axes) {
    if (axis.size() > std::numeric_limits<std::uint64_t>::max() / points) {
      throw grid.Error("the grid has more than 2^64 points");
    }
    points *= axis.size();
  }
  return points;
}

std::vector<std::string> ReadMetrics(const NodeReader& node) {
  const std::vector<std::string> names = AllMetricNames();
  std::vector<std::string> metrics;
  for (const NodeReader& element : node.Elements()) {
    const std::string name = element.AsString();
    if (!Contains(names, name)) {
      throw element.Error("unknown metric '" + name + "'; allowed: " + JoinNames(names, ", "));
    }
    if (Contains(metrics, name)) throw element.Error("metric '" + name + "' is listed twice");
    metrics.push_back(name);
  }
  if (metrics.empty()) throw node.Error("expected at least one metric (or leave metrics: out for all)");
  return metrics;
}

// A plot entry with cdf: true: the metric's empirical CDF over the samples, one curve per
// value of `series:` (a key of another axis).
template <typename AxisOf>
void ReadCdfPlot(const NodeReader& entry, const std::vector<SweepAxis>& axes, const AxisOf& axis_of,
                 SweepPlot* plot) {
  const auto sampled = std::find_if(axes.begin(), axes.end(), [](const SweepAxis& axis) {
    return axis.keys.front().kind == SweepValues::Kind::kSampled;
  });
  if (sampled == axes.end()) {
    throw entry.Child("cdf")->Error("an empirical CDF is drawn over samples; it needs a sampled sweep "
                                    "(samples: N and a distribution key in grid:)");
  }
  for (const char* other : {"x", "heatmap"}) {
    if (const auto child = entry.Child(other)) {
      throw child->Error("a cdf plot is drawn over the samples: give metric: and optionally series:, not " +
                         std::string(other) + ":");
    }
  }
  plot->x = sampled->keys.front().key;
  if (const auto series = entry.Child("series")) {
    std::size_t series_axis = 0;
    std::tie(plot->series, series_axis) = axis_of(*series);
    if (series_axis == static_cast<std::size_t>(sampled - axes.begin())) {
      throw series->Error("'" + plot->series + "' moves with the samples; choose a key of another axis");
    }
    if (axes[series_axis].size() > kMaxSeriesLines) {
      throw series->Error("'" + plot->series + "' has " + std::to_string(axes[series_axis].size()) +
                          " values; a plot shows at most " + std::to_string(kMaxSeriesLines) + " lines");
    }
  }
}

// A sampled sweep's default plots: the empirical CDF of each metric DefaultPlots would
// draw, one curve per value of the first other axis' first key when it is short.
std::vector<SweepPlot> DefaultCdfPlots(std::vector<SweepPlot> plots, const std::vector<SweepAxis>& axes,
                                       std::size_t sample_axis) {
  for (SweepPlot& plot : plots) {
    plot.cdf = true;
    plot.x = axes[sample_axis].keys.front().key;
    plot.series.clear();
    for (std::size_t a = 0; a < axes.size(); ++a) {
      if (a == sample_axis) continue;
      if (axes[a].size() <= kMaxSeriesLines) plot.series = axes[a].keys.front().key;
      break;
    }
  }
  return plots;
}

// Each cdf plot's limits: the bounds of the checks and gates on its metric.
void SetCdfLimits(Sweep* sweep) {
  for (SweepPlot& plot : sweep->plots) {
    if (!plot.cdf) continue;
    for (const Check& check : sweep->checks) {
      if (check.metric != plot.metric) continue;
      for (const auto& bound : {check.min, check.max}) {
        if (bound) plot.limits.push_back(*bound);
      }
    }
    for (const SampleGate& gate : sweep->gates) {
      if (gate.metric != plot.metric) continue;
      for (const auto& bound : {gate.min, gate.max}) {
        if (bound) plot.limits.push_back(*bound);
      }
    }
  }
}

std::vector<SweepPlot> ReadPlots(const NodeReader& node, const std::vector<std::string>& metrics,
                                 const std::vector<SweepAxis>& axes) {
  auto axis_of = [&](const NodeReader& key_node) {
    const std::string key = key_node.AsString();
    std::vector<std::string> keys;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      for (const auto& values : axes[a].keys) {
        if (values.key == key) return std::make_pair(key, a);
        keys.push_back(values.key);
      }
    }
    throw key_node.Error("'" + key + "' is not a key of the grid; grid keys: " +
                         JoinNames(keys, ", "));
  };
  std::vector<SweepPlot> plots;
  for (const NodeReader& entry : node.Elements()) {
    entry.ExpectMap({"metric", "x", "series", "heatmap", "log", "cdf"});
    SweepPlot plot;
    const auto metric = entry.Child("metric");
    if (!metric) throw entry.Error("a plot needs metric: and x: (or heatmap: [X_KEY, Y_KEY])");
    plot.metric = metric->AsString();
    if (!Contains(metrics, plot.metric)) {
      throw metric->Error(
          Contains(MetricNames(), plot.metric)
              ? "metric '" + plot.metric + "' is not kept; add it to metrics: (kept: " +
                    JoinNames(metrics, ", ") + ")"
              : "unknown metric '" + plot.metric + "'; kept metrics: " + JoinNames(metrics, ", "));
    }
    const auto x = entry.Child("x");
    const auto heatmap = entry.Child("heatmap");
    if (const auto cdf = entry.Child("cdf")) plot.cdf = cdf->AsChoice<bool>({{"true", true}, {"false", false}});
    if (plot.cdf) {
      ReadCdfPlot(entry, axes, axis_of, &plot);
      plots.push_back(plot);
      continue;
    }
    if (x && heatmap) throw heatmap->Error("give x: (a line plot) or heatmap: (a heat map), not both");
    if (!x && !heatmap) throw entry.Error("a plot needs x: KEY (a line plot) or heatmap: [X_KEY, Y_KEY]");
    if (x) {
      std::size_t x_axis = 0;
      std::tie(plot.x, x_axis) = axis_of(*x);
      if (const auto series = entry.Child("series")) {
        std::size_t series_axis = 0;
        std::tie(plot.series, series_axis) = axis_of(*series);
        if (series_axis == x_axis) {
          throw series->Error("'" + plot.series + "' moves with '" + plot.x +
                              "' (one axis of the grid); choose a key of another axis");
        }
        if (axes[series_axis].size() > kMaxSeriesLines) {
          throw series->Error("'" + plot.series + "' has " +
                              std::to_string(axes[series_axis].size()) +
                              " values; a plot shows at most " + std::to_string(kMaxSeriesLines) +
                              " lines (use heatmap: for two dense keys)");
        }
      }
    } else {
      if (const auto series = entry.Child("series")) {
        throw series->Error("series: belongs to a line plot (x:), not to a heat map");
      }
      const std::vector<NodeReader> keys = heatmap->Elements();
      if (keys.size() != 2) throw heatmap->Error("expected two keys: [X_KEY, Y_KEY]");
      std::size_t axis_x = 0;
      std::size_t axis_y = 0;
      std::tie(plot.heatmap_x, axis_x) = axis_of(keys[0]);
      std::tie(plot.heatmap_y, axis_y) = axis_of(keys[1]);
      if (axis_x == axis_y) {
        throw keys[1].Error("'" + plot.heatmap_y + "' moves with '" + plot.heatmap_x +
                            "' (one axis of the grid); a heat map needs keys of two axes");
      }
    }
    if (const auto log = entry.Child("log")) {
      plot.log = log->AsChoice<bool>({{"true", true}, {"false", false}});
    }
    plots.push_back(plot);
  }
  return plots;
}

// Default plots: each kept ratio metric (all kept metrics when metrics: is given) against
// the first key, one line per value of the second axis' first key when it is short.
std::vector<SweepPlot> DefaultPlots(const std::vector<std::string>& metrics, bool metrics_given,
                                    const std::vector<SweepAxis>& axes) {
  std::vector<SweepPlot> plots;
  for (const std::string& metric : metrics) {
    if (!metrics_given && metric != "peak_ratio" && metric != "residual_ratio") continue;
    SweepPlot plot;
    plot.metric = metric;
    plot.x = axes[0].keys[0].key;
    if (axes.size() > 1 && axes[1].size() <= kMaxSeriesLines) plot.series = axes[1].keys[0].key;
    plots.push_back(plot);
  }
  return plots;
}

// The position of the `index`-th grid override's value for this point.
std::pair<int, int> OverridePosition(const Sweep& sweep, const SweepPoint& point, int index) {
  const std::vector<std::uint64_t> digits = sweep.AxisIndices(point.index);
  int k = 0;
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    for (const auto& values : sweep.axes[a].keys) {
      if (++k == index) return values.Position(digits[a]);
    }
  }
  return {1, 1};
}

// A ConfigError from loading a point: the grid's overrides are located in the sweep file,
// the command line's keep their own --set numbering.
ConfigError Relocated(const Sweep& sweep, const SweepPoint& point, const ConfigError& error) {
  if (error.file() != kOverrideSource) return error;
  const int grid_overrides = static_cast<int>(point.keys.size());
  if (error.line() >= 1 && error.line() <= grid_overrides) {
    const auto [line, column] = OverridePosition(sweep, point, error.line());
    return ConfigError(sweep.file, line, column, error.key_path(), error.message());
  }
  return ConfigError(kOverrideSource, error.line() - grid_overrides, 1, error.key_path(),
                     error.message());
}

bool IsGridOverrideError(const SweepPoint& point, const ConfigError& error) {
  return error.file() == kOverrideSource && error.line() >= 1 &&
         error.line() <= static_cast<int>(point.keys.size());
}

// Point 0 against the base: a swept key must fit the scenario's tree and be a scenario
// key. Values are the points' business (a bad one is that point's error row).
void CheckGridAgainstBase(const Sweep& sweep, const std::vector<Override>& sets) {
  const SweepPoint point = MakePoint(sweep, 0, sets);
  try {
    BuildScenarioTree(sweep.base, point.overrides);
  } catch (const ConfigError& error) {
    if (IsGridOverrideError(point, error)) {
      const ConfigError located = Relocated(sweep, point, error);
      throw ConfigError(located.file(), located.line(), located.column(), error.key_path(),
                        error.message() + " (in the base scenario " + sweep.base + ")");
    }
    throw;
  }
  try {
    LoadOptions options;
    options.design_modes = sweep.design_modes;
    LoadScenario(sweep.base, point.overrides, options);
  } catch (const ConfigError& error) {
    const std::string unknown = "unknown key";
    if (IsGridOverrideError(point, error) &&
        error.message().compare(0, unknown.size(), unknown) == 0 &&
        error.key_path() == point.overrides[error.line() - 1].key_path) {
      throw Relocated(sweep, point, error);
    }
  }
}

// The note of a sweep whose pattern is left to the machine while grid keys change the
// machine: the points keep the base's design (Sweep::design_modes); empty otherwise.
std::string MachineDefaultsNote(const Sweep& sweep, const Scenario& base) {
  const controller::PatternConfig& pattern = base.controller.pattern;
  std::string keys;
  bool pattern_swept = false;
  for (const std::string& key : sweep.Keys()) {
    if (IsPathPrefix("machine", key)) keys += (keys.empty() ? "" : ", ") + key;
    pattern_swept = pattern_swept || IsPathPrefix("controller.pattern", key) || IsPathPrefix(key, "controller.pattern");
  }
  const bool defaulted = pattern.frequency_from_machine || pattern.frequencies_from_machine || pattern.damping_from_machine;
  const bool shapes = controller::FindShaper(pattern.method).kind != controller::ShaperKind::kNone;
  if (keys.empty() || !defaulted || !(shapes || pattern_swept) || !sweep.design_modes ||
      sweep.design_modes->modes.empty()) {
    return "";
  }
  std::string design;
  for (const double f : pattern.DesignFrequencies()) design += (design.empty() ? "" : ", ") + ShortestDouble(f);
  return "note: " + sweep.file + ": the pattern's design is left to the machine; every point takes the "
         "base scenario's (" + design + " Hz, from its participating modes along " + sweep.design_modes->axes +
         "), not its own: the swept keys " + keys + " move the plant, not the pattern "
         "(give controller.pattern.frequency_hz to choose it)";
}

void CheckSetsAvoidGrid(const Sweep& sweep, const std::vector<Override>& sets) {
  for (std::size_t i = 0; i < sets.size(); ++i) {
    for (const auto& axis : sweep.axes) {
      for (const auto& values : axis.keys) {
        if (IsPathPrefix(values.key, sets[i].key_path) ||
            IsPathPrefix(sets[i].key_path, values.key)) {
          throw ConfigError(kOverrideSource, static_cast<int>(i) + 1, 1, sets[i].key_path,
                            "'" + values.key + "' is swept by the grid (" + sweep.file + ":" +
                                std::to_string(values.line) +
                                "); change the grid, not the swept key");
        }
      }
    }
  }
}

std::string ResolveBase(const NodeReader& base, const std::string& sweep_path) {
  const std::string reference = base.AsString();
  const fs::path resolved = fs::path(reference).is_absolute()
                                ? fs::path(reference)
                                : fs::path(sweep_path).parent_path() / reference;
  const std::string file = resolved.lexically_normal().string();
  try {
    const YAML::Node root = ConfigDocument::ParseFile(file);
    if (root.IsMap() && root["base"] && root["grid"]) {
      throw base.Error("'" + reference + "' is a sweep; base: names a scenario");
    }
  } catch (const ConfigError& error) {
    if (error.line() > 0 || error.file() != file) throw;
    const std::string shown = file == reference ? "'" + reference + "'" : "'" + reference + "' (" + file + ")";
    throw base.Error("base scenario " + shown + ": " + error.message());
  }
  return file;
}

void HashText(std::uint64_t* hash, const std::string& text) {
  for (const unsigned char c : text) {
    *hash ^= c;
    *hash *= 0x100000001b3ULL;
  }
  *hash ^= 0xff;  // a separator no text contains
  *hash *= 0x100000001b3ULL;
}

// A file the hash covers (the G-code program): unreadable is an error, never an empty hash input.
std::string FileBytes(const std::string& path) {
  std::string text;
  std::string error;
  if (!ReadInputFile(path, &text, &error)) throw ConfigError(path, 0, 0, "", error);
  return text;
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::uint64_t SweepValues::size() const {
  if (kind == Kind::kSampled) return samples ? static_cast<std::uint64_t>(samples->size()) : 0;
  return kind == Kind::kList ? static_cast<std::uint64_t>(texts.size()) : steps;
}

namespace {

// The --set options a scenario was loaded with, as a key: "key=value\n" each.
std::string OverridesKey(std::vector<Override>::const_iterator first, std::vector<Override>::const_iterator last) {
  std::string key;
  for (; first != last; ++first) key += first->key_path + "=" + first->value_yaml + "\n";
  return key;
}

// printf's "%.15g" (std::to_chars' general format with a precision is that, to the
// character), without printf's cost: a sweep writes one a point.
std::string Digits15(double value) {
  char text[40];
  const std::to_chars_result written = std::to_chars(text, text + sizeof text, value, std::chars_format::general, 15);
  return std::string(text, written.ptr);
}

}  // namespace

std::string SweepValues::Text(std::uint64_t i) const {
  if (kind == Kind::kList) return texts[i];
  if (kind == Kind::kSampled) return Digits15((*samples)[i]);
  if (i == 0) return ShortestDouble(from);
  if (i + 1 == steps) return ShortestDouble(to);
  // Inner values in 15 significant digits: 15.3, not 15.300000000000001 (the value a
  // point runs with is the text it shows).
  const double last = static_cast<double>(steps - 1);
  const double k = static_cast<double>(i);
  const double value =
      kind == Kind::kLinear
          ? from + (to - from) * k / last
          : std::exp(std::log(from) + (std::log(to) - std::log(from)) * k / last);
  return Digits15(value);
}

std::string SweepValues::Yaml(std::uint64_t i) const {
  return kind == Kind::kList ? yamls[i] : Text(i);
}

std::pair<int, int> SweepValues::Position(std::uint64_t i) const {
  return kind == Kind::kList ? positions[i] : std::make_pair(line, column);
}

std::vector<std::string> Sweep::Keys() const {
  std::vector<std::string> keys;
  for (const auto& axis : axes) {
    for (const auto& values : axis.keys) keys.push_back(values.key);
  }
  return keys;
}

std::vector<std::uint64_t> Sweep::AxisIndices(std::uint64_t point) const {
  std::vector<std::uint64_t> digits(axes.size(), 0);
  for (std::size_t a = axes.size(); a-- > 0;) {
    digits[a] = point % axes[a].size();
    point /= axes[a].size();
  }
  return digits;
}

std::string SweepPoint::Label() const {
  std::string label;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    label += (i == 0 ? "" : ", ") + keys[i] + "=" + texts[i];
  }
  return label;
}

SweepPoint MakePoint(const Sweep& sweep, std::uint64_t index, const std::vector<Override>& sets) {
  SweepPoint point;
  point.index = index;
  const std::vector<std::uint64_t> digits = sweep.AxisIndices(index);
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    for (const auto& values : sweep.axes[a].keys) {
      point.keys.push_back(values.key);
      point.texts.push_back(values.Text(digits[a]));
      // Yaml is Text except for a list's values (one conversion a point, not two).
      point.overrides.push_back(
          Override{values.key, values.kind == SweepValues::Kind::kList ? values.Yaml(digits[a]) : point.texts.back()});
    }
  }
  point.overrides.insert(point.overrides.end(), sets.begin(), sets.end());
  return point;
}

bool IsSweepFile(const std::string& path) {
  try {
    const YAML::Node root = ConfigDocument::ParseFile(path);
    return root.IsMap() && root["base"].IsDefined() && root["grid"].IsDefined();
  } catch (const std::exception&) {
    return false;
  }
}

std::string SweepPath(const std::string& path) {
  // The path from the working directory (absolute when the file is outside it), its
  // directory's symbolic links, "." and ".." resolved as the kernel resolves them. The
  // file name itself is kept (a link to a sweep names that link). Anything that cannot be
  // resolved (a missing directory) is left as given, for the reader to report.
  std::error_code ec;
  const fs::path given(path);
  const fs::path name = given.filename();
  if (name.empty() || name == "." || name == "..") return path;
  const fs::path dir = fs::canonical(fs::absolute(given, ec).parent_path(), ec);
  if (ec) return path;
  const fs::path cwd = fs::canonical(fs::current_path(ec), ec);
  if (ec) return (dir / name).string();
  const fs::path relative = dir.lexically_relative(cwd);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  if (!inside) return (dir / name).string();
  return relative == "." ? name.string() : (relative / name).string();
}

Sweep LoadSweep(const std::string& given_path, const std::vector<Override>& sets,
                const SweepLoadOptions& options) {
  // The sweep's identity in what it writes (results.csv's error locations, manifest.json,
  // the base's path) is its file, not the spelling on the command line: shards run as
  // configs/s.yaml, ./configs/../configs/s.yaml and /abs/configs/s.yaml merge into the
  // unsharded bytes. A canonical path (not a content hash) so that messages still point
  // at the file; relative to the working directory so that shards run from the same
  // checkout on different machines agree too (docs/sweeps.md, shards and merge).
  const std::string path = SweepPath(given_path);
  const ConfigDocument document(ConfigDocument::ParseFile(path), path);
  const NodeReader top(document, document.root(), "");
  if (!top.IsMap()) throw top.Error("expected a mapping of sweep keys (" + JoinNames(kSweepKeys, ", ") + ")");
  top.ExpectMap(kSweepKeys);
  for (const char* required : {"base", "grid"}) {
    if (!top.Has(required)) {
      throw top.Error(std::string("a sweep needs base: (a scenario) and grid: (keys and their "
                                  "values); '") + required + "' is missing");
    }
  }
  Sweep sweep;
  sweep.file = path;
  sweep.name = fs::path(path).stem().string();
  top.Read("name", &sweep.name);
  const NodeReader base = *top.Child("base");
  sweep.base = ResolveBase(base, path);
  const NodeReader grid = *top.Child("grid");
  if (!grid.IsMap()) {
    throw grid.Error("expected a mapping of key paths to lists or ranges, e.g. "
                     "machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 201}");
  }
  sweep.axes = ReadGrid(document, grid);
  DrawSamples(&sweep, top, options);
  sweep.points = CountPoints(sweep.axes, grid);
  if (sweep.points > options.max_points && !options.force) {
    throw grid.Error("the grid has " + WithThousands(sweep.points) + " points, more than the " +
                     WithThousands(options.max_points) +
                     " a sweep runs without --force; pass --force to run it anyway");
  }
  const auto metrics = top.Child("metrics");
  sweep.metrics = metrics ? ReadMetrics(*metrics) : MetricNames();
  if (const auto plots = top.Child("plots")) {
    sweep.plots = ReadPlots(*plots, sweep.metrics, sweep.axes);
  } else {
    sweep.plots = DefaultPlots(sweep.metrics, metrics.has_value(), sweep.axes);
    if (sweep.sampling) sweep.plots = DefaultCdfPlots(sweep.plots, sweep.axes, sweep.sample_axis);
  }
  if (const auto checks = top.Child("checks")) ReadSweepChecks(*checks, &sweep);
  SetCdfLimits(&sweep);

  static std::atomic<std::uint64_t> next_id{1};
  sweep.id = next_id++;
  CheckSetsAvoidGrid(sweep, sets);
  const auto base_scenario = std::make_shared<const Scenario>(LoadScenario(sweep.base, sets));  // must be valid
  sweep.design_modes = FindDesignModes(base_scenario->machine, base_scenario->RunProgram());
  sweep.note = MachineDefaultsNote(sweep, *base_scenario);
  sweep.base_scenario = base_scenario;
  sweep.base_hash = BaseScenarioHash(sweep);  // the files as this load read them
  sweep.base_sets_key = OverridesKey(sets.begin(), sets.end());
  CheckGridAgainstBase(sweep, sets);
  return sweep;
}

namespace {

// Keys the command (controller::GenerateProgramCommand: controller, program, move, the
// machine's stroke and driven axis) does not read: the structure (the machine forms' lists,
// as their field lists name them, a lumped axis' `damping:` block, a modal form's
// `modal_file`), the drive, the integrator, the output view, the checks.
bool PlantOnlyKey(const std::string& key) {
  for (const char* prefix : {"drive", "integrator", "output", "checks"}) {
    if (IsPathPrefix(prefix, key)) return true;
  }
  static const std::vector<std::string> lists = [] {
    std::vector<std::string> names;
    model::ForEachMachineForm([&](const auto& form) {
      for (std::string& list : ListNames<std::decay_t<decltype(form)>>()) names.push_back(std::move(list));
    });
    names.emplace_back(model::LumpedDamping::kKey);
    names.emplace_back(model::ModalMachineConfig::kModalFileKey);
    return names;
  }();
  for (const std::string& list : lists) {
    if (IsPathPrefix("machine." + list, key)) return true;
    for (const char* axis : {"x", "y", "z"}) {
      if (IsPathPrefix(std::string("machine.axes.") + axis + "." + list, key)) return true;
    }
  }
  return false;
}

std::string CommandKey(const SweepPoint& point) {
  std::string key;
  for (std::size_t i = 0; i < point.overrides.size(); ++i) {
    const Override& o = point.overrides[i];
    // The --set options (after the point's values) and the swept keys the controller reads.
    if (i >= point.keys.size() || !PlantOnlyKey(o.key_path)) key += o.key_path + "=" + o.value_yaml + "\n";
  }
  return key;
}

// The scenario a point of a sweep loaded on this thread, with what it depends on besides
// the point's own values: the sweep and the --set options.
struct LoadedScenario {
  std::uint64_t sweep_id = 0;
  std::string sets_key;
  Scenario scenario;
  double motion_s = 0.0;  // MinimumMotionSeconds(scenario): the same for every such point
};

std::string SetsKey(const SweepPoint& point) {
  return OverridesKey(point.overrides.begin() + static_cast<std::ptrdiff_t>(point.keys.size()),
                      point.overrides.end());
}

// A point that ran with a warning (integrator.cross_check: warn) says so in its row's
// error column; its status stays ok.
std::string WarningText(const std::vector<std::string>& warnings) {
  std::string text;
  for (const std::string& warning : warnings) text += (text.empty() ? "warning: " : "; warning: ") + warning;
  return text;
}

}  // namespace

PointOutcome RunPoint(const Sweep& sweep, const std::vector<Override>& sets, std::uint64_t index) {
  return RunPoint(sweep, MakePoint(sweep, index, sets));  // (MakePoint reads the grid: no input error)
}

PointOutcome RunPoint(const Sweep& sweep, const SweepPoint& point) {
  PointOutcome outcome;
  outcome.index = point.index;
  try {
    // A point that changes only numbers of the structure takes the scenario the last
    // point loaded on this thread and sets them (structure_numbers.h). Otherwise the base
    // (and its machine file) is parsed once per thread (ParseCacheScope); a point whose
    // scenario does not load is loaded again without, which locates its error.
    thread_local LoadedScenario loaded;
    const bool structure_only =
        std::all_of(point.keys.begin(), point.keys.end(), IsStructureNumberKey);
    const std::string sets_key = SetsKey(point);
    Scenario loaded_here;
    const Scenario* run = &loaded_here;
    bool set = false;
    if (structure_only && sweep.id != 0 && !(loaded.sweep_id == sweep.id && loaded.sets_key == sets_key) &&
        sweep.base_scenario != nullptr && sweep.base_sets_key == sets_key) {
      loaded = {sweep.id, sets_key, *sweep.base_scenario, MinimumMotionSeconds(*sweep.base_scenario)};
    }
    if (structure_only && loaded.sweep_id == sweep.id && sweep.id != 0 && loaded.sets_key == sets_key) {
      // Set in place: every such point sets every swept number, so what the last one set
      // is overwritten (no copy of the scenario a point). A refused value may have left some
      // set: the cache is dropped then.
      const std::vector<Override> values(point.overrides.begin(),
                                         point.overrides.begin() + static_cast<std::ptrdiff_t>(point.keys.size()));
      set = SetStructureNumbers(&loaded.scenario, values, loaded.motion_s);
      if (set) {
        run = &loaded.scenario;
      } else {
        loaded = LoadedScenario{};
      }
    }
    if (!set) {
      LoadOptions options;
      options.design_modes = sweep.design_modes;  // the base's: the pattern stays fixed
      try {
        const ParseCacheScope parse_once;
        loaded_here = LoadScenario(sweep.base, point.overrides, options);
      } catch (const std::exception&) {
        loaded_here = LoadScenario(sweep.base, point.overrides, options);
      }
      if (structure_only) loaded = {sweep.id, sets_key, loaded_here, MinimumMotionSeconds(loaded_here)};
    }
    const Scenario& scenario = *run;
    try {
      // Points that differ only in keys the controller does not read (the natural-period
      // sweep: the plant's frequency) share one command and its samples, generated once for
      // all threads (shared_command.h): the same inputs, the same command, so the same
      // metrics bit for bit (tests/bench/sweep_test.cc checks the rows against independent
      // runs, tests/bench/shared_command_test.cc against a sweep without sharing).
      RunOptions options{false};  // no trace needed
      if (sweep.id != 0 && SharedCommandCache::Enabled()) {
        // The command this thread used last, when the point's is the same one: no lock and
        // no count of its owners a point (the threads of a sweep would take turns at the
        // cache's lock and at the shared count's cache line; the thread's copy keeps it).
        thread_local struct {
          std::uint64_t sweep_id = 0;
          std::string key;
          std::shared_ptr<const SharedCommand> command;
        } last;
        std::string key = CommandKey(point);
        if (last.command == nullptr || last.sweep_id != sweep.id || last.key != key) {
          std::shared_ptr<const SharedCommand> got = SharedCommandCache::Instance().Get(sweep.id, key, [&] {
            return GenerateScenarioCommand(scenario, scenario.RunProgram());
          });
          last = {sweep.id, std::move(key), std::move(got)};
        }
        options.command = &last.command->command;
        options.samples = &last.command->samples;
      }
      const RunResult result = RunScenario(scenario, options);
      outcome.metrics = result.metrics;
      outcome.error = WarningText(result.warnings);
    } catch (const ValidationError& error) {
      throw LocateValidationError(sweep.base, point.overrides, error);
    }
  } catch (const ConfigError& error) {
    outcome.status = PointOutcome::Status::kBadInput;
    outcome.error = Relocated(sweep, point, error).what();
  } catch (const model::SolverError& error) {
    outcome.status = PointOutcome::Status::kSolverFailed;
    outcome.error = SolverFailureText(error);
  } catch (const std::bad_alloc&) {
    throw;  // the machine's, not the point's: no row, the sweep stops and resumes later
  } catch (const std::exception& error) {
    outcome.status = PointOutcome::Status::kFailed;
    outcome.error = error.what();
  }
  if (!outcome.ok()) outcome.metrics = Metrics{};
  return outcome;
}

std::uint64_t BaseScenarioHash(const Sweep& sweep) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  HashText(&hash, "shapebench sweep 1");
  const YAML::Node base = BuildScenarioTree(sweep.base, {});
  HashText(&hash, YAML::Dump(base));
  if (base.IsMap() && base["program_file"] && base["program_file"].IsScalar()) {
    const fs::path program = fs::path(sweep.base).parent_path() / base["program_file"].Scalar();
    HashText(&hash, FileBytes(program.string()));
  }
  return hash;
}

std::string SweepHash(const Sweep& sweep, const std::vector<Override>& sets) {
  std::uint64_t hash = sweep.base_hash != 0 ? sweep.base_hash : BaseScenarioHash(sweep);
  for (const Override& set : sets) HashText(&hash, set.key_path + "=" + set.value_yaml);
  HashText(&hash, "grid");
  for (const auto& axis : sweep.axes) {
    HashText(&hash, "axis");
    for (const auto& values : axis.keys) {
      HashText(&hash, values.key);
      for (std::uint64_t i = 0; i < values.size(); ++i) HashText(&hash, values.Yaml(i));
    }
  }
  if (sweep.sampling) {
    // The sampling spec itself (its values are in the grid above): a changed design or seed
    // that happened to give the same texts is still another sweep.
    HashText(&hash, "sampling");
    HashText(&hash, std::string(DesignName(sweep.sampling->design)) + " seed " +
                        std::to_string(sweep.sampling->seed) + " samples " + std::to_string(sweep.sampling->samples));
    for (const auto& values : sweep.axes[sweep.sample_axis].keys) HashText(&hash, values.distribution->Describe());
  }
  HashText(&hash, "metrics");
  for (const auto& metric : sweep.metrics) HashText(&hash, metric);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string KeyUnit(const std::string& key) {
  static const std::vector<std::pair<std::string, std::string>> kUnits = {
      {"_mm_min", "mm/min"}, {"_m_s2", "m/s²"}, {"_m_s", "m/s"}, {"_hz", "Hz"},
      {"_mm", "mm"},         {"_kg", "kg"},     {"_1_s", "1/s"}, {"_s", "s"},
      {"_m", "m"}};
  for (const auto& [suffix, unit] : kUnits) {
    if (EndsWith(key, suffix)) return unit;
  }
  return "";
}

}  // namespace shapebench::bench
