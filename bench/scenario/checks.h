// Scenario::checks evaluated against a run's Metrics (the `check` command, JUnit).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bench/scenario/metrics.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

struct CheckResult {
  std::string metric;
  double value = NAN;  // NaN: not defined for this run
  std::string value_text;  // as printed: enough digits to differ from a violated bound
  std::string bound;   // "max 1.01", "min 0.5, max 2"
  bool passed = false;
  std::string message;  // why it failed; empty when passed
  std::string point;    // a sweep's point, "key=value, ..."; empty for a scenario
  double run_time_s = NAN;  // wall time of the run it was evaluated on (JUnit); NaN: not measured
  // A band check (Check::band): `value` is the worst over the band, found at
  // band_key = worst_at (NaN when no point ran), after `band_runs` runs.
  std::string band_key = {};  // (initialised: the brace-initialised results of tests stay warning-free)
  double band_from = NAN;
  double band_to = NAN;
  double worst_at = NAN;
  int band_runs = 0;
  bool banded() const { return !band_key.empty(); }
  // A sampled sweep's gate (bench/sweep/sampling.h, SampleGate): "yield" or
  // "quantile 0.95" (then `metric` is the metric), its estimate `value` from `samples`
  // samples (`passing` of them pass, for a yield), and the estimate's 95% interval
  // (Wilson score for a yield, order statistics for a quantile; +-inf: open).
  std::string statistic = {};
  std::uint64_t samples = 0;
  std::uint64_t passing = 0;
  double interval_low = NAN;
  double interval_high = NAN;
};

// The check's result for `value`, the metric's value (a band check's worst): bound,
// pass/fail and message. A band check's result carries the band and `worst_at`.
CheckResult EvaluateCheck(const Check& check, double value, double worst_at = NAN,
                          int band_runs = 0);

// How far a value is on the wrong side of the check's bounds (negative: inside; +inf for
// NaN): what makes one value worse than another.
double Violation(const Check& check, double value);

// "worst residual_ratio 0.061 at machine.modes[0].frequency_hz = 24.37 in [24, 26]"
// for a band check's result; "" for another.
std::string BandText(const CheckResult& result);

// Why `metric` is n/a when the static displacement is 0 (a model whose static deflections
// cancel in the output view): "the static displacement is 0 (...)" for the ratios to it and
// the settling time (its band is 5% of it); "" for any other metric.
std::string ZeroStaticReason(std::string_view metric);

// One result per check, in the scenario's order. A NaN value fails with
// "metric not defined for this run", or with "n/a because " ZeroStaticReason when that
// applies (static_displacement_m is 0); bounds are inclusive. A band check is evaluated on
// `metrics` too (its nominal point): EvaluateBandCheck (bench/sweep/band_check.h) gives
// its worst over the band.
std::vector<CheckResult> EvaluateChecks(const std::vector<Check>& checks, const Metrics& metrics);

// Everything `check` learnt about one scenario file, for the console and JUnit.
struct ScenarioCheckReport {
  std::string file;  // as given on the command line
  std::string name;  // the scenario's name
  std::vector<CheckResult> results;
  std::string error;  // non-empty when the run itself failed (then `results` is empty)
  double run_time_s = 0.0;
  // A sweep: the points whose run failed, (point, message); `results` has the others'.
  std::vector<std::pair<std::string, std::string>> point_errors;
};

// "PASS scenarios/fig2.yaml peak_ratio = 1.9998 (max 2.01)"; a failure adds ": message";
// a sweep's point follows the metric: "FAIL sweep.yaml residual_ratio @ key=21.5 = ...";
// a band check: "PASS f.yaml worst residual_ratio 0.041 at KEY = 24.37 in [24, 26] (max 0.05)".
std::string FormatCheckLine(const std::string& file, const CheckResult& result);

// What a result bounds: its metric, or a sampled sweep's statistic of it ("quantile 0.95
// of residual_ratio"; a yield is "yield").
std::string CheckedQuantity(const CheckResult& result);

// Human formatting of a metric value or bound: `digits` significant digits, "n/a" for NaN.
std::string FormatValue(double value, int digits = 5);

}  // namespace shapebench::bench
