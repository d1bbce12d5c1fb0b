// CompareHtmlReport (bench/compare/compare_html.h).
#include "bench/compare/compare_html.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/format.h"

namespace shapebench::bench {
namespace {

HtmlTable ChangesTable(const ScenarioComparison& comparison) {
  HtmlTable table;
  table.header = {"metric", "baseline", "candidate", "change", "relative", "favours"};
  for (const MetricChange& change : comparison.changes) {
    const MetricInfo& info = *change.info;
    table.rows.push_back({std::string(info.name), EngineeringText(change.baseline, info.unit),
                          EngineeringText(change.candidate, info.unit), ChangeText(change),
                          RelativeText(change), FavoursText(change)});
  }
  return table;
}

std::vector<HtmlCheck> GateChecks(const ScenarioComparison& comparison) {
  std::vector<HtmlCheck> checks;
  for (const Gate& gate : comparison.gates) {
    const auto change = std::find_if(comparison.changes.begin(), comparison.changes.end(),
                                     [&](const MetricChange& c) { return c.info == gate.info; });
    if (change == comparison.changes.end()) continue;  // ParseGate names a MetricTable() metric
    checks.push_back({GatePasses(gate, *change), "gate " + gate.text + ": " + GateDetail(gate, *change)});
  }
  return checks;
}

}  // namespace

HtmlReport CompareHtmlReport(const ScenarioComparison& comparison) {
  HtmlReport report;
  report.title = "shapebench compare: " + comparison.baseline.name + " vs " + comparison.candidate.name;
  report.subtitle = std::string(comparison.passed() ? "PASS" : "FAIL") + ": baseline " +
                    comparison.baseline.Label() + "; candidate " + comparison.candidate.Label();
  HtmlSection metrics;
  metrics.heading = "Metrics";
  metrics.table = ChangesTable(comparison);
  metrics.checks = GateChecks(comparison);
  report.sections.push_back(metrics);
  HtmlSection plot;
  plot.heading = "Deflection";
  plot.note = "Baseline blue, candidate red; where each run's commanded motion ends dotted.";
  const std::vector<OverlaidRun> runs = {
      {&comparison.baseline_run, &comparison.baseline_scenario, "baseline", "baseline: " + comparison.baseline.Label()},
      {&comparison.candidate_run, &comparison.candidate_scenario, "candidate",
       "candidate: " + comparison.candidate.Label()}};
  plot.svg = DeflectionOverlaySvg(runs, "deflection: baseline (blue) vs candidate (red)");
  report.sections.push_back(plot);
  for (const CompareSide* side : {&comparison.baseline, &comparison.candidate}) {
    HtmlSection yaml;
    yaml.heading = (side == &comparison.baseline ? "Baseline scenario: " : "Candidate scenario: ") + side->Label();
    yaml.preformatted = EffectiveScenarioYaml(side->file, side->overrides);
    report.sections.push_back(yaml);
  }
  return report;
}

}  // namespace shapebench::bench
