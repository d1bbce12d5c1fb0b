// The metric table (bench/scenario/metrics.h): one row per metric, read by JSON, tables, CSV
// columns, checks, and the glossary in docs/metrics.md.
#include "bench/scenario/metrics.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/output/html_report.h"
#include "bench/output/report.h"

namespace shapebench::bench {
namespace {

// The glossary rows of docs/metrics.md as the table writes them.
std::string GlossaryRow(const MetricInfo& info) {
  std::ostringstream row;
  row << "| `" << info.name << "` | " << info.unit << " | " << BetterName(info.better) << " | "
      << info.description << " |";
  return row.str();
}

// Tests that every metric has a unique name, a known unit, a description and a field of
// its own, and that the unit matches the name's suffix (_m metres, _s seconds).
TEST(MetricTable, RowsAreComplete) {
  std::set<std::string_view> names;
  std::vector<double Metrics::*> fields;
  for (const MetricInfo& info : MetricTable()) {
    EXPECT_TRUE(names.insert(info.name).second) << info.name;
    for (auto field : fields) EXPECT_NE(field, info.field) << info.name;
    fields.push_back(info.field);
    EXPECT_FALSE(info.description.empty()) << info.name;
    const std::set<std::string_view> units = {"m", "s", "Hz", "m/s^2", "1", "count", "bool"};
    EXPECT_EQ(units.count(info.unit), 1u) << info.name;
    const std::string name(info.name);
    if (name.size() > 2 && name.substr(name.size() - 2) == "_m") {
      EXPECT_EQ(info.unit, "m") << name;
    }
    if (name.size() > 2 && name.substr(name.size() - 2) == "_s") {
      EXPECT_EQ(info.unit, "s") << name;
    }
  }
  EXPECT_EQ(names.size(), MetricTable().size());
}

// Tests that JSON, the table and Named() list exactly the table's metrics, in its order.
TEST(MetricTable, EveryOutputReadsIt) {
  Metrics metrics;
  double value = 1.0;
  for (const MetricInfo& info : MetricTable()) metrics.*info.field = (value += 1.0);
  const auto json = MetricsJson(metrics);
  std::size_t i = 0;
  for (const auto& [name, entry] : json.items()) {
    ASSERT_LT(i, MetricTable().size());
    EXPECT_EQ(name, MetricTable()[i].name);
    EXPECT_EQ(entry.is_boolean(), MetricTable()[i].is_bool()) << name;
    ++i;
  }
  EXPECT_EQ(i, MetricTable().size());
  const auto named = metrics.Named();
  ASSERT_EQ(named.size(), MetricTable().size());
  for (std::size_t k = 0; k < MetricTable().size(); ++k) {
    EXPECT_EQ(named[k].first, MetricTable()[k].name);
    EXPECT_EQ(named[k].second, metrics.*MetricTable()[k].field);
  }
  EXPECT_EQ(MetricNames().size(), MetricTable().size());
  EXPECT_EQ(FindMetric("no_such_metric"), nullptr);
  EXPECT_EQ(FindMetric("peak_ratio")->field, &Metrics::peak_ratio);
}

// Tests that the glossary in docs/metrics.md is the metric table, row for row.
TEST(MetricTable, GlossaryInTheDocsIsTheTable) {
  std::ifstream in(std::string(SHAPEBENCH_SOURCE_DIR) + "/docs/metrics.md");
  ASSERT_TRUE(in) << "docs/metrics.md is missing";
  std::vector<std::string> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) == 0) rows.push_back(line);
  }
  std::string expected;
  for (const MetricInfo& info : MetricTable()) expected += GlossaryRow(info) + "\n";
  // Then the table of the metrics of plants with nonlinear elements.
  for (const MetricInfo& info : NonlinearMetricTable()) expected += GlossaryRow(info) + "\n";
  std::string actual;
  for (const std::string& row : rows) actual += row + "\n";
  EXPECT_EQ(actual, expected) << "docs/metrics.md's glossary should read:\n" << expected;
}

// Tests that the nonlinear plants' metrics are complete rows of their own: unique names
// that no MetricTable() row has, a unit matching the suffix, a field of their own; FindMetric
// finds them, MetricNames() (every run's columns) leaves them out and AllMetricNames() has
// them; JSON, the table and the HTML report's table leave them out where undefined and
// write them where defined.
TEST(MetricTable, NonlinearMetricsAreRowsOfTheirOwn) {
  std::set<std::string_view> names;
  for (const MetricInfo& info : MetricTable()) names.insert(info.name);
  const std::vector<std::string> main_names = MetricNames();
  const std::vector<std::string> all = AllMetricNames();
  EXPECT_EQ(all.size(), MetricTable().size() + NonlinearMetricTable().size());
  for (const MetricInfo& info : NonlinearMetricTable()) {
    EXPECT_TRUE(names.insert(info.name).second) << info.name;
    EXPECT_EQ(info.unit, "m") << info.name;
    EXPECT_FALSE(info.description.empty());
    EXPECT_EQ(FindMetric(info.name), &info);
    for (const MetricInfo& other : MetricTable()) EXPECT_NE(other.field, info.field) << info.name;
    EXPECT_EQ(std::count(main_names.begin(), main_names.end(), std::string(info.name)), 0);
    EXPECT_EQ(std::count(all.begin(), all.end(), std::string(info.name)), 1);
  }
  Metrics metrics;
  EXPECT_EQ(MetricsJson(metrics).size(), MetricTable().size());
  std::ostringstream table;
  PrintMetricsTable(table, metrics);
  EXPECT_EQ(table.str().find("dead_band_m"), std::string::npos);
  metrics.dead_band_m = 1.5e-6;
  const auto json = MetricsJson(metrics);
  EXPECT_EQ(json.size(), MetricTable().size() + 1);
  EXPECT_EQ(json["dead_band_m"].get<double>(), 1.5e-6);
  EXPECT_FALSE(json.contains("quadrant_glitch_m"));
  std::ostringstream with;
  PrintMetricsTable(with, metrics);
  EXPECT_NE(with.str().find("dead_band_m"), std::string::npos);
  const HtmlTable html = MetricsHtmlTable(metrics);
  ASSERT_EQ(html.rows.size(), MetricTable().size() + 1);  // the HTML report's table likewise
  EXPECT_EQ(html.rows.back().front(), "dead_band_m");
}

}  // namespace
}  // namespace shapebench::bench
