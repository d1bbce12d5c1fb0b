// Band checks (bench/sweep/band_check.h): the worst value of a metric over a range of one
// key, against a dense scan through the same run function; the CLI's line, JSON and
// JUnit; band keys' errors located in the scenario file.
#include "bench/sweep/band_check.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/metrics.h"
#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

const std::string kKey = "machine.modes[0].frequency_hz";

// The shipped method 1 scenario (the patent's pattern, designed for 25 Hz) with its
// checks replaced by `checks` (YAML lines after "checks:").
std::string Method1With(const std::string& checks) {
  const std::string shipped = testing::ReadText(kSourceDir + "/configs/scenarios/sdof_method1.yaml");
  return shipped.substr(0, shipped.find("\nchecks:")) + "\nchecks:\n" + checks;
}

// The band check's result over [from, to] against a dense scan through the same run
// function (6001 points, then 1e-6 Hz steps around its best).
void ExpectMatchesDenseScan(double from, double to) {
  SCOPED_TRACE("band [" + FormatValue(from) + ", " + FormatValue(to) + "]");
  testing::ScratchDir dir;
  const std::string path = dir.Write(
      "band.yaml", Method1With("  residual_ratio: {max: 1.0, band: {key: \"" + kKey + "\", from: " +
                               FormatValue(from) + ", to: " + FormatValue(to) + "}}\n"));
  const Scenario scenario = LoadScenario(path, {});
  ASSERT_EQ(scenario.checks.size(), 1u);
  const Check& check = scenario.checks[0];
  const CheckResult result = EvaluateBandCheck(scenario, {}, check);

  BandPointRunner runner(scenario, {}, check);
  EXPECT_TRUE(runner.fast());
  double best_x = from;
  double best = -1.0;
  for (int k = 0; k <= 6000; ++k) {
    const double x = from + (to - from) * k / 6000.0;
    const double value = runner(x);
    if (value > best) best = value, best_x = x;
  }
  const double coarse_x = best_x;
  for (int k = -2000; k <= 2000; ++k) {
    const double x = coarse_x + 1e-6 * k;
    if (x < from || x > to) continue;
    const double value = runner(x);
    if (value > best) best = value, best_x = x;
  }
  EXPECT_NEAR(result.worst_at, best_x, 1e-3) << BandText(result);
  EXPECT_NEAR(result.value, best, 1e-4) << BandText(result);
  EXPECT_TRUE(result.passed) << BandText(result);
  EXPECT_EQ(result.band_key, kKey);
  EXPECT_GT(result.band_runs, 64);
  EXPECT_LT(result.band_runs, 64 + 3 * 30);

  // The same point reloaded from its sources (no shared command): the same metric.
  const Scenario reloaded = LoadScenario(path, {{kKey, BandValueText(result.worst_at)}});
  EXPECT_DOUBLE_EQ(RunScenario(reloaded, RunOptions{false}).metrics.residual_ratio, result.value);
}

// Tests that the band search's worst residual_ratio of method 1 (the patent's pattern,
// designed for 25 Hz) over 22-28 Hz and over 24-26 Hz lies within 1e-3 Hz of a dense
// scan's and its value within 1e-4, through the same run function (whatever
// residual_ratio's definition), and that the structure-number path gives the metric a
// reload gives.
TEST(BandCheck, WorstMatchesDenseScan) {
  ExpectMatchesDenseScan(22.0, 28.0);
  ExpectMatchesDenseScan(24.0, 26.0);
  ExpectMatchesDenseScan(22.5, 27.0);
}

