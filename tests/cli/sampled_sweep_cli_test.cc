// Sampled sweeps through the built CLI (docs/sweeps.md, "Sampled grids", "Yield and
// quantiles"): the same points for any --jobs and shards, a changed seed refused by resume
// and merge, the quantile and yield gates at their boundaries, the shipped yield study's
// numbers recomputed from its results.csv, and the empirical-CDF plot.
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"
#include "bench/sweep/sampling.h"
#include "common/sample_math.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::ReadCsv;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;
using testing::SpawnCli;

const std::string kYieldStudy = "configs/sweeps/moving_column_yield.yaml";

// A sampled sweep of the SDOF test scenario: method 1 and zvd crossed with `samples`
// normal frequencies (seed `seed`), and `checks` (YAML lines).
std::string SampledSweep(const ScratchDir& dir, const std::string& name, int samples, int seed,
                         const std::string& checks = "") {
  return dir.Write(name, "base: " + DataPath("sweeps/sdof_method1.yaml") +
                             "\ngrid:\n  controller.pattern.method: [\"1\", zvd]\n"
                             "  machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}, "
                             "truncated: {min: 23.75, max: 26.25}}\n"
                             "samples: " + std::to_string(samples) + "\nseed: " + std::to_string(seed) +
                             "\ndesign: latin_hypercube\nmetrics: [residual_ratio, peak_ratio]\n" + checks);
}

// Tests that seed 42 gives byte-identical results.csv for --jobs 1 and 2, and for 2 and 3
// shards merged: every process computes the same points.
TEST(SampledSweepCli, SamePointsForJobsAndShards) {
  const ScratchDir dir;
  const std::string sweep = SampledSweep(dir, "s.yaml", 60, 42);
  const auto run = [&](std::vector<std::string> args) {
    const CliResult r = RunCli(args, kSourceDir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
  };
  run({"sweep", sweep, "--jobs", "1", "--out", dir.File("one")});
  run({"sweep", sweep, "--jobs", "2", "--out", dir.File("two")});
  const std::string reference = ReadText(dir.File("one/results.csv"));
  ASSERT_EQ(std::count(reference.begin(), reference.end(), '\n'), 121);
  EXPECT_EQ(ReadText(dir.File("two/results.csv")), reference);
  for (const int shards : {2, 3}) {
    std::vector<std::string> merge = {"merge"};
    for (int i = 0; i < shards; ++i) {
      const std::string out = dir.File("shard" + std::to_string(shards) + "-" + std::to_string(i));
      run({"sweep", sweep, "--shard", std::to_string(i) + "/" + std::to_string(shards), "--out", out, "--jobs", "1"});
      merge.push_back(out);
    }
    const std::string merged = dir.File("merged" + std::to_string(shards));
    merge.insert(merge.end(), {"--out", merged});
    run(merge);
    EXPECT_EQ(ReadText(merged + "/results.csv"), reference) << shards << " shards";
  }
}

// Tests that a sampled sweep cut off after some of its rows (results.csv.partial with a
// torn last row) resumes to the bytes of an uninterrupted run.
TEST(SampledSweepCli, ResumeGivesTheSameBytes) {
  const ScratchDir dir;
  const std::string sweep = SampledSweep(dir, "s.yaml", 50, 42);
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", dir.File("whole")}, kSourceDir).exit_code, 0);
  const std::string whole = ReadText(dir.File("whole/results.csv"));
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", dir.File("cut")}, kSourceDir).exit_code, 0);
  std::filesystem::remove(dir.File("cut/results.csv"));
  std::size_t at = 0;
  for (int line = 0; line < 40; ++line) at = whole.find('\n', at) + 1;
  std::ofstream(dir.File("cut/results.csv.partial"), std::ios::binary) << whole.substr(0, at + 7);  // torn row
  const CliResult resumed = RunCli({"sweep", sweep, "--out", dir.File("cut"), "--jobs", "2"}, kSourceDir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("(39 done before)"), std::string::npos) << resumed.out;  // header + 39 rows kept
  EXPECT_EQ(ReadText(dir.File("cut/results.csv")), whole);
}

// Tests that a sweep started again in its directory with another seed is refused (exit
// 2), and merge refuses shards run with different seeds; the manifest names the sampling.
TEST(SampledSweepCli, AnotherSeedIsAnotherSweep) {
  const ScratchDir dir;
  const std::string a = SampledSweep(dir, "a.yaml", 20, 42);
  const std::string b = SampledSweep(dir, "b/a.yaml", 20, 43);
  ASSERT_EQ(RunCli({"sweep", a, "--out", dir.File("out")}, kSourceDir).exit_code, 0);
  const nlohmann::json manifest = nlohmann::json::parse(ReadText(dir.File("out/manifest.json")));
  EXPECT_EQ(manifest.at("sampling").at("seed"), 42);
  EXPECT_EQ(manifest.at("sampling").at("design"), "latin_hypercube");
  EXPECT_EQ(manifest.at("sampling").at("samples"), 20);
  const CliResult resumed = RunCli({"sweep", b, "--out", dir.File("out")}, kSourceDir);
  EXPECT_EQ(resumed.exit_code, 2) << resumed.err;
  ASSERT_EQ(RunCli({"sweep", a, "--shard", "0/2", "--out", dir.File("s0")}, kSourceDir).exit_code, 0);
  ASSERT_EQ(RunCli({"sweep", b, "--shard", "1/2", "--out", dir.File("s1")}, kSourceDir).exit_code, 0);
  const CliResult merged = RunCli({"merge", dir.File("s0"), dir.File("s1"), "--out", dir.File("m")}, kSourceDir);
  EXPECT_EQ(merged.exit_code, 2);
  EXPECT_NE(merged.err.find("shards of different sweeps"), std::string::npos) << merged.err;
}

// The residual ratios of results.csv's rows of one method, in point order.
std::vector<double> Residuals(const std::vector<std::vector<std::string>>& rows, const std::string& method) {
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const std::size_t residual = column("residual_ratio");
  const std::size_t status = column("status");
  std::vector<double> values;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][1] == method) values.push_back(rows[r][status] == "ok" ? std::stod(rows[r][residual]) : NAN);
  }
  return values;
}

