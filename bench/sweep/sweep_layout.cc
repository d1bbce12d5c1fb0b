// SweepLayout, ShortKey, SweepPlotFileName, FivePercentLevel (bench/sweep/sweep_layout.h).
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/ends_with.h"
#include "bench/sweep/sweep_layout.h"

namespace shapebench::bench {
namespace {

std::string SafeName(const std::string& text) {
  std::string name;
  for (const char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == '-';
    name += keep ? c : '_';
  }
  return name;
}

// The robust bands a sweep asks for: each line plot of a ratio metric, then each ratio
// metric checked with a max and not plotted, along the first line plot's keys. The
// threshold: the metric's max check, else band_threshold:, else its 5% level.
std::vector<BandSpec> BandSpecs(const Sweep& sweep) {
  const auto threshold = [&](const std::string& metric) {
    for (const Check& check : sweep.checks) {
      if (check.metric == metric && check.max) return *check.max;
    }
    return sweep.band_threshold ? *sweep.band_threshold : FivePercentLevel(metric);
  };
  std::vector<BandSpec> specs;
  const auto add = [&](const std::string& metric, const SweepPlot& plot) {
    for (const BandSpec& spec : specs) {
      if (spec.metric == metric && spec.x == plot.x && spec.series == plot.series) return;
    }
    const double level = threshold(metric);
    if (std::isfinite(level)) specs.push_back({metric, plot.x, plot.series, level});
  };
  const SweepPlot* first = nullptr;
  for (const SweepPlot& plot : sweep.plots) {
    if (plot.heatmap() || plot.cdf) continue;
    if (first == nullptr) first = &plot;
    if (EndsWith(plot.metric, "_ratio")) add(plot.metric, plot);
  }
  for (const Check& check : sweep.checks) {
    if (first != nullptr && check.max && EndsWith(check.metric, "_ratio")) add(check.metric, *first);
  }
  return specs;
}

}  // namespace

double FivePercentLevel(const std::string& metric) {
  if (metric == "peak_ratio") return 1.05;
  if (metric == "residual_ratio" || metric == "residual_peak_ratio" || metric == "cruise_residual_ratio") {
    return 0.05;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

SweepLayout SweepLayout::Of(const Sweep& sweep) {
  SweepLayout layout;
  layout.name = sweep.name;
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    layout.axis_sizes.push_back(sweep.axes[a].size());
    for (const auto& values : sweep.axes[a].keys) {
      layout.keys.push_back(values.key);
      layout.key_axis.push_back(a);
      layout.key_log.push_back(values.log());
    }
  }
  layout.metrics = sweep.metrics;
  layout.plots = sweep.plots;
  if (!sweep.sampling) layout.bands = BandSpecs(sweep);  // samples are no interval
  return layout;
}

nlohmann::ordered_json SweepLayout::ToJson() const {
  nlohmann::ordered_json json;
  json["name"] = name;
  json["keys"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    json["keys"].push_back({{"key", keys[k]}, {"axis", key_axis[k]}, {"log", bool(key_log[k])}});
  }
  json["axis_sizes"] = axis_sizes;
  json["metrics"] = metrics;
  json["plots"] = nlohmann::ordered_json::array();
  for (const SweepPlot& plot : plots) {
    nlohmann::ordered_json entry;
    entry["metric"] = plot.metric;
    if (plot.heatmap()) {
      entry["heatmap"] = {plot.heatmap_x, plot.heatmap_y};
    } else {
      entry["x"] = plot.x;
      if (!plot.series.empty()) entry["series"] = plot.series;
    }
    if (plot.log) entry["log"] = *plot.log;
    if (plot.cdf) {
      entry["cdf"] = true;
      entry["limits"] = plot.limits;
    }
    json["plots"].push_back(entry);
  }
  if (!bands.empty()) {
    json["bands"] = nlohmann::ordered_json::array();
    for (const BandSpec& band : bands) {
      json["bands"].push_back(
          {{"metric", band.metric}, {"x", band.x}, {"series", band.series}, {"threshold", band.threshold}});
    }
  }
  return json;
}

SweepLayout SweepLayout::FromJson(const nlohmann::json& json) {
  // 1e30 or -1 as an axis or a size is no layout (and converting 1e30 is undefined).
  const auto whole = [](const nlohmann::json& value) {
    if (!value.is_number_unsigned()) throw std::runtime_error("malformed sweep layout: expected a whole number");
    return value.get<std::uint64_t>();
  };
  try {
    for (const char* list : {"keys", "axis_sizes", "plots"}) {
      if (!json.at(list).is_array()) {
        throw std::runtime_error(std::string("malformed sweep layout: ") + list + ": expected an array");
      }
    }
    SweepLayout layout;
    layout.name = json.at("name").get<std::string>();
    for (const auto& key : json.at("keys")) {
      layout.keys.push_back(key.at("key").get<std::string>());
      layout.key_axis.push_back(whole(key.at("axis")));
      layout.key_log.push_back(key.at("log").get<bool>());
    }
    for (const auto& size : json.at("axis_sizes")) layout.axis_sizes.push_back(whole(size));
    layout.metrics = json.at("metrics").get<std::vector<std::string>>();
    for (const auto& entry : json.at("plots")) {
      SweepPlot plot;
      plot.metric = entry.at("metric").get<std::string>();
      if (entry.contains("heatmap")) {
        if (entry.at("heatmap").size() != 2) throw std::runtime_error("malformed sweep layout: heatmap: expected two keys");
        plot.heatmap_x = entry.at("heatmap").at(0).get<std::string>();
        plot.heatmap_y = entry.at("heatmap").at(1).get<std::string>();
      } else {
        plot.x = entry.at("x").get<std::string>();
        if (entry.contains("series")) plot.series = entry.at("series").get<std::string>();
      }
      if (entry.contains("log")) plot.log = entry.at("log").get<bool>();
      if (entry.contains("cdf")) {
        plot.cdf = entry.at("cdf").get<bool>();
        plot.limits = entry.at("limits").get<std::vector<double>>();
      }
      layout.plots.push_back(plot);
    }
    if (json.contains("bands")) {
      for (const auto& entry : json.at("bands")) {
        layout.bands.push_back({entry.at("metric").get<std::string>(), entry.at("x").get<std::string>(),
                                entry.at("series").get<std::string>(), entry.at("threshold").get<double>()});
      }
    }
    for (const auto axis : layout.key_axis) {
      if (axis >= layout.axis_sizes.size()) throw std::runtime_error("a key's axis is out of range");
    }
    for (const auto size : layout.axis_sizes) {
      if (size == 0) throw std::runtime_error("an axis has no values");
    }
    return layout;
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error(std::string("malformed sweep layout: ") + error.what());
  }
}

std::string ShortKey(const std::string& key, const std::vector<std::string>& keys) {
  // Dotted components from the end: the first suffix no other key ends with.
  for (std::size_t dot = key.size(); dot != std::string::npos;) {
    dot = dot == 0 ? std::string::npos : key.rfind('.', dot - 1);
    const std::string suffix = dot == std::string::npos ? key : key.substr(dot + 1);
    bool unique = true;
    for (const std::string& other : keys) {
      if (other == key) continue;
      unique = unique && !(other == suffix || EndsWith(other, "." + suffix));
    }
    if (unique) return suffix;
  }
  return key;
}

std::string SweepPlotFileName(const SweepPlot& plot, const std::vector<std::string>& keys) {
  const auto key = [&](const std::string& name) { return ShortKey(name, keys); };
  if (plot.cdf) return SafeName(plot.metric + "-cdf" + (plot.series.empty() ? "" : "-by-" + key(plot.series))) + ".png";
  if (plot.heatmap()) {
    return SafeName(plot.metric + "-over-" + key(plot.heatmap_x) + "-and-" + key(plot.heatmap_y)) + ".png";
  }
  return SafeName(plot.metric + "-vs-" + key(plot.x) + (plot.series.empty() ? "" : "-by-" + key(plot.series))) +
         ".png";
}

}  // namespace shapebench::bench