// Tests that a min bound searches the minimum, and that with both bounds the value further
// on the wrong side of its bound is reported.
TEST(BandCheck, MinBoundAndBothBounds) {
  testing::ScratchDir dir;
  const std::string band = ", band: {key: \"" + kKey + "\", from: 22, to: 28}}\n";
  const std::string path = dir.Write(
      "band.yaml", Method1With("  residual_ratio: {min: 0.5" + band + "  peak_ratio: {min: 0.9, max: 1.0" + band));
  const Scenario scenario = LoadScenario(path, {});
  BandPointRunner runner(scenario, {}, scenario.checks[0]);
  double least = 1e9;
  double most_peak = -1e9;
  BandPointRunner peak(scenario, {}, scenario.checks[1]);
  for (int k = 0; k <= 600; ++k) {
    least = std::min(least, runner(22.0 + 0.01 * k));
    most_peak = std::max(most_peak, peak(22.0 + 0.01 * k));
  }
  const CheckResult min = EvaluateBandCheck(scenario, {}, scenario.checks[0]);
  EXPECT_LE(min.value, least + 1e-4);
  EXPECT_FALSE(min.passed);
  EXPECT_NE(min.message.find("below min"), std::string::npos);
  // The peak ratio rises above 1 somewhere near 22 or 28 Hz, far from its min bound.
  const CheckResult both = EvaluateBandCheck(scenario, {}, scenario.checks[1]);
  EXPECT_NEAR(both.value, most_peak, 1e-4);
  EXPECT_EQ(both.passed, most_peak <= 1.0);
}

// Tests that `check` prints the worst value and where, and that --json and --junit carry
// them (the JUnit testcase named by the band, its failure message the worst value).
TEST(BandCheck, CliLineJsonAndJunit) {
  testing::ScratchDir dir;
  const std::string path = dir.Write(
      "band.yaml", Method1With("  residual_ratio: {max: 1.0e-9, band: {key: \"" + kKey + "\", from: 24, to: 26}}\n"));
  const testing::CliResult line = testing::RunCli({"check", path}, kSourceDir);
  EXPECT_EQ(line.exit_code, 1) << line.err;
  EXPECT_NE(line.out.find("FAIL " + path + " worst residual_ratio "), std::string::npos) << line.out;
  EXPECT_NE(line.out.find(" at " + kKey + " = "), std::string::npos) << line.out;
  EXPECT_NE(line.out.find(" in [24, 26] (max 1e-09): above max 1e-09"), std::string::npos) << line.out;

  const std::string junit = dir.File("report.xml");
  const testing::CliResult json = testing::RunCli({"check", path, "--json", "--junit", junit}, kSourceDir);
  EXPECT_EQ(json.exit_code, 1) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  const nlohmann::json& band = parsed["files"][0]["results"][0]["band"];
  EXPECT_EQ(band["key"], kKey);
  const double worst_at = band["worst_at"].get<double>();
  const double worst = band["worst_value"].get<double>();
  EXPECT_GE(worst_at, 24.0);
  EXPECT_LE(worst_at, 26.0);
  EXPECT_GT(worst, 1e-9);
  EXPECT_EQ(parsed["files"][0]["results"][0]["passed"], false);

  const std::string xml = testing::ReadText(junit);
  EXPECT_NE(xml.find("name=\"residual_ratio over " + kKey + " in [24, 26]\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<property name=\"worst_at\" value=\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<property name=\"worst_value\" value=\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure type=\"CheckFailed\" message=\"worst residual_ratio "), std::string::npos) << xml;
  EXPECT_NE(xml.find(FormatValue(worst_at, 7)), std::string::npos) << xml;
}

// A short scenario whose band is written in block style: its key on line 11, column 12;
// from on line 12, column 13; to on line 13, column 11.
std::string BandScenario(const std::string& key, const std::string& from, const std::string& to) {
  return "machine:\n"
         "  modes: [{frequency_hz: 25.0}]\n"
         "drive: {type: kinematic}\n"
         "controller: {period_s: 0.001, feed_mm_min: 30000, accel_time_s: 0.3,\n"
         "             pattern: {method: 1, mode: both, frequency_hz: 25.0}}\n"
         "move: {distance_mm: 213}\n"
         "checks:\n"
         "  residual_ratio:\n"
         "    max: 0.05\n"
         "    band:\n"
         "      key: " + key + "\n"
         "      from: " + from + "\n"
         "      to: " + to + "\n";
}

// The error that loading the scenario and validating its bands gives.
ConfigError BandError(const std::string& path) {
  return testing::ErrorOf([&] { ValidateBandChecks(LoadScenario(path, {}), {}); });
}

