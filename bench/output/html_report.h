// `--report FILE.html` of run, check, sweep and compare: one self-contained page (inline
// <style>, inline SVG plots, nothing fetched; run's interactive trace inlines its charting
// library, bench/output/interactive_trace.h, the only script), every text from the input
// HTML-escaped. The commands fill an HtmlReport with plain data (the rooms above this one,
// sweep and compare, hand theirs in) and write it atomically.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bench/config/override.h"
#include "bench/output/report.h"
#include "bench/scenario/checks.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/metrics.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

// A table of text cells (escaped when rendered).
struct HtmlTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// One PASS/FAIL line.
struct HtmlCheck {
  bool passed = false;
  std::string text;
};

// One section of the page; each part present is shown in this order.
struct HtmlSection {
  std::string heading;
  std::string note;           // a paragraph
  HtmlTable table;            // shown when it has a header
  std::vector<HtmlCheck> checks;
  std::string svg;            // an <svg> element from gnuplot, or the interactive trace's
                              // elements (ours, inlined as is)
  // A collapsible table (<details>, closed) under `details_summary`, after the checks: a
  // sweep's failing points, which may be hundreds.
  std::string details_summary;
  HtmlTable details;
  std::string preformatted;   // verbatim text (the effective scenario's YAML)
};

struct HtmlReport {
  std::string title;
  std::string subtitle;
  std::vector<HtmlSection> sections;
};

// &, <, >, " and ' as entities; control characters other than tab and newline, and
// bytes that are not UTF-8, as U+FFFD.
std::string HtmlEscape(std::string_view text);

// The page.
std::string RenderHtml(const HtmlReport& report);

// Writes the page atomically (WriteFileAtomically).
void WriteHtmlReport(const std::string& path, const HtmlReport& report);

// Metric, value, unit, description for every metric in MetricTable() order.
HtmlTable MetricsHtmlTable(const Metrics& metrics);

// The PASS/FAIL lines of check results (FormatCheckLine without the file).
std::vector<HtmlCheck> HtmlChecks(const std::vector<CheckResult>& results);

// The inline SVG of the deflection plot (WriteDeflectionPlot's, svg terminal), and of the
// overlay of several runs (WriteDeflectionOverlayPlot's). Throw std::runtime_error when
// gnuplot is missing or fails.
std::string DeflectionSvg(const RunResult& result, const Scenario& scenario);
std::string DeflectionOverlaySvg(const std::vector<OverlaidRun>& runs, const std::string& title);

// One curve of an XY plot: its legend entry and its points (NaN ys are left out).
struct XySeries {
  std::string title;
  std::vector<std::pair<double, double>> points;
};

// Points joined by lines per series against a numeric key (a sweep's metric against its
// first key), as inline SVG.
std::string XySvg(const std::string& x_label, const std::string& y_label,
                  const std::vector<XySeries>& series);

// The scenario's YAML tree as a run reads it (BuildScenarioTree), as YAML text.
std::string EffectiveScenarioYaml(const std::string& path, const std::vector<Override>& overrides);

// `run --report`: the metrics table, the deflection plot, the checks evaluated (when the
// scenario has any) and the effective scenario's YAML.
HtmlReport RunHtmlReport(const Scenario& scenario, const RunResult& result,
                         const std::vector<CheckResult>& checks, const std::string& scenario_yaml);

// `check --report`: a summary, then per file its PASS/FAIL lines or its error.
HtmlReport CheckHtmlReport(const std::vector<ScenarioCheckReport>& reports);

// A sweep's results as plain data (results.csv's columns and rows).
struct SweepHtmlData {
  std::string name;
  std::string file;
  std::vector<std::string> keys;     // the swept keys (the first is the plots' x)
  std::vector<std::string> columns;  // results.csv's header
  std::vector<std::vector<std::string>> rows;
  // The sweep's own plots (its `plots:`, log scales, thresholds and robust bands), each
  // (heading, inline <svg>); empty: a plot of every ratio against the first key.
  std::vector<std::pair<std::string, std::string>> plots;
  HtmlTable bands;  // bands.csv's rows (bench/sweep/robust_band.h); no header: none
  std::string base_yaml;  // the base scenario with the --set overrides applied
};

// `sweep --report`: the ratio metrics against the first key, the results table (metric
// columns in engineering units) and the base scenario's YAML.
HtmlReport SweepHtmlReport(const SweepHtmlData& data);

}  // namespace shapebench::bench