// `value` printed with a printf format of one double.
std::string PrintedNumber(const char* format, double value) {
  char text[40];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string Text17(double value) { return PrintedNumber("%.17g", value); }

// Tests that a quantile gate passes with max at the sample quantile (the rank ceil(q N)
// sample of results.csv, sorted here) and fails just below it, and a yield gate passes
// with min the passing fraction counted here and fails one sample above it; the reported
// order-statistic interval is the samples at the ranks QuantileInterval gives.
TEST(SampledSweepCli, GatesPassAndFailAtTheBoundary) {
  const ScratchDir dir;
  constexpr int n = 40;
  const std::string sweep = SampledSweep(dir, "s.yaml", n, 42);
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", dir.File("out")}, kSourceDir).exit_code, 0);
  const auto rows = ReadCsv(dir.File("out/results.csv"));
  std::vector<double> method1 = Residuals(rows, "1");
  ASSERT_EQ(method1.size(), static_cast<std::size_t>(n));
  std::vector<double> sorted = method1;
  std::sort(sorted.begin(), sorted.end());
  const double q90 = sorted[static_cast<std::size_t>(std::ceil(0.9 * n)) - 1];
  const std::vector<double> zvd = Residuals(rows, "zvd");
  const double zvd_max = *std::max_element(zvd.begin(), zvd.end());
  const auto check = [&](const std::string& name, const std::string& checks) {
    return RunCli({"check", SampledSweep(dir, name, n, 42, "checks:\n" + checks), "--json"}, kSourceDir);
  };
  // Both groups' 0.9-quantiles must be under max: zvd's is far under method 1's.
  ASSERT_LT(zvd_max, q90);
  const CliResult at = check("q_at.yaml", "  residual_ratio: {quantile: 0.9, max: " + Text17(q90) + "}\n");
  EXPECT_EQ(at.exit_code, 0) << at.out << at.err;
  const CliResult below = check(
      "q_below.yaml", "  residual_ratio: {quantile: 0.9, max: " + Text17(std::nextafter(q90, 0.0)) + "}\n");
  EXPECT_EQ(below.exit_code, 1) << below.out;
  // JUnit: one testcase per gate and method, named by the statistic; method 1's fails.
  const CliResult junit = RunCli({"check", dir.File("q_below.yaml"), "--junit", dir.File("j.xml")}, kSourceDir);
  EXPECT_EQ(junit.exit_code, 1);
  const std::string xml = ReadText(dir.File("j.xml"));
  EXPECT_NE(xml.find("name=\"quantile 0.9 of residual_ratio @ controller.pattern.method=1\""), std::string::npos) << xml;
  std::size_t testcases = 0;
  for (std::size_t at = xml.find("<testcase"); at != std::string::npos; at = xml.find("<testcase", at + 1)) ++testcases;
  EXPECT_EQ(testcases, 2u) << xml;
  EXPECT_NE(xml.find("<failure"), std::string::npos) << xml;
  const nlohmann::json json = nlohmann::json::parse(at.out);
  const nlohmann::json& result = json.at("files").at(0).at("results").at(0);
  EXPECT_EQ(result.at("point"), "controller.pattern.method=1");
  EXPECT_EQ(result.at("value").get<double>(), q90);
  const QuantileRanks ranks = QuantileInterval(n, 0.9);
  EXPECT_EQ(result.at("statistic").at("interval_95").at(0).get<double>(), sorted[ranks.lower - 1]);
  if (ranks.upper <= static_cast<std::uint64_t>(n)) {
    EXPECT_EQ(result.at("statistic").at("interval_95").at(1).get<double>(), sorted[ranks.upper - 1]);
  } else {
    EXPECT_TRUE(result.at("statistic").at("interval_95").at(1).is_null());
  }

  int passing = 0;
  for (const double r : method1) passing += r <= 0.05;
  ASSERT_LT(passing, n);
  const std::string per_point = "  residual_ratio: {max: 0.05}\n";
  const CliResult yield_at =
      check("y_at.yaml", per_point + "  yield: {min: " + Text17(static_cast<double>(passing) / n) + "}\n");
  EXPECT_EQ(yield_at.exit_code, 0) << yield_at.out << yield_at.err;
  const CliResult yield_above =
      check("y_above.yaml", per_point + "  yield: {min: " + Text17(static_cast<double>(passing + 1) / n) + "}\n");
  EXPECT_EQ(yield_above.exit_code, 1) << yield_above.out;
}

// The 95% Wilson interval, computed here from its formula.
std::pair<double, double> Wilson(int k, int n) {
  const double z = 1.959963984540054;
  const double p = static_cast<double>(k) / n;
  const double centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
  const double half = z / (1.0 + z * z / n) * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

std::string Fixed3(double value) { return PrintedNumber("%.3f", value); }

// Tests the shipped yield study: each method's yield that `check --json` reports is the
// fraction of its rows in results.csv with residual_ratio <= 0.05, counted here, with the
// Wilson interval computed here; method 1 fails the 0.95 gate, zvd passes; and the table
// in docs/sweeps.md shows these numbers (3 decimals).
TEST(SampledSweepCli, ShippedYieldStudyMatchesAnIndependentCount) {
  const ScratchDir dir;
  const CliResult swept = RunCli({"sweep", kYieldStudy, "--out", dir.File("out")}, kSourceDir);
  ASSERT_EQ(swept.exit_code, 0) << swept.err;
  const auto rows = ReadCsv(dir.File("out/results.csv"));
  const CliResult checked = RunCli({"check", kYieldStudy, "--json"}, kSourceDir);
  EXPECT_EQ(checked.exit_code, 1) << checked.err;
  const nlohmann::json results = nlohmann::json::parse(checked.out).at("files").at(0).at("results");
  ASSERT_EQ(results.size(), 2u);
  const std::string docs = ReadText(std::string(kSourceDir) + "/docs/sweeps.md");
  for (const auto& [index, method] : std::vector<std::pair<int, std::string>>{{0, "1"}, {1, "zvd"}}) {
    const std::vector<double> residuals = Residuals(rows, method);
    const int n = static_cast<int>(residuals.size());
    ASSERT_EQ(n, 500);
    int passing = 0;
    for (const double r : residuals) passing += r <= 0.05;
    const auto [low, high] = Wilson(passing, n);
    const nlohmann::json& result = results.at(index);
    EXPECT_EQ(result.at("point"), "controller.pattern.method=" + method);
    EXPECT_EQ(result.at("statistic").at("passing"), passing);
    EXPECT_DOUBLE_EQ(result.at("value").get<double>(), static_cast<double>(passing) / n);
    EXPECT_NEAR(result.at("statistic").at("interval_95").at(0).get<double>(), low, 1e-12);
    EXPECT_NEAR(result.at("statistic").at("interval_95").at(1).get<double>(), high, 1e-12);
    EXPECT_EQ(result.at("passed").get<bool>(), static_cast<double>(passing) / n >= 0.95) << method;
    const std::string row = "| " + method + " | " + Fixed3(static_cast<double>(passing) / n) + " (" +
                            std::to_string(passing) + " of " + std::to_string(n) + ") | " + Fixed3(low) +
                            " to " + Fixed3(high) + " |";
    EXPECT_NE(docs.find(row), std::string::npos) << "docs/sweeps.md lacks the row " << row;
  }
  EXPECT_FALSE(results.at(0).at("passed").get<bool>());
  EXPECT_TRUE(results.at(1).at("passed").get<bool>());
}

std::size_t LineCount(const std::string& path) {
  const std::string text = ReadText(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Runs `args` until `partial` holds more than `lines` lines (at most 10 minutes), then
// sends SIGTERM; the exit status and stderr.
std::pair<int, std::string> RunUntilRows(const std::vector<std::string>& args, const std::string& partial,
                                         std::size_t lines, const ScratchDir& dir) {
  const pid_t pid = SpawnCli(args, kSourceDir, dir.File("err.txt"));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (std::chrono::steady_clock::now() < deadline && LineCount(partial) <= lines) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ReadText(dir.File("err.txt"))};
}

// Tests that a sampled sweep of 20,000,000 Latin-hypercube samples writes its first rows
// without listing its samples: SIGTERM after a few rows keeps them with a manifest under
// 64 KiB that says how to resume, the same command resumes from those rows (more rows, the
// first ones unchanged, the manifest accepted), and the rows' values are the samples an
// eager draw of the whole list gives (SampleDraw, the same for every index).
TEST(SampledSweepCli, TwentyMillionSamplesStartAtOnceAndResume) {
  const ScratchDir dir;
  const std::string sweep = dir.Write(
      "big.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                      "\ngrid:\n  machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}}\n"
                      "samples: 20000000\nseed: 7\ndesign: latin_hypercube\nmetrics: [residual_ratio]\n");
  const std::string out = dir.File("out");
  const std::string partial = out + "/results.csv.partial";
  const std::vector<std::string> args = {"sweep", sweep, "--force", "--jobs", "1", "--out", out};
  const auto [code, err] = RunUntilRows(args, partial, 3, dir);
  EXPECT_EQ(code, 128 + SIGTERM) << err;
  EXPECT_NE(err.find("of 20000000 points done, kept in " + partial + "; run the same command again to resume"),
            std::string::npos)
      << err;
  ASSERT_TRUE(std::filesystem::exists(out + "/manifest.json"));
  EXPECT_LT(std::filesystem::file_size(out + "/manifest.json"), 64u << 10);
  const std::string first = ReadText(partial);
  const std::size_t kept = LineCount(partial) - 1;
  ASSERT_GE(kept, 3u);

  const auto [again, again_err] = RunUntilRows(args, partial, kept + 3, dir);
  EXPECT_EQ(again, 128 + SIGTERM) << again_err;
  EXPECT_EQ(again_err.find("manifest"), std::string::npos) << again_err;
  EXPECT_NE(again_err.find("run the same command again to resume"), std::string::npos) << again_err;
  const std::string resumed = ReadText(partial);
  EXPECT_GT(LineCount(partial), kept + 3);
  EXPECT_EQ(resumed.compare(0, first.size(), first), 0) << "the kept rows stay as they were";

  const Distribution normal{Distribution::Kind::kNormal, 25.0, 0.625, std::nullopt, std::nullopt};
  const SweepSampling sampling{20000000, 7, SampleDesign::kLatinHypercube};
  const SampleDraw draw(sampling, 0, normal);
  const auto rows = ReadCsv(partial);
  for (std::size_t r = 1; r < std::min<std::size_t>(rows.size(), 50); ++r) {
    EXPECT_EQ(rows[r][1], PrintedNumber("%.15g", draw.Value(r - 1))) << "row " << r;
  }
}

// Tests that an output directory whose manifest lists every sample, with the hash that
// listed them (as shapebench wrote it before the samples were computed per point), is
// refused by resume saying so, not as another sweep's.
TEST(SampledSweepCli, ResumeOfAManifestListingTheSamplesSaysWhy) {
  const ScratchDir dir;
  const std::string sweep = SampledSweep(dir, "s.yaml", 20, 42);
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", dir.File("out")}, kSourceDir).exit_code, 0);
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(ReadText(dir.File("out/manifest.json")));
  const auto rows = ReadCsv(dir.File("out/results.csv"));
  std::vector<std::string> listed;
  for (std::size_t r = 1; r <= 20; ++r) listed.push_back(rows[r][2]);
  manifest["grid"][1][0]["list"] = listed;
  manifest["hash"] = "0123456789abcdef";
  std::ofstream(dir.File("out/manifest.json"), std::ios::binary | std::ios::trunc) << manifest.dump(2) << "\n";
  const CliResult resumed = RunCli({"sweep", sweep, "--out", dir.File("out")}, kSourceDir);
  EXPECT_EQ(resumed.exit_code, 2);
  EXPECT_NE(resumed.err.find("written by an earlier shapebench that listed every sample in its manifest; this "
                             "version cannot resume it"),
            std::string::npos)
      << resumed.err;
}

// Tests that a sampled sweep draws the empirical CDF of its checked metric, one curve per
// method, with the limit (a PNG next to results.csv), and that merge draws it too.
TEST(SampledSweepCli, DrawsTheEmpiricalCdf) {
  const ScratchDir dir;
  const std::string sweep = SampledSweep(dir, "s.yaml", 30, 42, "checks:\n  residual_ratio: {quantile: 0.9, max: 0.1}\n");
  const CliResult r = RunCli({"sweep", sweep, "--out", dir.File("out")}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string png = dir.File("out/residual_ratio-cdf-by-method.png");
  ASSERT_TRUE(std::filesystem::exists(png)) << r.out;
  EXPECT_EQ(ReadText(png).substr(1, 3), "PNG");
  const nlohmann::json manifest = nlohmann::json::parse(ReadText(dir.File("out/manifest.json")));
  const nlohmann::json& plot = manifest.at("layout").at("plots").at(0);
  EXPECT_TRUE(plot.at("cdf").get<bool>());
  EXPECT_EQ(plot.at("limits"), nlohmann::json::array({0.1}));
  for (const int i : {0, 1}) {
    ASSERT_EQ(RunCli({"sweep", sweep, "--shard", std::to_string(i) + "/2", "--out", dir.File("s" + std::to_string(i))},
                     kSourceDir).exit_code, 0);
  }
  ASSERT_EQ(RunCli({"merge", dir.File("s0"), dir.File("s1"), "--out", dir.File("m")}, kSourceDir).exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir.File("m/residual_ratio-cdf-by-method.png")));
}

// Tests that a quantile landing on samples without a value (radial_error_m: no arc, n/a for
// every point) prints and reports n/a, never "= inf m" (issue 32 item 16), and fails
// saying why; its interval ends are n/a (null in JSON) too.
TEST(SampledSweepCli, QuantileOfSamplesWithoutAValueIsNotAvailable) {
  const ScratchDir dir;
  const std::string sweep = SampledSweep(dir, "na.yaml", 8, 42, "checks:\n  radial_error_m: {quantile: 0.5, max: 1}\n");
  const CliResult text = RunCli({"check", sweep}, kSourceDir);
  EXPECT_EQ(text.exit_code, 1) << text.out << text.err;
  EXPECT_EQ(text.out.find("= inf"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("quantile 0.5 of radial_error_m @ controller.pattern.method=1 = n/a ("), std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find(": n/a: the quantile falls on one of the 8 of 8 samples without a value"), std::string::npos)
      << text.out;
  const CliResult json = RunCli({"check", sweep, "--json"}, kSourceDir);
  const nlohmann::json result = nlohmann::json::parse(json.out).at("files").at(0).at("results").at(0);
  EXPECT_TRUE(result.at("value").is_null()) << result.dump();
  EXPECT_FALSE(result.at("passed").get<bool>()) << result.dump();
}

}  // namespace
}  // namespace shapebench::bench
