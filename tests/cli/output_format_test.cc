// What the CLI prints and writes, as people and tools read it: --version, the "wrote"
// lines of --out, engineering units in tables, shortest exact CSV numbers, JUnit times and
// messages, the pattern report's table and machine modes.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/output/gnuplot.h"
#include "bench/output/report.h"
#include "bench/scenario/checks.h"
#include "common/format.h"
#include "bench/scenario/metrics.h"
#include "tests/support/bench_test_support.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;


// The first line `command` prints, without its newline ("" when it fails).
std::string FirstLine(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "";
  char buffer[256] = {};
  const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  const int status = pclose(pipe);
  if (!read || status != 0) return "";
  std::string line = buffer;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  return line;
}

// Every line of `text` that starts with "wrote ".
std::vector<std::string> WroteLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("wrote ", 0) == 0) lines.push_back(line.substr(6));
  }
  return lines;
}

// Every field of a CSV text that parses fully as a number.
std::vector<std::string> NumberFields(const std::string& text) {
  std::vector<std::string> numbers;
  std::istringstream in(text);
  CsvReader reader(in);
  std::vector<std::string> fields;
  while (reader.Next(&fields)) {
    for (const std::string& field : fields) {
      char* end = nullptr;
      std::strtod(field.c_str(), &end);
      if (!field.empty() && end == field.c_str() + field.size()) numbers.push_back(field);
    }
  }
  return numbers;
}