// Tests that a band check on a ratio of a model whose static deflections cancel at every
// point of the band (the damping does not change them) fails at a point of the band naming
// why the ratio is n/a there: the static displacement is 0.
TEST(BandCheck, RatioOfAZeroStaticFailsNamingTheReason) {
  testing::ScratchDir dir;
  const std::string shipped = testing::ReadText(kSourceDir + "/tests/bench/data/reliability/cancelling_modes.yaml");
  const std::string key = "machine.modes[0].damping_ratio";
  const std::string path = dir.Write("band.yaml", shipped.substr(0, shipped.find("\nchecks:")) +
                                                      "\nchecks:\n  peak_ratio: {max: 2.0, band: {key: \"" + key +
                                                      "\", from: 0.01, to: 0.05}}\n");
  const Scenario scenario = LoadScenario(path, {});
  ASSERT_EQ(scenario.checks.size(), 1u);
  const CheckResult result = EvaluateBandCheck(scenario, {}, scenario.checks[0]);
  EXPECT_FALSE(result.passed);
  EXPECT_TRUE(std::isnan(result.value));
  EXPECT_GE(result.worst_at, 0.01);
  EXPECT_LE(result.worst_at, 0.05);
  const std::string expected = "peak_ratio is n/a at " + key + " = " + FormatValue(result.worst_at, 7) +
                               " because the static displacement is 0 (the model's static deflections cancel";
  EXPECT_EQ(result.message.rfind(expected, 0), 0u) << result.message;
}

// Tests that band keys' errors are located at FILE:LINE:COL of the band: an unknown key, a
// key that is not a number, an index out of range and a value the scenario refuses at the
// key; from >= to at `to`.
TEST(BandCheck, ConfigErrorsAreLocated) {
  testing::ScratchDir dir;
  const std::string key_path = "checks.residual_ratio.band.key";
  const std::string unknown = dir.Write("unknown.yaml", BandScenario("machine.modes[0].frequency", "22", "28"));
  testing::ExpectError(BandError(unknown), unknown, 11, 12, key_path, "unknown key 'frequency'");
  const std::string text = dir.Write("text.yaml", BandScenario("controller.pattern.mode", "22", "28"));
  testing::ExpectError(BandError(text), text, 11, 12, key_path, "is not a number");
  const std::string index = dir.Write("index.yaml", BandScenario("machine.modes[3].frequency_hz", "22", "28"));
  testing::ExpectError(BandError(index), index, 11, 12, key_path, "band point machine.modes[3].frequency_hz = 22");
  const std::string refused = dir.Write("refused.yaml", BandScenario(kKey, "-5", "28"));
  testing::ExpectError(BandError(refused), refused, 11, 12, key_path, "= -5: ");
  const std::string reversed = dir.Write("reversed.yaml", BandScenario(kKey, "28", "22"));
  testing::ExpectError(BandError(reversed), reversed, 13, 11, "checks.residual_ratio.band.to",
                       "must be above from");
  const std::string good = dir.Write("good.yaml", BandScenario(kKey, "22", "28"));
  EXPECT_NO_THROW(ValidateBandChecks(LoadScenario(good, {}), {}));
  // The CLI exits 2 with the located error before running anything.
  const testing::CliResult cli = testing::RunCli({"check", unknown}, kSourceDir);
  EXPECT_EQ(cli.exit_code, 2);
  EXPECT_NE(cli.err.find(unknown + ":11:12: " + key_path), std::string::npos) << cli.err;
}

// Tests that a sweep's check refuses a band, located at its `band` key (its grid spans keys).
TEST(BandCheck, SweepChecksTakeNoBand) {
  testing::ScratchDir dir;
  dir.Write("s.yaml", BandScenario(kKey, "22", "28"));
  const std::string sweep = dir.Write(
      "sweep.yaml",
      "base: s.yaml\n"
      "grid:\n"
      "  controller.feed_mm_min: [20000, 30000]\n"
      "checks:\n"
      "  residual_ratio: {max: 0.05, band: {key: \"" + kKey + "\", from: 22, to: 28}}\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadSweep(sweep, {}); }), sweep, 5, 31,
                       "checks.residual_ratio.band", "unknown key 'band'; allowed: min, max");
}

}  // namespace
}  // namespace shapebench::bench
