#include "bench/scenario/checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string_view>

#include "common/format.h"

namespace shapebench::bench {

std::string FormatValue(double value, int digits) {
  if (std::isnan(value)) return "n/a";
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

double Violation(const Check& check, double value) {
  if (std::isnan(value)) return std::numeric_limits<double>::infinity();
  double violation = -std::numeric_limits<double>::infinity();
  if (check.max) violation = std::max(violation, value - *check.max);
  if (check.min) violation = std::max(violation, *check.min - value);
  return violation;
}

CheckResult EvaluateCheck(const Check& check, double value, double worst_at, int band_runs) {
  CheckResult result;
  result.metric = check.metric;
  // Lengths and times as people read them ("8 um", "12.5 ms"); check --json keeps the SI value.
  const MetricInfo* info = FindMetric(check.metric);
  const std::string_view unit = info != nullptr && (info->unit == "m" || info->unit == "s") ? info->unit : "";
  const auto text = [unit](double x, int digits = 5) {
    return unit.empty() ? FormatValue(x, digits) : EngineeringText(x, unit, digits);
  };
  result.value = value;
  if (check.band) {
    result.band_key = check.band->key;
    result.band_from = check.band->from;
    result.band_to = check.band->to;
    result.worst_at = worst_at;
    result.band_runs = band_runs;
  }
  if (check.min) result.bound = "min " + text(*check.min);
  if (check.max) result.bound += (result.bound.empty() ? "" : ", ") + ("max " + text(*check.max));

  result.value_text = text(result.value);
  std::optional<double> violated;
  if (std::isnan(result.value)) {
    result.message = check.band && !std::isnan(worst_at)
                         ? "metric not defined at " + check.band->key + " = " + FormatValue(worst_at, 7)
                         : "metric not defined for this run";
  } else if (check.min && result.value < *check.min) {
    result.message = "below min " + text(*check.min);
    violated = check.min;
  } else if (check.max && result.value > *check.max) {
    result.message = "above max " + text(*check.max);
    violated = check.max;
  } else {
    result.passed = true;
  }
  // 1.01000004 must not print as "1.01 (max 1.01)" next to FAIL.
  if (violated && result.value_text == text(*violated)) {
    result.value_text = text(result.value, 17);
  }
  return result;
}

std::string ZeroStaticReason(std::string_view metric) {
  struct Relative {
    std::string_view metric;
    std::string_view instead;  // the absolute metric to bound instead
  };
  static constexpr Relative kRelative[] = {{"peak_ratio", "peak_deflection_m"},
                                           {"residual_ratio", "residual_amplitude_m"},
                                           {"residual_peak_ratio", "residual_peak_m"},
                                           {"cruise_residual_ratio", ""},
                                           {"settling_time_s", ""}};
  for (const Relative& r : kRelative) {
    if (r.metric != metric) continue;
    std::string reason =
        "the static displacement is 0 (the model's static deflections cancel in the output view), so " +
        std::string(metric == "settling_time_s" ? "the settling band (5% of it) is 0"
                                                : "no ratio to it is defined");
    if (!r.instead.empty()) reason += "; bound " + std::string(r.instead) + " instead";
    return reason;
  }
  return "";
}

std::vector<CheckResult> EvaluateChecks(const std::vector<Check>& checks,
                                        const Metrics& metrics) {
  std::vector<CheckResult> results;
  for (const Check& check : checks) {
    double value = NAN;
    if (const MetricInfo* info = FindMetric(check.metric)) value = metrics.*info->field;
    results.push_back(EvaluateCheck(check, value));
    const std::string reason = metrics.static_displacement_m == 0.0 ? ZeroStaticReason(check.metric) : "";
    if (std::isnan(value) && !reason.empty()) results.back().message = check.metric + " is n/a because " + reason;
  }
  return results;
}

std::string BandText(const CheckResult& result) {
  if (!result.banded()) return "";
  // The location to 7 significant digits: finer than the search's 1e-4 of the band.
  return "worst " + result.metric + " " + result.value_text + " at " + result.band_key + " = " +
         FormatValue(result.worst_at, 7) + " in [" + FormatValue(result.band_from, 15) + ", " +
         FormatValue(result.band_to, 15) + "]";
}

std::string CheckedQuantity(const CheckResult& result) {
  if (result.statistic.empty() || result.statistic == result.metric) return result.metric;
  return result.statistic + " of " + result.metric;
}

std::string FormatCheckLine(const std::string& file, const CheckResult& result) {
  std::string line =
      std::string(result.passed ? "PASS " : "FAIL ") + file + " " +
      (result.banded() ? BandText(result)
                       : CheckedQuantity(result) +
                             (result.point.empty() ? "" : " @ " + result.point) +
                             " = " + result.value_text) +
      " (" + result.bound + ")";
  if (!result.passed) line += ": " + result.message;
  return line;
}

}  // namespace shapebench::bench
