// The pages of run, check and sweep --report (bench/output/html_report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <yaml-cpp/yaml.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/output/gnuplot.h"
#include "bench/output/html_report.h"
#include "bench/output/interactive_trace.h"

namespace shapebench::bench {
namespace {

// A table of a few thousand rows is what a browser shows without effort.
constexpr std::size_t kMaxTableRows = 5000;

HtmlSection ScenarioYamlSection(const std::string& heading, const std::string& yaml) {
  HtmlSection section;
  section.heading = heading;
  section.note = "The YAML tree the run read: the file, its machine file spliced in, the --set overrides applied.";
  section.preformatted = yaml;
  return section;
}

// The column's number, NaN when the cell is not one.
double Number(const std::string& cell) {
  if (cell.empty()) return NAN;
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  return end != nullptr && *end == '\0' ? value : NAN;
}

int ColumnOf(const std::vector<std::string>& columns, const std::string& name) {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

// results.csv's cells, a metric's in engineering units with the unit in the header.
HtmlTable SweepTable(const SweepHtmlData& data) {
  HtmlTable table;
  std::vector<std::string> units(data.columns.size());
  for (std::size_t c = 0; c < data.columns.size(); ++c) {
    const MetricInfo* info = FindMetric(data.columns[c]);
    std::string header = data.columns[c];
    if (info != nullptr && (info->unit == "m" || info->unit == "s")) {
      units[c] = std::string(info->unit);
      header += info->unit == "m" ? " [um]" : " [ms]";
    }
    table.header.push_back(header);
  }
  for (const auto& row : data.rows) {
    if (table.rows.size() == kMaxTableRows) break;
    std::vector<std::string> cells;
    for (std::size_t c = 0; c < row.size(); ++c) {
      const double value = Number(row[c]);
      const bool scaled = c < units.size() && !units[c].empty() && std::isfinite(value);
      cells.push_back(scaled ? FormatValue(value * (units[c] == "m" ? 1e6 : 1e3)) : row[c]);
    }
    table.rows.push_back(cells);
  }
  return table;
}

// The first key whose every value is a number: the plots' x ("" when none is).
std::string NumericKey(const SweepHtmlData& data) {
  for (const std::string& key : data.keys) {
    const int c = ColumnOf(data.columns, key);
    if (c < 0) continue;
    const bool numeric = std::all_of(data.rows.begin(), data.rows.end(), [&](const auto& row) {
      return static_cast<std::size_t>(c) < row.size() && std::isfinite(Number(row[c]));
    });
    if (numeric && !data.rows.empty()) return key;
  }
  return "";
}

// The ratio metrics (unit "1") of results.csv against `x_key`, one curve per metric and
// value of the other keys (at most kMaxSeries curves: a plot stays readable).
std::vector<XySeries> SweepSeries(const SweepHtmlData& data, const std::string& x_key) {
  constexpr std::size_t kMaxSeries = 12;
  std::vector<XySeries> series;
  const int x = ColumnOf(data.columns, x_key);
  if (x < 0) return series;
  for (std::size_t c = 0; c < data.columns.size(); ++c) {
    const MetricInfo* info = FindMetric(data.columns[c]);
    if (info == nullptr || info->unit != "1") continue;
    for (const auto& row : data.rows) {
      if (row.size() <= std::max<std::size_t>(c, x) || !std::isfinite(Number(row[c]))) continue;
      std::string group;
      for (const std::string& key : data.keys) {
        const int k = ColumnOf(data.columns, key);
        if (key == x_key || k < 0) continue;
        group += (group.empty() ? "" : ", ") + key + "=" + row[k];
      }
      const std::string title = data.columns[c] + (group.empty() ? "" : " (" + group + ")");
      auto curve = std::find_if(series.begin(), series.end(), [&](const XySeries& s) { return s.title == title; });
      if (curve == series.end()) {
        if (series.size() == kMaxSeries) continue;
        curve = series.insert(series.end(), XySeries{title, {}});
      }
      curve->points.emplace_back(Number(row[x]), Number(row[c]));
    }
  }
  for (XySeries& curve : series) std::sort(curve.points.begin(), curve.points.end());
  return series;
}

// A sweep's check results: per check one line (points passing, the bound, the worst
// value and where), then the failing points in a closed <details> table.
void SweepCheckSummary(const std::vector<CheckResult>& results, HtmlSection* section) {
  std::vector<std::string> metrics;
  for (const CheckResult& result : results) {
    if (std::find(metrics.begin(), metrics.end(), result.metric) == metrics.end()) metrics.push_back(result.metric);
  }
  section->details.header = {"point", "check", "value", "bound", "why"};
  for (const std::string& metric : metrics) {
    std::size_t total = 0;
    std::size_t passing = 0;
    const CheckResult* worst = nullptr;
    for (const CheckResult& result : results) {
      if (result.metric != metric) continue;
      ++total;
      passing += result.passed ? 1 : 0;
      if (!result.passed) {
        section->details.rows.push_back({result.point, metric, result.value_text, result.bound, result.message});
        // The worst: the largest value above a max, the smallest below a min.
        const bool above = result.message.rfind("above", 0) == 0;
        if (worst == nullptr || (above ? result.value > worst->value : result.value < worst->value)) worst = &result;
      }
    }
    std::string text = metric + ": " + std::to_string(passing) + " of " + std::to_string(total) + " points pass";
    if (worst != nullptr) text += " (" + worst->bound + "); worst " + worst->value_text + " @ " + worst->point;
    section->checks.push_back({passing == total, text});
  }
  section->details_summary =
      std::to_string(section->details.rows.size()) + " failing point-checks (click to list them)";
  if (section->details.rows.empty()) section->details.header.clear();
}

}  // namespace

std::string EffectiveScenarioYaml(const std::string& path, const std::vector<Override>& overrides) {
  YAML::Emitter out;
  out << BuildScenarioTree(path, overrides);
  return std::string(out.c_str()) + "\n";
}

std::string XySvg(const std::string& x_label, const std::string& y_label,
                  const std::vector<XySeries>& series) {
  return RunGnuplotSvg("the sweep plot", [&](std::FILE* gnuplot, const std::string& output_path) {
    std::fprintf(gnuplot, "set terminal svg size 1000,600 noenhanced font 'sans,10' background '#ffffff'\n");
    std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output_path).c_str());
    std::fprintf(gnuplot, "set xlabel %s\nset ylabel %s\nset grid\n", GnuplotQuoted(x_label).c_str(),
                 GnuplotQuoted(y_label).c_str());
    std::fprintf(gnuplot, "set key outside right top\n");
    std::string plot;
    for (std::size_t s = 0; s < series.size(); ++s) {
      std::fprintf(gnuplot, "$s%zu << EOD\n", s);
      for (const auto& [x, y] : series[s].points) std::fprintf(gnuplot, "%.10g %.10g\n", x, y);
      std::fprintf(gnuplot, "EOD\n");
      plot += (plot.empty() ? "plot " : ", ") + std::string("$s") + std::to_string(s) +
              " using 1:2 with linespoints pt 7 ps 0.4 title " + GnuplotQuoted(series[s].title);
    }
    if (plot.empty()) plot = "plot NaN notitle";
    std::fprintf(gnuplot, "%s\nunset output\nquit\n", plot.c_str());
  });
}

