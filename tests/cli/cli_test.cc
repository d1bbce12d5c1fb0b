// The built CLI as users' scripts see it: exit codes, stdout/stderr formats, files.
#include <filesystem>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/metrics.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;


// "error: FILE:LINE:COL: key.path: message" on one line.
bool IsLocatedError(const std::string& err, const std::string& file, const std::string& key_path) {
  const std::regex pattern("error: " + std::regex_replace(file, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                           ":[0-9]+:[0-9]+: " +
                           std::regex_replace(key_path, std::regex(R"([.\[\]])"), R"(\$&)") +
                           ": .+\n");
  return std::regex_search(err, pattern);
}

// Tests that `run` prints the metrics table and exits 0.
TEST(Cli, RunPrintsTable) {
  const CliResult r = RunCli({"run", DataPath("shaped_method1.yaml")}, kSourceDir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const auto& [name, value] : Metrics{}.Named()) {
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  }
  EXPECT_TRUE(r.err.empty()) << r.err;
}

// Tests that `run --json` prints exactly one JSON object carrying every metric name, then
// residual_modes (per pole its frequency, damping and amplitude, summing to
// residual_amplitude_m) and integrator_rtol_used.
TEST(Cli, RunJsonIsOneObject) {
  const CliResult r = RunCli({"run", DataPath("shaped_method1.yaml"), "--json"}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);  // throws on trailing text
  ASSERT_TRUE(json.is_object());
  for (const auto& [name, value] : Metrics{}.Named()) EXPECT_TRUE(json.contains(name)) << name;
  EXPECT_EQ(json.size(), Metrics{}.Named().size() + 6);  // + residual_modes, integrator_rtol_used, 4 *_source
  EXPECT_TRUE(json.contains("integrator_rtol_used"));
  const nlohmann::json& modes = json.at("residual_modes");
  ASSERT_EQ(modes.size(), 1u);  // one 25 Hz mode
  EXPECT_NEAR(modes[0].at("frequency_hz").get<double>(), 25.0, 1e-9);
  EXPECT_DOUBLE_EQ(modes[0].at("amplitude_m").get<double>(), json["residual_amplitude_m"].get<double>());
  EXPECT_LT(json["peak_ratio"].get<double>(), 1.01);
}

// Tests that `run --set` changes the run (method none doubles the peak, Fig. 2).
TEST(Cli, RunSetOverrides) {
  const CliResult r = RunCli({"run", DataPath("shaped_method1.yaml"), "--json", "--set",
                              "controller.pattern.method=none"},
                             kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["peak_ratio"].get<double>(), 2.0, 0.01);
}

// Tests that `run --out DIR` creates DIR with metrics.json, trace.csv, trace.mat and the PNG
// plots (deflection over time, XY path, command), and says nothing on stderr (gnuplot's warnings reach
// it: a move along one axis once gave "empty x range").
TEST(Cli, RunOutWritesFiles) {
  ScratchDir dir;
  const std::string out = dir.File("nested/out");
  const CliResult r = RunCli({"run", DataPath("shaped_method1_xy.yaml"), "--out", out}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto metrics = nlohmann::json::parse(ReadText(out + "/metrics.json"));
  EXPECT_EQ(metrics.size(), Metrics{}.Named().size() + 6);  // and residual_modes, integrator_rtol_used, 4 *_source
  EXPECT_TRUE(metrics.at("residual_modes").is_array());
  const std::string csv = ReadText(out + "/trace.csv");
  EXPECT_EQ(csv.rfind("t_s,command_position_m,command_velocity_m_s,command_accel_m_s2,deflection_m,", 0), 0u);
  const std::string png = ReadText(out + "/deflection.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(ReadText(out + "/path.png").substr(1, 3), "PNG");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 6u);  // no temporaries left behind
}

// Tests that bad input exits 2 with a located error on stderr and writes nothing.
TEST(Cli, BadInputExits2AndWritesNothing) {
  ScratchDir dir;
  const std::string out = dir.File("out");
  const std::string scenario = DataPath("unknown_key.yaml");
  const CliResult r = RunCli({"run", scenario, "--out", out}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(IsLocatedError(r.err, scenario, "controller.feed_rate")) << r.err;
  EXPECT_NE(r.err.find("allowed: period_s, feed_mm_min"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Tests that an error in a referenced machine file names that file, and writes nothing.
TEST(Cli, MachineFileErrorNamesThatFile) {
  ScratchDir dir;
  const std::string out = dir.File("out");
  const CliResult r =
      RunCli({"run", "tests/bench/data/uses_bad_machine_file.yaml", "--out", out}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "error: tests/bench/data/machines/bad_damping.yaml:3:41: "
            "machine.modes[1].damping_ratio: " +
                r.err.substr(r.err.find("damping_ratio: ") + 15));
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Tests that a bad --set is reported as --set:N:1 with its key path, exit 2.
TEST(Cli, BadSetReportsItsIndex) {
  const CliResult r = RunCli({"run", DataPath("shaped_method1.yaml"), "--set", "move.distance_mm=5",
                              "--set", "controller.period_s=-1"},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("error: --set:2:1: controller.period_s: ", 0), 0u) << r.err;
}

// Tests that a solver failure exits 3 with "error: solver failed: FLAG: ...", writes no
// output directory, and is a JUnit <error> under `check`.
TEST(Cli, SolverFailureExits3) {
  ScratchDir dir;
  const std::vector<std::string> starve = {"--set", "integrator.method=cvode", "--set",
                                           "integrator.max_num_steps=1", "--set",
                                           "integrator.rtol=1e-10"};
  std::vector<std::string> run = {"run", DataPath("shaped_method1.yaml"), "--out", dir.File("out")};
  run.insert(run.end(), starve.begin(), starve.end());
  const CliResult r = RunCli(run, kSourceDir);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(^error: solver failed: CV_[A-Z_]+: )"))) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out")));

  std::vector<std::string> check = {"check", DataPath("shaped_method1.yaml"), "--junit",
                                    dir.File("report.xml")};
  check.insert(check.end(), starve.begin(), starve.end());
  const CliResult c = RunCli(check, kSourceDir);
  EXPECT_EQ(c.exit_code, 3) << c.err;
  EXPECT_EQ(std::system(("xmllint --noout " + testing::ShellQuoted(dir.File("report.xml"))).c_str()), 0);
  EXPECT_NE(ReadText(dir.File("report.xml")).find("<error type=\"RunError\""), std::string::npos);
}

// Tests that usage errors (CLI11) print "error:" and the usage, exit 2.
TEST(Cli, UsageErrorsExit2) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{}, {"run"}, {"frobnicate"}, {"run", "a.yaml", "--bogus"}}) {
    const CliResult r = RunCli(args, kSourceDir);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("Usage"), std::string::npos) << r.err;
  }
  EXPECT_EQ(RunCli({"--help"}, kSourceDir).exit_code, 0);
}

// Tests that `check` prints PASS lines and exits 0 when every check holds.
TEST(Cli, CheckPasses) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const CliResult r =
      RunCli({"check", "tests/bench/data/shaped_method1.yaml", "--junit", junit}, kSourceDir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::regex_search(
      r.out, std::regex(R"(^PASS tests/bench/data/shaped_method1\.yaml peak_ratio = \S+ \(max 1\.01\)\n)")))
      << r.out;
  EXPECT_NE(r.out.find("PASS tests/bench/data/shaped_method1.yaml residual_ratio = "),
            std::string::npos);
  EXPECT_EQ(std::system(("xmllint --noout " + testing::ShellQuoted(junit)).c_str()), 0);
}

