// The plots of a sweep, drawn from results.csv (so `merge` draws the same ones): a metric
// against one swept key, one line per value of a second key, or a heat map over two
// keys. Axes carry the keys' and metrics' units; ratios get their 5% level (residual
// ratios at 0.05, peak_ratio at 1.05: 5% above the static deflection). Keys of the other
// axes are held at their first value (the title says which).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/sweep/sweep.h"

namespace shapebench::bench {

// What plotting needs to know about a sweep besides results.csv; kept in manifest.json.
struct SweepLayout {
  std::string name;
  std::vector<std::string> keys;        // results.csv's key columns
  std::vector<std::uint64_t> key_axis;  // the axis of each key
  std::vector<bool> key_log;            // log-spaced range
  std::vector<std::uint64_t> axis_sizes;
  std::vector<std::string> metrics;     // results.csv's metric columns
  std::vector<SweepPlot> plots;

  static SweepLayout Of(const Sweep& sweep);
  nlohmann::ordered_json ToJson() const;
  static SweepLayout FromJson(const nlohmann::json& json);  // throws std::runtime_error
};

// The shortest dotted suffix of `key` that no other of `keys` ends with (whole
// components): "frequency_hz" for machine.modes[0].frequency_hz unless another key ends
// in frequency_hz, then "modes[0].frequency_hz".
std::string ShortKey(const std::string& key, const std::vector<std::string>& keys);

// The file name of a plot, each key by its ShortKey among the sweep's `keys`:
// "residual_ratio-vs-frequency_hz-by-method.png", "peak_ratio-over-frequency_hz-and-
// feed_mm_min.png"; characters other than [A-Za-z0-9._-] replaced by '_'.
std::string SweepPlotFileName(const SweepPlot& plot, const std::vector<std::string>& keys);

// Whether the metric's axis (a heat map's colour scale) is drawn in log: the plot's
// `log:` when given; else for a ratio metric whose positive `values` span more than two
// decades (a residual ratio from 1e-4 to 2 would leave everything under 5% flat).
// Non-positive values are then left out (gaps).
bool LogMetricAxis(const SweepPlot& plot, const std::vector<double>& values);

// Draws every plot of `layout` from `results_csv` into `out_dir`; returns the PNG paths.
// Throws std::runtime_error when gnuplot is missing or fails.
std::vector<std::string> WriteSweepPlots(const std::string& out_dir, const SweepLayout& layout,
                                         const std::string& results_csv);

// The 5% level of a metric, or NaN when it has none: 0.05 for residual ratios, 1.05 for
// peak_ratio.
double FivePercentLevel(const std::string& metric);

}  // namespace shapebench::bench