HtmlReport RunHtmlReport(const Scenario& scenario, const RunResult& result,
                         const std::vector<CheckResult>& checks, const std::string& scenario_yaml) {
  HtmlReport report;
  report.title = "shapebench run: " + scenario.name;
  report.subtitle = scenario.source_file;
  HtmlSection metrics;
  metrics.heading = "Metrics";
  metrics.table = MetricsHtmlTable(result.metrics);
  report.sections.push_back(metrics);
  HtmlSection sources;
  sources.heading = "Where in the program";
  sources.note = "The block executing when each largest value was reached, and the latest change of the "
                 "commanded acceleration within one damped period of the lowest mode before it (the likely cause).";
  sources.table.header = {"metric", "at", "cause"};
  for (const auto& [name, source] : SourceEntries(result.sources)) {
    if (!source->present) continue;
    const std::string text = SourceText(*source);
    const std::size_t split = text.find("; cause ");
    sources.table.rows.push_back({name, text.substr(0, split), text.substr(split + 8)});
  }
  if (!sources.table.rows.empty()) report.sections.push_back(sources);
  HtmlSection plot;
  plot.heading = "Deflection";
  plot.note = "Deflection in um and command acceleration in m/s² against time; the static band dashed, "
              "the end of the commanded motion dotted.";
  plot.svg = DeflectionSvg(result, scenario);
  report.sections.push_back(plot);
  HtmlSection interactive;
  interactive.heading = "Interactive trace";
  interactive.note = "Drag to zoom (shift-drag to pan), double-click to reset; hover for the values.";
  interactive.svg = InteractiveTraceHtml(result);  // "" without libjs-dygraphs: the static plot only
  if (!interactive.svg.empty()) report.sections.push_back(interactive);
  if (!checks.empty()) {
    HtmlSection section;
    const bool passed = std::all_of(checks.begin(), checks.end(), [](const CheckResult& c) { return c.passed; });
    section.heading = std::string("Checks: ") + (passed ? "PASS" : "FAIL");
    section.checks = HtmlChecks(checks);
    report.sections.push_back(section);
  }
  report.sections.push_back(ScenarioYamlSection("Effective scenario", scenario_yaml));
  return report;
}

