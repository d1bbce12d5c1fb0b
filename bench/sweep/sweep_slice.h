// One plot's slice of results.csv (ReadSlice) and the values of its keys; shared by the
// sweep's plots and its robust bands (bench/sweep/robust_band.h).
#pragma once

#include <string>
#include <vector>

#include "bench/sweep/sweep_layout.h"

namespace shapebench::bench {

// Whether `text` is a whole finite number (then *value).
bool ParseNumber(const std::string& text, double* value);

// The values of one plotted key along its axis: numbers when every one is a number.
struct AxisValues {
  std::vector<std::string> texts;
  std::vector<double> numbers;
  bool numeric = true;
  bool log = false;

  // The coordinate of the i-th value: the number, or the index for text values.
  double Coordinate(std::size_t i) const { return numeric ? numbers[i] : static_cast<double>(i); }
  // Evenly spaced numbers (a heat map draws them at their values; otherwise by index).
  bool Uniform() const;
  void Finish();
};

// One plot's slice of results.csv: the rows whose other axes are at their first value.
struct Slice {
  AxisValues x;
  AxisValues y;  // series (line plot) or the heat map's y key; one empty value if none
  std::vector<double> z;  // [iy * nx + ix], NaN where undefined or failed
  std::string fixed;      // "k=v, ..." of the keys held at their first value
};

// The slice of `metric` over `x_key` and `y_key` ("" for none), metres scaled to um when
// `scaled`. Throws std::runtime_error when a key or the metric is not a column.
Slice ReadSlice(const SweepLayout& layout, const std::string& results_csv, const std::string& metric,
                const std::string& x_key, const std::string& y_key, bool scaled = true);

// Metrics in metres are plotted in um (micrometres).
double MetricScale(const std::string& metric);

}  // namespace shapebench::bench
