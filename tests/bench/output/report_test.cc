// The metrics table and JSON, the trace CSV, JUnit XML and atomic file writing.
#include "bench/output/report.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "common/atomic_file.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ReadText;
using testing::ScratchDir;

Metrics SomeMetrics() {
  Metrics metrics;
  metrics.static_displacement_m = 8.1e-6;
  metrics.peak_deflection_m = 1.62e-5;
  metrics.peak_ratio = 2.0;
  metrics.motion_time_s = 1.05;
  return metrics;
}

// Tests that the table has one aligned line per metric with (engineering) units and n/a for NaN.
TEST(Report, MetricsTable) {
  std::ostringstream out;
  PrintMetricsTable(out, SomeMetrics());
  const std::string text = out.str();
  // The names padded to the longest metric name and two blanks.
  std::size_t width = 0;
  for (const MetricInfo& info : MetricTable()) width = std::max(width, info.name.size());
  const auto row = [&](const std::string& name, const std::string& value) {
    return name + std::string(width + 2 - name.size(), ' ') + value + "\n";
  };
  EXPECT_NE(text.find(row("static_displacement_m", "8.1 um")), std::string::npos) << text;  // engineering units
  EXPECT_NE(text.find(row("peak_ratio", "2")), std::string::npos) << text;
  EXPECT_NE(text.find(row("motion_time_s", "1.05 s")), std::string::npos) << text;
  EXPECT_NE(text.find(row("settling_time_s", "n/a")), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'),
            static_cast<long>(Metrics{}.Named().size()));
}

// Tests that the JSON keeps Named() order and writes NaN as null.
TEST(Report, MetricsJsonOrderAndNull) {
  const auto json = MetricsJson(SomeMetrics());
  const auto named = Metrics{}.Named();
  ASSERT_EQ(json.size(), named.size());
  std::size_t i = 0;
  for (auto it = json.begin(); it != json.end(); ++it, ++i) EXPECT_EQ(it.key(), named[i].first);
  EXPECT_TRUE(json["settling_time_s"].is_null());
  EXPECT_DOUBLE_EQ(json["peak_ratio"].get<double>(), 2.0);
}

// Tests that the trace CSV has the documented header and full-precision rows.
TEST(Report, TraceCsv) {
  ScratchDir dir;
  Trace trace;
  trace.time_s = {0.0, 0.1};
  trace.command_position_m = {0.0, 1.0 / 3.0};
  trace.command_velocity_m_s = {0.0, 2.0};
  trace.command_accel_m_s2 = {0.0, -4.0};
  trace.deflection_m = {0.0, 1e-6};
  trace.command_m = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.25, 0)};
  trace.actual_m = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.25, 1e-6)};
  trace.deflection_axes_m = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1e-6)};
  trace.block = {0, -1};
  trace.planned_feed_mm_min = {6000, 0};
  const std::string path = dir.File("trace.csv");
  WriteTraceCsv(path, trace);
  EXPECT_EQ(ReadText(path),
            "t_s,command_position_m,command_velocity_m_s,command_accel_m_s2,deflection_m,"
            "command_x_m,command_y_m,command_z_m,actual_x_m,actual_y_m,actual_z_m,"
            "deflection_x_m,deflection_y_m,deflection_z_m,block,planned_feed_mm_min\n"
            "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,6000\n"
            "0.1,0.3333333333333333,2,-4,1e-06,0.5,0.25,0,"  // shortest exact (common/csv.h)
            "0.5,0.25,1e-06,0,0,1e-06,-1,0\n");
}

// Tests that XML special characters and bytes XML cannot hold are escaped or dropped.
TEST(Report, XmlEscape) {
  EXPECT_EQ(XmlEscape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&apos;");
  EXPECT_EQ(XmlEscape(std::string("x\x01y", 3)), "x\xEF\xBF\xBDy");
  EXPECT_EQ(XmlEscape("\xC2\xB5m"), "\xC2\xB5m");  // valid UTF-8 kept
  EXPECT_EQ(XmlEscape("\xFFz"), "\xEF\xBF\xBDz");
}

// Tests that the JUnit report counts tests, failures and errors and escapes names.
TEST(Report, JUnitCounts) {
  ScratchDir dir;
  ScenarioCheckReport ok{"a&b.yaml", "a", {}, "", 0.5, {}};
  CheckResult pass{"peak_ratio", 1.0, "1", "max 1.01", true, "", ""};
  CheckResult fail{"residual_ratio", 0.5, "0.5", "max 0.01", false, "above max 0.01", ""};
  ok.results = {pass, fail};
  ScenarioCheckReport broken{"b.yaml", "b", {}, "solver failed: CV_TOO_MUCH_WORK: <x>", 0.1, {}};
  const std::string path = dir.File("junit.xml");
  WriteJUnit(path, {ok, broken});
  const std::string xml = ReadText(path);
  EXPECT_NE(xml.find("<testsuites name=\"shapebench check\" tests=\"3\" failures=\"1\" errors=\"1\""),
            std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"a&amp;b.yaml\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("CV_TOO_MUCH_WORK: &lt;x&gt;"), std::string::npos) << xml;
  // The message names the value and the bound it crossed.
  EXPECT_NE(xml.find("<failure type=\"CheckFailed\" message=\"residual_ratio = 0.5 &gt; max 0.01\">"),
            std::string::npos) << xml;
}

// Tests that a band check's JUnit properties carry the shortest text that reads back as
// the same double ("18.15", not "18.149999999999999").
TEST(Report, JUnitBandNumbersAreShortest) {
  ScratchDir dir;
  ScenarioCheckReport report{"a.yaml", "a", {}, "", 0.5, {}};
  CheckResult band{"residual_ratio", 0.061, "0.061", "max 0.05", false, "above max 0.05", ""};
  band.band_key = "machine.modes[0].frequency_hz";
  band.band_from = 15.0;
  band.band_to = 35.0;
  band.worst_at = 18.15;
  band.band_runs = 40;
  report.results = {band};
  const std::string path = dir.File("junit.xml");
  WriteJUnit(path, {report});
  const std::string xml = ReadText(path);
  EXPECT_NE(xml.find("<property name=\"worst_at\" value=\"18.15\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<property name=\"worst_value\" value=\"0.061\"/>"), std::string::npos) << xml;
}

// Tests that atomic writes leave only the final file, and nothing when writing fails.
TEST(Report, AtomicWriteLeavesNoTemporaries) {
  ScratchDir dir;
  WriteFileAtomically(dir.File("x.txt"), [](std::ostream& out) { out << "done"; });
  EXPECT_EQ(ReadText(dir.File("x.txt")), "done");
  EXPECT_THROW(WriteFileAtomically(dir.File("y.txt"),
                                   [](std::ostream&) { throw std::runtime_error("midway"); }),
               std::runtime_error);
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(names, std::vector<std::string>{"x.txt"});
  EXPECT_THROW(WriteFileAtomically(dir.File("missing/dir/z.txt"), [](std::ostream&) {}),
               std::runtime_error);
}

}  // namespace
}  // namespace shapebench::bench