HtmlReport CheckHtmlReport(const std::vector<ScenarioCheckReport>& reports) {
  HtmlReport report;
  report.title = "shapebench check";
  std::size_t passed = 0;
  std::size_t failed = 0;
  std::size_t errors = 0;
  for (const ScenarioCheckReport& file : reports) {
    HtmlSection section;
    section.heading = file.name + " (" + file.file + ")";
    if (!file.error.empty()) {
      section.checks.push_back({false, "error: " + file.error});
      ++errors;
    }
    for (const auto& [point, message] : file.point_errors) {
      section.checks.push_back({false, "error @ " + point + ": " + message});
      ++errors;
    }
    const bool sweep = std::any_of(file.results.begin(), file.results.end(),
                                   [](const CheckResult& result) { return !result.point.empty(); });
    if (sweep) {
      SweepCheckSummary(file.results, &section);  // a line per check, the failures folded
    } else {
      section.checks = HtmlChecks(file.results);
    }
    for (const CheckResult& result : file.results) ++(result.passed ? passed : failed);
    report.sections.push_back(section);
  }
  const bool ok = failed == 0 && errors == 0;
  report.subtitle = std::string(ok ? "PASS" : "FAIL") + ": " + std::to_string(passed) + " passed, " +
                    std::to_string(failed) + " failed, " + std::to_string(errors) + " errors in " +
                    std::to_string(reports.size()) + " files";
  return report;
}

HtmlReport SweepHtmlReport(const SweepHtmlData& data) {
  HtmlReport report;
  report.title = "shapebench sweep: " + data.name;
  report.subtitle = data.file + ": " + std::to_string(data.rows.size()) + " points";
  for (const auto& [heading, svg] : data.plots) {  // the sweep's own plots, as its PNGs
    HtmlSection plot;
    plot.heading = heading;
    plot.svg = svg;
    report.sections.push_back(plot);
  }
  if (!data.bands.header.empty()) {
    HtmlSection bands;
    bands.heading = "Robust bands";
    bands.note = "Per series, the intervals of the swept key where the metric stays at or below the threshold "
                 "(the check's max, band_threshold: or its 5% level); rank 1 holds the design frequency when one "
                 "does (bands.csv).";
    bands.table = data.bands;
    report.sections.push_back(bands);
  }
  const std::string x_key = NumericKey(data);
  const std::vector<XySeries> series = data.plots.empty() ? SweepSeries(data, x_key) : std::vector<XySeries>{};
  if (!series.empty()) {
    HtmlSection plot;
    plot.heading = "Ratios against " + x_key;
    plot.svg = XySvg(x_key, "ratio", series);
    report.sections.push_back(plot);
  }
  HtmlSection table;
  table.heading = "Results";
  table.note = "results.csv, lengths in um and times in ms.";
  if (data.rows.size() > kMaxTableRows) {
    table.note += " The first " + std::to_string(kMaxTableRows) + " of " + std::to_string(data.rows.size()) +
                  " rows (results.csv has them all).";
  }
  table.table = SweepTable(data);
  report.sections.push_back(table);
  report.sections.push_back(ScenarioYamlSection("Base scenario", data.base_yaml));
  return report;
}

}  // namespace shapebench::bench
