// What plotting needs to know about a sweep besides results.csv (SweepLayout, kept in
// manifest.json so `merge` draws the same), the robust bands it asks for, and the names
// of its plots' files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/sweep/sweep.h"

namespace shapebench::bench {

// A robust band to find (bench/sweep/robust_band.h): where `metric` stays at or below
// `threshold` along `x`, per value of `series` ("" for none).
struct BandSpec {
  std::string metric;
  std::string x;
  std::string series;
  double threshold = 0.0;
};

// What plotting needs to know about a sweep besides results.csv; kept in manifest.json.
struct SweepLayout {
  std::string name;
  std::vector<std::string> keys;        // results.csv's key columns
  std::vector<std::uint64_t> key_axis;  // the axis of each key
  std::vector<bool> key_log;            // log-spaced range
  std::vector<std::uint64_t> axis_sizes;
  std::vector<std::string> metrics;     // results.csv's metric columns
  std::vector<SweepPlot> plots;
  // The robust bands: each line plot of a ratio metric, and each ratio metric checked
  // with a max along the first line plot's keys (absent from older manifests: none).
  std::vector<BandSpec> bands;

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

// The 5% level of a metric, or NaN when it has none: 0.05 for residual ratios, 1.05 for
// peak_ratio.
double FivePercentLevel(const std::string& metric);

}  // namespace shapebench::bench
