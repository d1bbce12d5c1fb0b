#include "bench/sweep/sweep_metrics_reader.h"

#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>

#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/metrics.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

constexpr std::uint64_t kMaxSeriesLines = 30;

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& candidate : names) {
    if (candidate == name) return true;
  }
  return false;
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

}  // namespace

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

}  // namespace shapebench::bench
