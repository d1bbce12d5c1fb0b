// Scenario::checks evaluated against a run's Metrics (the `check` command, JUnit).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bench/sim/metrics.h"
#include "bench/sim/scenario.h"

namespace shapebench::bench {

struct CheckResult {
  std::string metric;
  double value = NAN;  // NaN: not defined for this run
  std::string value_text;  // as printed: enough digits to differ from a violated bound
  std::string bound;   // "max 1.01", "min 0.5, max 2"
  bool passed = false;
  std::string message;  // why it failed; empty when passed
  std::string point;    // a sweep's point, "key=value, ..."; empty for a scenario
};

// One result per check, in the scenario's order. A NaN value fails with
// "metric not defined for this run"; bounds are inclusive.
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
// a sweep's point follows the metric: "FAIL sweep.yaml residual_ratio @ key=21.5 = ...".
std::string FormatCheckLine(const std::string& file, const CheckResult& result);

// Human formatting of a metric value or bound: `digits` significant digits, "n/a" for NaN.
std::string FormatValue(double value, int digits = 5);

}  // namespace shapebench::bench