// Tests that a failing check exits 1 and writes valid JUnit XML recording the failure.
TEST(Cli, CheckFailureExits1WithJUnit) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const CliResult r = RunCli({"check", "tests/bench/data/shaped_method1.yaml",
                              "tests/bench/data/unshaped_fails.yaml", "--junit", junit},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("FAIL tests/bench/data/unshaped_fails.yaml peak_ratio = 2"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PASS tests/bench/data/unshaped_fails.yaml motion_time_s = "),
            std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 4);
  ASSERT_TRUE(std::filesystem::exists(junit));
  EXPECT_EQ(std::system(("xmllint --noout " + testing::ShellQuoted(junit)).c_str()), 0);
  const std::string xml = ReadText(junit);
  EXPECT_NE(xml.find("tests=\"4\" failures=\"1\" errors=\"0\""), std::string::npos) << xml;
}

// Tests that `check` on a file without checks is bad input (exit 2), nothing written.
TEST(Cli, CheckWithoutChecksExits2) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const CliResult r = RunCli({"check", "tests/bench/data/shaped_method1.yaml",
                              "tests/bench/data/no_checks.yaml", "--junit", junit},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("error: tests/bench/data/no_checks.yaml: checks: ", 0), 0u) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(std::filesystem::exists(junit));
}

// Tests that `modes --json` has exactly the documented shape: the documented keys, each mode with
// its axis, and the static deflection per modelled axis (a single-form machine: Y only).
TEST(Cli, ModesJsonShape) {
  const CliResult r = RunCli({"modes", DataPath("machines/two_modes.yaml"), "--json"}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json.size(), 3u);
  ASSERT_TRUE(json["modes"].is_array());
  ASSERT_EQ(json["modes"].size(), 2u);
  for (const auto& mode : json["modes"]) {
    ASSERT_EQ(mode.size(), 4u);
    EXPECT_EQ(mode["axis"], "y");
    EXPECT_TRUE(mode["frequency_hz"].is_number());
    EXPECT_TRUE(mode["damping_ratio"].is_number());
    EXPECT_TRUE(mode["participation"].is_number());
  }
  EXPECT_NEAR(json["modes"][0]["frequency_hz"].get<double>(), 25.0, 1e-6);
  EXPECT_TRUE(json["static_deflection_per_accel_s2"].is_number());
  const nlohmann::json& by_axis = json["static_deflection_per_accel_s2_by_axis"];
  ASSERT_TRUE(by_axis.is_object());
  ASSERT_EQ(by_axis.size(), 1u);
  EXPECT_EQ(by_axis["y"], json["static_deflection_per_accel_s2"]);
}

// Tests that `modes` reads a scenario's machine too, with --set, and prints a table.
TEST(Cli, ModesOfScenarioWithSet) {
  const CliResult r = RunCli({"modes", DataPath("uses_machine_file.yaml"), "--set",
                              "machine.modes[1].frequency_hz=120"},
                             kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("120"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("static_deflection_per_accel_s2"), std::string::npos) << r.out;
}

// Tests that `pattern` prints the para. 49 parameters, impulses, profile table and
// residual for method 2 (ST1 = ST2 = T/6 = 66.6667 x 0.1 ms at 25 Hz).
TEST(Cli, PatternReport) {
  const CliResult r = RunCli({"pattern", DataPath("uses_machine_file.yaml")}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ST1 = 66.6667 (0.1 ms units)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("SR2 = 0.000000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mode = 1 (start of acc/dec only)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("profile table"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("residual vibration at 25 Hz"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace shapebench::bench
