#include "bench/compare/compare_report.h"

#include "common/format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <typeinfo>

#include "bench/output/report.h"
#include "common/atomic_file.h"
#include "common/interrupt.h"
#include "common/shown_text.h"
#include "bench/output/json_number.h"

namespace shapebench::bench {
namespace {

using Json = nlohmann::ordered_json;
using TableRow = std::vector<std::string>;

// Columns left-aligned, two spaces apart; the last one not padded.
void PrintRows(std::ostream& out, const std::vector<TableRow>& rows) {
  std::vector<std::size_t> widths;
  for (const TableRow& row : rows) {
    widths.resize(std::max(widths.size(), row.size()));
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  for (const TableRow& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(widths[c] - row[c].size() + 2, ' ');
    }
    out << TerminalSafe(line) << "\n";
  }
}

// In engineering units: "87.0475 um", "726 ms", "0.0123".
std::string Value(const MetricInfo& info, double value) {
  if (info.is_bool() && !std::isnan(value)) return value != 0.0 ? "true" : "false";
  return EngineeringText(value, info.shown_unit());
}

Json JsonValue(const MetricInfo& info, double value) {
  if (!std::isfinite(value)) return nullptr;
  if (info.is_bool()) return value != 0.0;
  return value;
}

Json SideJson(const CompareSide& side) {
  Json overrides = Json::array();
  for (const Override& override : side.overrides)
    overrides.push_back(override.key_path + "=" + override.value_yaml);
  return Json{{"file", side.file}, {"name", side.name}, {"overrides", overrides}, {"label", side.Label()}};
}

Json ChangeJson(const MetricChange& change) {
  return Json{{"baseline", JsonValue(*change.info, change.baseline)},
              {"candidate", JsonValue(*change.info, change.candidate)},
              {"change", JsonNumber(change.change)},
              {"relative_change", JsonNumber(change.relative_change)},
              {"favours", std::string(VerdictName(change.better))}};
}

Json PointJson(const PointChange& point) {
  Json json{{"point", point.point}, {"label", point.label}};
  json.update(ChangeJson(point.change));
  return json;
}

void PrintSides(std::ostream& out, const CompareSide& baseline, const CompareSide& candidate,
                const std::string& points = "") {
  std::vector<TableRow> rows = {{"baseline", baseline.Label()}, {"candidate", candidate.Label()}};
  if (!points.empty()) rows.push_back({"points", points});
  PrintRows(out, rows);
  out << "\n";
}

const MetricChange& ChangeOf(const std::vector<MetricChange>& changes, const Gate& gate) {
  return changes[static_cast<std::size_t>(gate.info - MetricTable().data())];
}

std::string GateLine(bool passed, const Gate& gate) {
  return std::string(passed ? "PASS" : "FAIL") + " gate " + gate.text + ": ";
}

// Writes `files` into DIR (StagedDirectory: complete or absent), naming DIR in errors.
void WriteStaged(const std::string& out_dir, const std::function<void(const std::filesystem::path&)>& files) {
  const DeferInterrupts defer;
  StagedDirectory staged(out_dir);
  try {
    files(std::filesystem::path(staged.path()));
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  ThrowIfInterrupted("the output in " + out_dir + " is complete");
}

template <typename Comparison>
void WriteTextAndJson(const std::filesystem::path& dir, const Comparison& comparison) {
  WriteFileAtomically((dir / "compare.txt").string(),
                      [&](std::ostream& out) { PrintComparison(out, comparison); });
  WriteFileAtomically((dir / "compare.json").string(),
                      [&](std::ostream& out) { out << ComparisonJson(comparison).dump(2) << "\n"; });
}

}  // namespace

void PrintComparison(std::ostream& out, const ScenarioComparison& comparison) {
  PrintSides(out, comparison.baseline, comparison.candidate);
  std::vector<TableRow> rows = {
      {"metric", "unit", "better", "baseline", "candidate", "change", "relative", "favours"}};
  for (const MetricChange& change : comparison.changes) {
    const MetricInfo& info = *change.info;
    rows.push_back({std::string(info.name), std::string(info.unit), std::string(BetterName(info.better)),
                    Value(info, change.baseline), Value(info, change.candidate), ChangeText(change),
                    RelativeText(change), FavoursText(change)});
  }
  PrintRows(out, rows);
  if (!comparison.gates.empty()) out << "\n";
  for (const Gate& gate : comparison.gates) {
    const MetricChange& change = ChangeOf(comparison.changes, gate);
    out << TerminalSafe(GateLine(GatePasses(gate, change), gate) + GateDetail(gate, change)) << "\n";
  }
}

Json ComparisonJson(const ScenarioComparison& comparison) {
  Json metrics = Json::array();
  for (const MetricChange& change : comparison.changes) {
    Json row{{"name", std::string(change.info->name)},
             {"unit", std::string(change.info->unit)},
             {"better", std::string(BetterName(change.info->better))}};
    row.update(ChangeJson(change));
    metrics.push_back(row);
  }
  Json gates = Json::array();
  for (const Gate& gate : comparison.gates) {
    const MetricChange& change = ChangeOf(comparison.changes, gate);
    gates.push_back(Json{{"gate", gate.text},
                         {"metric", std::string(gate.info->name)},
                         {"max_worsening", gate.max_worsening},
                         {"worsening", JsonNumber(change.worsening)},
                         {"passed", GatePasses(gate, change)},
                         {"detail", GateDetail(gate, change)}});
  }
  return Json{{"kind", "scenarios"},
              {"baseline", SideJson(comparison.baseline)},
              {"candidate", SideJson(comparison.candidate)},
              {"metrics", metrics},
              {"gates", gates},
              {"passed", comparison.passed()}};
}

void PrintComparison(std::ostream& out, const SweepComparison& comparison) {
  std::string points = std::to_string(comparison.points);
  if (comparison.failed_points > 0) {
    points += " (" + std::to_string(comparison.failed_points) +
              " failed to run on a side, compared "
              "on " +
              std::to_string(comparison.points - comparison.failed_points) + ")";
  }
  PrintSides(out, comparison.baseline, comparison.candidate, points);
  std::vector<TableRow> rows = {{"metric", "unit", "better", "cand. better", "base. better", "same", "n/a",
                            "worst: baseline", "candidate", "change", "relative", "at"}};
  for (const SweepMetricSummary& summary : comparison.metrics) {
    const MetricInfo& info = *summary.info;
    TableRow row = {std::string(info.name),
               std::string(info.unit),
               std::string(BetterName(info.better)),
               std::to_string(summary.candidate_better),
               std::to_string(summary.baseline_better),
               std::to_string(summary.same),
               std::to_string(summary.not_comparable)};
    if (summary.has_worst) {
      const MetricChange& worst = summary.worst.change;
      row.insert(row.end(),
                 {Value(info, worst.baseline), Value(info, worst.candidate), ChangeText(worst),
                  RelativeText(worst), summary.worst.label});
    } else {
      row.insert(row.end(), {"n/a", "n/a", "n/a", "n/a", ""});
    }
    rows.push_back(row);
  }
  PrintRows(out, rows);
  if (!comparison.gates.empty()) out << "\n";
  const std::uint64_t compared = comparison.points - comparison.failed_points;
  for (const SweepGateSummary& gate : comparison.gates) {
    std::string line = GateLine(gate.passed(), gate.gate) + std::to_string(compared - gate.failed) + " of " +
                       std::to_string(compared) + " points pass";
    if (gate.not_comparable > 0) line += " (" + std::to_string(gate.not_comparable) + " n/a)";
    if (gate.has_worst)
      line += "; worst: " + GateDetail(gate.gate, gate.worst.change) + " @ " + gate.worst.label;
    out << TerminalSafe(line) << "\n";
  }
}

Json ComparisonJson(const SweepComparison& comparison) {
  Json metrics = Json::array();
  for (const SweepMetricSummary& summary : comparison.metrics) {
    metrics.push_back(Json{{"name", std::string(summary.info->name)},
                           {"unit", std::string(summary.info->unit)},
                           {"better", std::string(BetterName(summary.info->better))},
                           {"candidate_better", summary.candidate_better},
                           {"baseline_better", summary.baseline_better},
                           {"same", summary.same},
                           {"not_comparable", summary.not_comparable},
                           {"worst", summary.has_worst ? PointJson(summary.worst) : Json(nullptr)}});
  }
  Json gates = Json::array();
  for (const SweepGateSummary& gate : comparison.gates) {
    gates.push_back(Json{{"gate", gate.gate.text},
                         {"metric", std::string(gate.gate.info->name)},
                         {"max_worsening", gate.gate.max_worsening},
                         {"failed_points", gate.failed},
                         {"not_comparable", gate.not_comparable},
                         {"passed", gate.passed()},
                         {"worst", gate.has_worst ? PointJson(gate.worst) : Json(nullptr)}});
  }
  return Json{{"kind", "sweeps"},
              {"baseline", SideJson(comparison.baseline)},
              {"candidate", SideJson(comparison.candidate)},
              {"points", comparison.points},
              {"failed_points", comparison.failed_points},
              {"metrics", metrics},
              {"gates", gates},
              {"passed", comparison.passed()}};
}

void WriteComparisonOutputs(const std::string& out_dir, const ScenarioComparison& comparison) {
  WriteStaged(out_dir, [&](const std::filesystem::path& dir) {
    WriteTextAndJson(dir, comparison);
    const std::vector<OverlaidRun> runs = {{&comparison.baseline_run, &comparison.baseline_scenario,
                                            "baseline", "baseline: " + comparison.baseline.Label()},
                                           {&comparison.candidate_run, &comparison.candidate_scenario,
                                            "candidate", "candidate: " + comparison.candidate.Label()}};
    WriteDeflectionOverlayPlot((dir / "deflection.png").string(), runs,
                               "deflection: baseline " + comparison.baseline.name + " (blue) vs candidate " +
                                   comparison.candidate.name + " (red)");
  });
}

SweepComparison CompareSweepsWritingTo(const std::string& out_dir, const ComparedSweeps& sweeps,
                                       const std::vector<Gate>& gates, int jobs, std::ostream& err) {
  SweepComparison comparison;
  WriteStaged(out_dir, [&](const std::filesystem::path& dir) {
    WriteFileAtomically((dir / "points.csv").string(), [&](std::ostream& out) {
      comparison = CompareSweeps(sweeps, gates, jobs, &out, err);
    });
    WriteTextAndJson(dir, comparison);
  });
  return comparison;
}

}  // namespace shapebench::bench