// Tests that --version prints "shapebench " and the source tree's git describe (baked in
// at build time), or "unknown" outside a git checkout.
TEST(OutputFormat, VersionIsTheGitDescribeOfTheSource) {
  const CliResult r = RunCli({"--version"}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string described =
      FirstLine("git -C '" + std::string(kSourceDir) + "' describe --always --dirty 2>/dev/null");
  EXPECT_EQ(r.out, "shapebench " + (described.empty() ? std::string("unknown") : described) + "\n");
  EXPECT_EQ(r.err, "");
}

// Tests that lengths print in um below 1 mm and mm below 1 m, times in ms below 1 s,
// frequencies in Hz and ratios bare; zero keeps the SI unit, NaN is n/a.
TEST(OutputFormat, EngineeringTextChoosesThePrefixByMagnitude) {
  EXPECT_EQ(EngineeringText(7.99855e-06, "m"), "7.99855 um");
  EXPECT_EQ(EngineeringText(-3e-6, "m"), "-3 um");
  EXPECT_EQ(EngineeringText(0.0125, "m"), "12.5 mm");
  EXPECT_EQ(EngineeringText(1.5, "m"), "1.5 m");
  EXPECT_EQ(EngineeringText(0.0, "m"), "0 m");
  EXPECT_EQ(EngineeringText(0.25, "s"), "250 ms");
  EXPECT_EQ(EngineeringText(2.0, "s"), "2 s");
  EXPECT_EQ(EngineeringText(25.0, "Hz"), "25 Hz");
  EXPECT_EQ(EngineeringText(0.726, "1"), "0.726");
  EXPECT_EQ(EngineeringText(3.0, "count"), "3");
  EXPECT_EQ(EngineeringText(NAN, "m"), "n/a");
  EXPECT_EQ(EngineeringText(1.23456789e-6, "m", 3), "1.23 um");
}

// Tests that the metrics table shows lengths and times in engineering units, never an
// exponent of a metre or second.
TEST(OutputFormat, MetricsTableUsesEngineeringUnits) {
  Metrics metrics;
  metrics.residual_amplitude_m = 7.99855e-06;
  metrics.motion_time_s = 0.4125;
  metrics.residual_ratio = 0.0613;
  std::ostringstream out;
  PrintMetricsTable(out, metrics);
  const std::string table = out.str();
  EXPECT_TRUE(std::regex_search(table, std::regex("residual_amplitude_m +7\\.99855 um\n"))) << table;
  EXPECT_TRUE(std::regex_search(table, std::regex("motion_time_s +412\\.5 ms\n"))) << table;
  EXPECT_TRUE(std::regex_search(table, std::regex("residual_ratio +0\\.0613\n"))) << table;
  EXPECT_EQ(table.find("e-0"), std::string::npos) << table;
}

// Tests that a check line shows a length's value and bound in um (and the bound's
// message), ratios as before.
TEST(OutputFormat, CheckLinesUseEngineeringUnits) {
  const CheckResult length = EvaluateCheck(Check{"residual_amplitude_m", std::nullopt, 1e-5}, 2e-5);
  EXPECT_EQ(FormatCheckLine("f.yaml", length),
            "FAIL f.yaml residual_amplitude_m = 20 um (max 10 um): above max 10 um");
  const CheckResult ratio = EvaluateCheck(Check{"residual_ratio", std::nullopt, 0.05}, 0.0613);
  EXPECT_EQ(FormatCheckLine("f.yaml", ratio), "FAIL f.yaml residual_ratio = 0.0613 (max 0.05): above max 0.05");
  // A value that rounds to its bound still shows the digits that tell them apart.
  const CheckResult close = EvaluateCheck(Check{"motion_time_s", std::nullopt, 0.5}, 0.50000001);
  EXPECT_NE(close.value_text, "500 ms");
  EXPECT_EQ(close.bound, "max 500 ms");
}

// Tests that CSV numbers are the shortest text that reads back as the same double.
TEST(OutputFormat, ExactDoubleIsShortestRoundTrip) {
  EXPECT_EQ(ExactDouble(0.726), "0.726");
  EXPECT_EQ(ExactDouble(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(ExactDouble(25.0), "25");
  EXPECT_EQ(ExactDouble(NAN), "");
  EXPECT_EQ(ExactDouble(std::numeric_limits<double>::infinity()), "inf");
  std::uint64_t state = 12345;
  for (int i = 0; i < 10000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double x = std::ldexp(static_cast<double>(state >> 11), -53) * std::pow(10.0, i % 40 - 20);
    const std::string text = ExactDouble(i % 2 == 0 ? x : -x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), i % 2 == 0 ? x : -x) << text;
    char longer[40];
    std::snprintf(longer, sizeof longer, "%.17g", x);
    EXPECT_LE(text.size(), std::string(longer).size() + (i % 2 == 0 ? 0 : 1)) << text;
  }
}

// Tests that run --out lists the six files it wrote as "wrote DIR/FILE" after the table,
// that they exist, and that every number of trace.csv is in its shortest exact form.
TEST(OutputFormat, RunOutListsWhatItWroteAndTraceNumbersAreShortest) {
  ScratchDir dir;
  const std::string out = dir.File("run");
  const CliResult r = RunCli({"run", DataPath("shaped_method1_xy.yaml")  /* an XY path: path.png too */, "--out", out}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> wrote = WroteLines(r.out);
  EXPECT_EQ(wrote, (std::vector<std::string>{out + "/metrics.json", out + "/trace.csv", out + "/trace.mat",
                                             out + "/deflection.png", out + "/path.png", out + "/command.png"}))
      << r.out;
  for (const std::string& file : wrote) EXPECT_TRUE(std::filesystem::exists(file)) << file;
  EXPECT_EQ(PngDefect(out + "/command.png"), "");  // shaped against unshaped: gnuplot drew both
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> numbers = NumberFields(ReadText(out + "/trace.csv"));
  ASSERT_GT(numbers.size(), 1000u);
  for (const std::string& number : numbers) {
    ASSERT_EQ(number, ExactDouble(std::strtod(number.c_str(), nullptr))) << number;
  }
  // --json: stdout stays one JSON document, the list goes to stderr.
  const std::string json_out = dir.File("json");
  const CliResult j = RunCli({"run", DataPath("shaped_method1_xy.yaml")  /* an XY path: path.png too */, "--json", "--out", json_out}, kSourceDir);
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_TRUE(nlohmann::json::accept(j.out)) << j.out;
  EXPECT_EQ(WroteLines(j.err).size(), 6u) << j.err;
}

// Tests that sensitivity --out lists its CSV and plot.
TEST(OutputFormat, SensitivityOutListsWhatItWrote) {
  ScratchDir dir;
  const std::string out = dir.File("sens");
  const CliResult r = RunCli({"sensitivity", "configs/sensitivity/shapers.yaml", "--out", out}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(WroteLines(r.out),
            (std::vector<std::string>{out + "/sensitivity.csv", out + "/sensitivity.png"}))
      << r.out;
}

// Tests that sweep --out lists the manifest, results.csv and every plot it drew, and that
// every metric in results.csv is in its shortest exact form ("0.726", not
// "0.72599999999999998").
TEST(OutputFormat, SweepOutListsWhatItWroteAndCsvNumbersAreShortest) {
  ScratchDir dir;
  const std::string out = dir.File("sweep");
  const CliResult r =
      RunCli({"sweep", "tests/bench/data/sweeps/map.yaml", "--jobs", "1", "--out", out}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> wrote = WroteLines(r.out);
  ASSERT_GE(wrote.size(), 5u) << r.out;  // manifest, results and three plots
  EXPECT_EQ(wrote[0], out + "/manifest.json");
  EXPECT_EQ(wrote[1], out + "/results.csv");
  for (const std::string& file : wrote) EXPECT_TRUE(std::filesystem::exists(file)) << file;
  EXPECT_EQ(r.out.find("\nplot "), std::string::npos) << r.out;
  const std::vector<std::string> numbers = NumberFields(ReadText(out + "/results.csv"));
  ASSERT_GT(numbers.size(), 40u);
  for (const std::string& number : numbers) {
    EXPECT_EQ(number, ExactDouble(std::strtod(number.c_str(), nullptr))) << number;
  }
}

// Tests that a JUnit testcase carries the time of its run and a failure message naming
// the value and the bound it crossed.
TEST(OutputFormat, JUnitHasRunTimesAndValueAndLimitInFailures) {
  ScenarioCheckReport report;
  report.file = "f.yaml";
  report.name = "f";
  report.run_time_s = 0.02;
  CheckResult failed = EvaluateCheck(Check{"residual_ratio", std::nullopt, 0.05}, 0.0613);
  failed.run_time_s = 0.012;
  CheckResult passed = EvaluateCheck(Check{"peak_ratio", std::nullopt, 1.1}, 1.0);
  passed.run_time_s = 0.0071;
  report.results = {failed, passed};
  ScratchDir dir;
  WriteJUnit(dir.File("junit.xml"), {report});
  const std::string xml = ReadText(dir.File("junit.xml"));
  EXPECT_NE(xml.find("name=\"residual_ratio\" time=\"0.012\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"peak_ratio\" time=\"0.007\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("message=\"residual_ratio = 0.0613 &gt; max 0.05\""), std::string::npos) << xml;
}

// Tests that `check --junit` on a sweep gives each point's testcase its measured time
// (not 0) and a failure message with the value and the bound.
TEST(OutputFormat, CheckJUnitTimesAreMeasured) {
  ScratchDir dir;
  const std::string junit = dir.File("junit.xml");
  const CliResult r = RunCli(
      {"check", "tests/bench/data/sweeps/failing_point.yaml", "--jobs", "1", "--junit", junit,
       // CVODE: a few ms a point, so the 3-decimal times cannot all round to 0.000
       "--set", "integrator.method=cvode"},
      kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const std::string xml = ReadText(junit);
  const std::regex testcase("<testcase [^>]*time=\"([0-9.]+)\"");
  double total_s = 0.0;
  int cases = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), testcase); it != std::sregex_iterator(); ++it) {
    total_s += std::stod((*it)[1].str());
    ++cases;
  }
  EXPECT_EQ(cases, 6);  // 3 points x 2 checks
  EXPECT_GT(total_s, 0.0) << xml;
  EXPECT_NE(xml.find("message=\"residual_ratio @ machine.modes[0].frequency_hz=24.5 = "), std::string::npos)
      << xml;
}

// Tests that the pattern report lists only the profile table's coefficients above 1e-4 of
// the largest, counting the rest, and the residual vibration at each of the machine's
// modes with its own damping.
TEST(OutputFormat, PatternListsTheLargeCoefficientsAndEveryMachineMode) {
  const CliResult r = RunCli({"pattern", "configs/scenarios/gantry_zvd.yaml"}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::regex hidden("  \\.\\.\\. and ([0-9]+) more below 0\\.0001 of the largest \\(\\|alpha_n\\| <= [^,]+, sum [^)]+\\)\n");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(r.out, match, hidden)) << r.out;
  EXPECT_GT(std::stoi(match[1].str()), 0);
  const std::size_t machine = r.out.find("residual vibration at the machine's modes");
  ASSERT_NE(machine, std::string::npos) << r.out;
  const CliResult modes = RunCli({"modes", "configs/scenarios/gantry_zvd.yaml", "--json"}, kSourceDir);
  ASSERT_EQ(modes.exit_code, 0) << modes.err;
  const std::string section = r.out.substr(machine);
  int rows = 0;
  const std::regex row("\n  ([xyz]) +([0-9]+) +([0-9.e+-]+) +([0-9.e+-]+) +[0-9.e+-]+ +[0-9.e+-]+ +[0-9.e+-]+");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), row); it != std::sregex_iterator(); ++it) {
    ++rows;
  }
  EXPECT_EQ(static_cast<std::size_t>(rows), nlohmann::json::parse(modes.out).at("modes").size()) << section;
  EXPECT_GT(rows, 0);
}

}  // namespace
}  // namespace shapebench::bench
