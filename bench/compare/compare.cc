#include "bench/compare/compare.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "common/decimal.h"
#include "common/format.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string Joined(const std::vector<std::string>& names, const std::string& separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

// REL of --gate: a finite number >= 0, the whole text.
double ParseRelative(const std::string& text, const std::string& gate) {
  double value = 0.0;
  if (!ParseDecimal(text, &value) || value < 0.0) {
    throw std::runtime_error("--gate " + ClippedForMessage(gate) +
                             ": REL must be a number >= 0 (a fraction: 0.05 is 5%), got '" +
                             ClippedForMessage(text) + "'");
  }
  return value;
}

}  // namespace

std::string_view VerdictName(Verdict verdict) {
  switch (verdict) {
    case Verdict::kSame: return "same";
    case Verdict::kBaseline: return "baseline";
    case Verdict::kCandidate: return "candidate";
    case Verdict::kNotComparable: break;
  }
  return "n/a";
}

double RelativeFloor(std::string_view unit) {
  if (unit == "m") return 1e-9;
  if (unit == "s" || unit == "1" || unit == "Hz") return 1e-6;
  return 1.0;  // "count", "bool"
}

MetricChange CompareMetric(const MetricInfo& info, double baseline, double candidate) {
  MetricChange change;
  change.info = &info;
  change.baseline = baseline;
  change.candidate = candidate;
  if (std::isnan(baseline) || std::isnan(candidate)) return change;
  const double scale = std::max(std::fabs(baseline), RelativeFloor(info.unit));
  change.change = candidate - baseline;
  change.relative_change = change.change / scale;
  const double worse =
      info.better == Better::kLower ? std::fabs(candidate) - std::fabs(baseline) : baseline - candidate;
  change.worsening = worse / scale;
  change.better = worse > 0.0 ? Verdict::kBaseline : worse < 0.0 ? Verdict::kCandidate : Verdict::kSame;
  return change;
}

std::vector<MetricChange> CompareMetrics(const Metrics& baseline, const Metrics& candidate) {
  std::vector<MetricChange> changes;
  changes.reserve(MetricTable().size());
  for (const MetricInfo& info : MetricTable()) {
    changes.push_back(CompareMetric(info, baseline.*info.field, candidate.*info.field));
  }
  return changes;
}

std::vector<std::string> ClosestNames(const std::string& name, const std::vector<std::string>& names) {
  const std::size_t within = std::max<std::size_t>(2, name.size() / 3);
  std::vector<std::pair<std::size_t, std::string>> close;
  for (const std::string& candidate : names) {
    const std::size_t distance = EditDistance(name, candidate);
    // A part of a name ("residual") is close to every name that holds it.
    const bool part = name.size() >= 3 && candidate.find(name) != std::string::npos;
    if (distance <= within || part) close.emplace_back(part ? 0 : distance, candidate);
  }
  std::stable_sort(close.begin(), close.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> closest;
  for (const auto& entry : close) closest.push_back(entry.second);
  return closest;
}

Gate ParseGate(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw std::runtime_error("--gate: expected METRIC=REL (e.g. residual_ratio=0.05), got '" +
                             ClippedForMessage(text) + "'");
  }
  const std::string name = text.substr(0, equals);
  Gate gate;
  gate.text = text;
  gate.info = FindMetric(name);
  // compare covers MetricTable(), not the nonlinear plants' own metrics.
  const bool compared = gate.info != nullptr && gate.info >= MetricTable().data() &&
                        gate.info < MetricTable().data() + MetricTable().size();
  if (!compared) gate.info = nullptr;
  if (gate.info == nullptr) {
    const std::vector<std::string> names = MetricNames();
    const std::vector<std::string> closest = ClosestNames(name, names);
    std::string message =
        "--gate " + ClippedForMessage(text) + ": unknown metric '" + ClippedForMessage(name) + "'";
    if (!closest.empty()) message += "; did you mean " + Joined(closest, " or ") + "?";
    throw std::runtime_error(message + " allowed: " + Joined(names, ", "));
  }
  gate.max_worsening = ParseRelative(text.substr(equals + 1), text);
  return gate;
}

std::vector<Gate> ParseGates(const std::vector<std::string>& texts) {
  std::vector<Gate> gates;
  for (const std::string& text : texts) gates.push_back(ParseGate(text));
  return gates;
}

bool GatePasses(const Gate& gate, const MetricChange& change) {
  return !std::isnan(change.worsening) && change.worsening <= gate.max_worsening;
}

std::string FormatPercent(double fraction) {
  if (std::isnan(fraction)) return "n/a";
  if (fraction == 0.0) return "0%";
  char text[48];
  std::snprintf(text, sizeof text, "%+.4g%%", fraction * 100.0);
  return text;
}

double NoiseFloor(const MetricInfo& info, double baseline, double candidate) {
  double floor = 0.0;
  if (info.unit == "m") floor = 1e-12;
  if (info.unit == "s") floor = 1e-9;
  if (info.unit == "Hz" || info.unit == "1") floor = 1e-9;
  if (info.unit == "m/s^2") floor = 1e-12;
  if (info.unit == "count" || info.is_bool()) return 0.0;
  return std::max(floor, 1e-9 * std::max(std::fabs(baseline), std::fabs(candidate)));
}

std::string ChangeText(const MetricChange& change) {
  if (std::isnan(change.change)) return "n/a";
  if (std::fabs(change.change) <= NoiseFloor(*change.info, change.baseline, change.candidate)) return "same";
  const std::string text = EngineeringText(change.change, change.info->shown_unit());
  return change.change > 0.0 ? "+" + text : text;
}

std::string RelativeText(const MetricChange& change) {
  if (!std::isnan(change.change) &&
      std::fabs(change.change) <= NoiseFloor(*change.info, change.baseline, change.candidate)) {
    return "same";
  }
  return FormatPercent(change.relative_change);
}

std::string FavoursText(const MetricChange& change) {
  return ChangeText(change) == "same" ? "same" : std::string(VerdictName(change.better));
}

std::string GateDetail(const Gate& gate, const MetricChange& change) {
  const std::string limit = " (gate " + FormatNumber(gate.max_worsening * 100.0) + "%)";
  if (std::isnan(change.baseline) || std::isnan(change.candidate)) {
    const bool both = std::isnan(change.baseline) && std::isnan(change.candidate);
    return std::string(both                          ? "n/a in both runs"
                       : std::isnan(change.baseline) ? "baseline n/a"
                                                     : "candidate n/a") +
           ": not comparable" + limit;
  }
  if (change.worsening == 0.0) return "no worse" + limit;
  const std::string amount = FormatPercent(std::fabs(change.worsening)).substr(1);
  return (change.worsening > 0.0 ? "worse by " : "better by ") + amount + limit;
}

}  // namespace shapebench::bench
