#include "bench/sim/checks.h"

#include <cmath>
#include <cstdio>
#include <optional>

namespace shapebench::bench {

std::string FormatValue(double value, int digits) {
  if (std::isnan(value)) return "n/a";
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::vector<CheckResult> EvaluateChecks(const std::vector<Check>& checks,
                                        const Metrics& metrics) {
  std::vector<CheckResult> results;
  for (const Check& check : checks) {
    CheckResult result;
    result.metric = check.metric;
    if (const MetricInfo* info = FindMetric(check.metric)) result.value = metrics.*info->field;
    if (check.min) result.bound = "min " + FormatValue(*check.min);
    if (check.max) result.bound += (result.bound.empty() ? "" : ", ") + ("max " + FormatValue(*check.max));

    result.value_text = FormatValue(result.value);
    std::optional<double> violated;
    if (std::isnan(result.value)) {
      result.message = "metric not defined for this run";
    } else if (check.min && result.value < *check.min) {
      result.message = "below min " + FormatValue(*check.min);
      violated = check.min;
    } else if (check.max && result.value > *check.max) {
      result.message = "above max " + FormatValue(*check.max);
      violated = check.max;
    } else {
      result.passed = true;
    }
    // 1.01000004 must not print as "1.01 (max 1.01)" next to FAIL.
    if (violated && result.value_text == FormatValue(*violated)) {
      result.value_text = FormatValue(result.value, 17);
    }
    results.push_back(result);
  }
  return results;
}

std::string FormatCheckLine(const std::string& file, const CheckResult& result) {
  std::string line = std::string(result.passed ? "PASS " : "FAIL ") + file + " " + result.metric +
                     (result.point.empty() ? "" : " @ " + result.point) + " = " +
                     result.value_text + " (" + result.bound + ")";
  if (!result.passed) line += ": " + result.message;
  return line;
}

}  // namespace shapebench::bench
