// The metrics of one run, SI units, and the one table that names them. NaN means "not
// defined for this run" (no cruise phase; never settled within the simulated time) and is
// written as null. JSON, the metrics table, results.csv's columns, checks and
// docs/metrics.md all read MetricTable(): a metric is defined in exactly one place.
#pragma once

#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shapebench::bench {

struct Metrics {
  double static_displacement_m = NAN;
  double peak_deflection_m = NAN;
  double peak_ratio = NAN;
  double residual_amplitude_m = NAN;
  double residual_ratio = NAN;
  double residual_peak_m = NAN;
  double residual_peak_ratio = NAN;
  double cruise_residual_ratio = NAN;
  double motion_time_s = NAN;
  double settling_time_s = NAN;
  double max_contour_error_m = NAN;
  double radial_error_m = NAN;
  double peak_deflection_x_m = NAN;
  double peak_deflection_y_m = NAN;
  double peak_deflection_z_m = NAN;
  double static_displacement_x_m = NAN;
  double static_displacement_y_m = NAN;
  double static_displacement_z_m = NAN;
  double short_block_clamps = NAN;
  double stroke_overshoot_m = NAN;
  double stroke_alarm = NAN;  // 1 or 0; written as a bool
  double peak_command_acceleration_m_s2 = NAN;
  double pattern_frequency_hz = NAN;
  double pattern_damping_ratio = NAN;
  // Of plants with nonlinear elements only (NonlinearMetricTable()).
  double dead_band_m = NAN;
  double quadrant_glitch_m = NAN;

  // (name, value) in MetricTable() order.
  std::vector<std::pair<std::string, double>> Named() const;
};

// Which way a metric gets better (compare, gates, the glossary).
enum class Better { kLower, kHigher };

// One row of the metric table.
struct MetricInfo {
  std::string_view name;
  // "m", "s", "Hz", "m/s^2", "1" (a ratio), "count" or "bool" (a 0/1 value written as
  // false/true).
  std::string_view unit;
  Better better;
  std::string_view description;
  double Metrics::*field;

  bool is_bool() const { return unit == "bool"; }
  // The unit a table prints after the number: a physical unit, nothing for a ratio, a count
  // or a bool.
  std::string_view shown_unit() const { return unit == "1" || unit == "count" || is_bool() ? "" : unit; }
};

// Every metric, in the order JSON, tables and results.csv list them (their number is the
// table's size: a row is all a new metric adds here).
const std::vector<MetricInfo>& MetricTable();

// The metrics of a plant with nonlinear elements (docs/nonlinear.md): NaN for every other
// run, and then left out of JSON and the metrics table (a linear run's output stays as it
// was); checks and a sweep's `metrics:` may name them (a linear run's value is n/a).
const std::vector<MetricInfo>& NonlinearMetricTable();

// The row of `name` in either table; nullptr when there is none.
const MetricInfo* FindMetric(std::string_view name);

// The metric names in table order.
std::vector<std::string> MetricNames();
// Those and the nonlinear plants' (what checks and a sweep's `metrics:` accept).
std::vector<std::string> AllMetricNames();

std::string_view BetterName(Better better);  // "lower" | "higher"

}  // namespace shapebench::bench
