// `shapebench sweep`, `merge` and `check` on sweep files through the built CLI (docs/sweeps.md,
// must-show 2 and 4): results.csv independent of --jobs, of sharding and of a kill and
// restart; failing points recorded; plots; JUnit naming the point.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::ReadCsv;
using testing::ReadText;
using testing::Args;
using testing::RunCli;
using testing::ScratchDir;
using testing::SpawnCli;

const std::string kNaturalPeriod = "tests/bench/data/sweeps/natural_period.yaml";
// Method 4 with t1 = 4.77 ms: valid up to 34.9 Hz; at 35 Hz T/6 = 4.762 ms < t1.
const std::vector<std::string> kMethod4 = {"--set", "controller.pattern.method=4", "--set",
                                           "controller.pattern.t1_s=0.00477"};

std::size_t Lines(const std::string& path) {
  const std::string text = ReadText(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Runs the natural-period sweep into `out`; the reference every other way must match.
std::string Reference(const ScratchDir& dir, const std::vector<std::string>& sets, const std::string& name) {
  const std::string out = dir.File(name);
  const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--jobs", "1", "--out", out}, sets), kSourceDir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out + "/results.csv";
}

// Tests that the 201-point natural-period sweep of the default SDOF scenario writes the
// same results.csv byte for byte with --jobs 1 and --jobs 2, as the default scenario and
// with method 4 at t1 = 4.77 ms, where the 35 Hz point (t1 > T/6) has status error with
// its located message and the 200 others complete; stderr stays quiet (not a terminal).
TEST(SweepCli, JobsDoNotChangeResults) {
  ScratchDir dir;
  for (const auto& sets : {std::vector<std::string>{}, kMethod4}) {
    const std::string one = Reference(dir, sets, sets.empty() ? "default1" : "method4_1");
    const std::string out2 = dir.File(sets.empty() ? "default2" : "method4_2");
    const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--jobs", "2", "--out", out2}, sets), kSourceDir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_EQ(ReadText(out2 + "/results.csv"), ReadText(one));
    EXPECT_FALSE(std::filesystem::exists(out2 + "/results.csv.partial"));

    const auto rows = ReadCsv(one);
    ASSERT_EQ(rows.size(), 202u);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"point", "machine.modes[0].frequency_hz",
                                                  "controller.pattern.frequency_hz", "peak_ratio",
                                                  "residual_ratio", "motion_time_s", "status", "error"}));
    EXPECT_EQ(rows[1][1], "15");
    EXPECT_EQ(rows[2][1], "15.1");
    EXPECT_EQ(rows[201][1], "35");
    for (std::size_t i = 1; i <= 200; ++i) {
      EXPECT_EQ(rows[i][0], std::to_string(i - 1));
      EXPECT_EQ(rows[i][6], "ok") << rows[i][7];
      EXPECT_LT(std::stod(rows[i][4]), 1e-6) << "the pattern tracks the mode: no residual";
    }
    if (sets.empty()) {
      EXPECT_EQ(rows[201][6], "ok");
      EXPECT_NE(r.out.find("201 points, 201 ok, 0 error"), std::string::npos) << r.out;
    } else {
      EXPECT_EQ(rows[201][6], "error");
      EXPECT_EQ(rows[201][3], "");
      EXPECT_EQ(rows[201][7].rfind("--set:2:1: controller.pattern.t1_s: must be in [0, T/6]", 0), 0u)
          << rows[201][7];
      EXPECT_NE(r.out.find("201 points, 200 ok, 1 error"), std::string::npos) << r.out;
    }
  }
}

// Tests that two shards (--shard 0/2 and 1/2, run with different --jobs) merged give the
// unsharded results.csv byte for byte and its manifest; that merge refuses a missing
// shard and a shard of another sweep (different --set), exit 2.
TEST(SweepCli, ShardsMergeToTheUnshardedFile) {
  ScratchDir dir;
  const std::string reference = Reference(dir, kMethod4, "whole");
  for (const std::string shard : {"0", "1"}) {
    const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--shard", shard + "/2", "--jobs", shard == "0" ? "1" : "2",
                                     "--out", dir.File("shard" + shard)},
                                    kMethod4),
                               kSourceDir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = ReadCsv(dir.File("shard" + shard + "/results.csv"));
    ASSERT_EQ(rows.size(), shard == "0" ? 102u : 101u);
    EXPECT_EQ(rows[2][0], shard == "0" ? "2" : "3");  // every other point, with its index
  }
  const CliResult merged =
      RunCli({"merge", dir.File("merged"), dir.File("shard1"), dir.File("shard0")}, kSourceDir);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(ReadText(dir.File("merged/results.csv")), ReadText(reference));
  EXPECT_EQ(ReadText(dir.File("merged/manifest.json")), ReadText(dir.File("whole/manifest.json")));
  EXPECT_EQ(ReadText(dir.File("merged/residual_ratio-vs-modes_0_.frequency_hz.png")).substr(1, 3), "PNG");

  const CliResult missing = RunCli({"merge", "--out", dir.File("m2"), dir.File("shard0")}, kSourceDir);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("shard 1/2 is missing"), std::string::npos) << missing.err;

  ASSERT_EQ(RunCli({"sweep", kNaturalPeriod, "--shard", "1/2", "--out", dir.File("other1")}, kSourceDir).exit_code, 0);
  const CliResult other = RunCli({"merge", dir.File("m3"), dir.File("shard0"), dir.File("other1")}, kSourceDir);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("shards of different sweeps"), std::string::npos) << other.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("m3/results.csv")));
}

// Tests that shards of one sweep file named three ways (as the unsharded run names it,
// through "./sweeps/../", by its absolute path) merge to the unsharded results.csv and
// manifest byte for byte, error rows located in the sweep file and in the base included:
// the sweep's files name it by its path from the working directory, not as spelled.
TEST(SweepCli, ShardsOfDifferentlySpelledPathsMergeToTheUnshardedFile) {
  ScratchDir dir;
  // Method 4 with t1 = 5 ms is valid for a 25 Hz pattern, not for 40 Hz (T/6 = 4.17 ms): an
  // error located in the base; a -3 Hz mode is one located in the sweep file.
  dir.Write("scenarios/base.yaml",
            "machine:\n  modes:\n    - {frequency_hz: 25.0, damping_ratio: 0.0, gain: 1.0}\n"
            "controller:\n  period_s: 0.001\n  feed_mm_min: 30000\n  accel_time_s: 0.3\n"
            "  pattern: {method: 4, mode: both, frequency_hz: 25.0, k1: 0.675, t1_s: 0.005}\n"
            "move: {distance_mm: 213}\nintegrator: {method: exact}\n");
  dir.Write("sweeps/spelled.yaml",
            "base: ../scenarios/base.yaml\ngrid:\n  controller.pattern.frequency_hz: [25, 40]\n"
            "  machine.modes[0].frequency_hz: [25, -3, 26]\nmetrics: [residual_ratio]\nplots: []\n");
  const std::string work = dir.path().string();
  ASSERT_EQ(RunCli({"sweep", "sweeps/spelled.yaml", "--out", "whole"}, work).exit_code, 0);
  const std::string whole = ReadText(dir.File("whole/results.csv"));
  EXPECT_NE(whole.find(",error,sweeps/spelled.yaml:4:39: machine.modes[0].frequency_hz: "), std::string::npos)
      << whole;
  EXPECT_NE(whole.find(",error,\"scenarios/base.yaml:"), std::string::npos) << whole;

  const std::vector<std::string> spellings = {"./sweeps/../sweeps/spelled.yaml", dir.File("sweeps/spelled.yaml")};
  for (std::size_t shard = 0; shard < 2; ++shard) {
    const CliResult r = RunCli({"sweep", spellings[shard], "--shard", std::to_string(shard) + "/2", "--out",
                                "shard" + std::to_string(shard)},
                               work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const auto& order : {std::vector<std::string>{"shard0", "shard1"}, std::vector<std::string>{"shard1", "shard0"}}) {
    const std::string out = "merged_" + order.front();
    const CliResult merged = RunCli({"merge", out, order[0], order[1]}, work);
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    EXPECT_EQ(ReadText(dir.File(out + "/results.csv")), whole);
    EXPECT_EQ(ReadText(dir.File(out + "/manifest.json")), ReadText(dir.File("whole/manifest.json")));
  }
}

// Tests that a sweep killed (SIGKILL) after some rows and started again with the same
// --out (and another --jobs) skips the rows already written and ends with the
// uninterrupted run's results.csv byte for byte, a torn last row included.
TEST(SweepCli, KillAndRestartGivesTheSameFile) {
  ScratchDir dir;
  const std::string reference = Reference(dir, kMethod4, "whole");
  const std::string out = dir.File("killed");
  const std::string partial = out + "/results.csv.partial";
  std::size_t rows_before_kill = 0;
  // The sweep takes ~0.2 s; a loaded machine may let it finish before the kill: retry.
  for (int attempt = 0; attempt < 5 && rows_before_kill == 0; ++attempt) {
    std::filesystem::remove_all(out);
    const pid_t pid = SpawnCli(Args({"sweep", kNaturalPeriod, "--jobs", "1", "--out", out}, kMethod4), kSourceDir);
    ASSERT_GT(pid, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline && Lines(partial) < 11 &&
           !std::filesystem::exists(out + "/results.csv")) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    // Killed with every row written but before the rename: finished too, retry.
    if (WIFSIGNALED(status) && !std::filesystem::exists(out + "/results.csv") && Lines(partial) - 1 < 201u) {
      rows_before_kill = Lines(partial) - 1;
    }
  }
  ASSERT_GT(rows_before_kill, 0u) << "the sweep always finished before it could be killed";
  ASSERT_LT(rows_before_kill, 201u);
  std::ofstream(partial, std::ios::app) << "999,34.9,34.9,1.00";  // a row torn by the kill

  const CliResult restarted = RunCli(Args({"sweep", kNaturalPeriod, "--jobs", "2", "--out", out}, kMethod4), kSourceDir);
  ASSERT_EQ(restarted.exit_code, 0) << restarted.err;
  EXPECT_NE(restarted.out.find("(" + std::to_string(rows_before_kill) + " done before)"), std::string::npos)
      << restarted.out;
  EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference));
  EXPECT_FALSE(std::filesystem::exists(partial));

  // Run again: everything is done, nothing changes.
  const CliResult again = RunCli(Args({"sweep", kNaturalPeriod, "--out", out}, kMethod4), kSourceDir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("(201 done before)"), std::string::npos) << again.out;
  EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference));
}

// Tests that a sweep on one job and on two (whose calling thread writes the manifest when
// its first row is ready, while the other computes) never shows a row without the manifest
// beside it: watched from its start until it ends, each time a row is seen, manifest.json
// is complete (this sweep's hash), and the run ends with the reference bytes.
TEST(SweepCli, NoRowBeforeItsManifestOnOneJobOrTwo) {
  ScratchDir dir;
  const std::string reference = Reference(dir, kMethod4, "whole");
  const std::string manifest = ReadText(dir.File("whole/manifest.json"));
  for (const std::string jobs : {"1", "2"}) {
    const std::string out = dir.File("watched" + jobs);
    const std::string partial = out + "/results.csv.partial";
    const pid_t pid = SpawnCli(Args({"sweep", kNaturalPeriod, "--jobs", jobs, "--out", out}, kMethod4), kSourceDir);
    ASSERT_GT(pid, 0);
    int checked = 0;
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
      if (Lines(partial) > 1) {
        EXPECT_EQ(ReadText(out + "/manifest.json"), manifest) << jobs;
        ++checked;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << jobs;
    EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference)) << jobs;
    EXPECT_EQ(ReadText(out + "/manifest.json"), manifest) << jobs;
    // Rows reach the file every 100 ms; a loaded machine may finish first (nothing seen).
    RecordProperty("rows_seen_" + jobs, checked);
  }
}

// Tests that a partial file cut inside the quoted error field of its last row (the way a
// kill can leave it) is resumed from the last complete row, to the same bytes.
TEST(SweepCli, RowTornInsideAQuotedFieldIsRunAgain) {
  ScratchDir dir;
  const std::string reference = Reference(dir, kMethod4, "whole");
  const std::string text = ReadText(reference);
  ASSERT_EQ(text.substr(text.size() - 2), "\"\n");  // the last row ends in its quoted error
  std::filesystem::create_directories(dir.File("torn"));
  std::filesystem::copy_file(dir.File("whole/manifest.json"), dir.File("torn/manifest.json"));
  std::ofstream(dir.File("torn/results.csv.partial"), std::ios::binary) << text.substr(0, text.size() - 30);
  const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--out", dir.File("torn")}, kMethod4), kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(200 done before)"), std::string::npos) << r.out;
  EXPECT_EQ(ReadText(dir.File("torn/results.csv")), text);
}

// Tests that a resumed sweep takes the rows of results.csv.ahead (points that finished
// behind a slower one before the last run stopped) instead of running their points: the
// directory holds 50 rows in order and, ahead, the rows of points 60-69 and of point 200
// (an error row), then a row torn by a kill; resumed on one job and on two with those 11
// points set to hang (SHAPEBENCH_TEST_HANG_POINT: running one would never end, and
// `timeout` would fail the run), it ends, reports 61 points done before, writes the
// uninterrupted run's results.csv byte for byte and leaves no results.csv.ahead.
TEST(SweepCli, ResumeTakesRowsAheadInsteadOfRunningThem) {
  ScratchDir dir;
  const std::string reference = Reference(dir, kMethod4, "whole");
  for (const std::string jobs : {"1", "2"}) {
    const std::string out = dir.File("ahead" + jobs);
    const std::string hang = testing::WriteSweepDirWithRowsAhead(dir.File("whole"), out, 50,
                                                                 {64, 60, 200, 61, 62, 63, 65, 66, 67, 68, 69});
    const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--jobs", jobs, "--out", out}, kMethod4), kSourceDir,
                               "SHAPEBENCH_TEST_HANG_POINT=" + hang + " timeout -k 10 120 ");
    ASSERT_EQ(r.exit_code, 0) << r.err;  // 124 (137: killed by -k): a point ahead was run again, and hung
    EXPECT_NE(r.out.find(", 200 ok, 1 error (61 done before)"), std::string::npos) << r.out;
    EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference)) << jobs;
    EXPECT_FALSE(std::filesystem::exists(out + "/results.csv.ahead"));
    EXPECT_FALSE(std::filesystem::exists(out + "/results.csv.partial"));
  }
}

// Tests that an output directory holding another sweep's results is refused (exit 2)
// and left as it was, and that a grid over the limit needs --force.
TEST(SweepCli, RefusesAnotherSweepsDirectoryAndHugeGrids) {
  ScratchDir dir;
  const std::string reference = Reference(dir, {}, "whole");
  const std::string before = ReadText(reference);
  const CliResult r = RunCli(Args({"sweep", kNaturalPeriod, "--out", dir.File("whole")}, kMethod4), kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holds the results of another sweep"), std::string::npos) << r.err;
  EXPECT_EQ(ReadText(reference), before);

  const std::string big = dir.Write("big.yaml",
                                    "base: " + testing::DataPath("sweeps/sdof_method1.yaml") +
                                        "\ngrid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 3000}\n"
                                        "  controller.accel_time_s: {from: 0.1, to: 0.4, steps: 1000}\n");
  const CliResult huge = RunCli({"sweep", big, "--out", dir.File("big")}, kSourceDir);
  EXPECT_EQ(huge.exit_code, 2);
  EXPECT_NE(huge.err.find(big + ":3:3: grid: the grid has 3,000,000 points"), std::string::npos) << huge.err;
  EXPECT_NE(huge.err.find("--force"), std::string::npos) << huge.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("big")));

  const CliResult bad_shard = RunCli({"sweep", kNaturalPeriod, "--shard", "2/2"}, kSourceDir);
  EXPECT_EQ(bad_shard.exit_code, 2);
  EXPECT_NE(bad_shard.err.find("--shard: expected I/N"), std::string::npos) << bad_shard.err;
}

// Tests that `check` takes --force as `sweep` does: without it a grid over the limit is
// refused naming --force; with it the grid loads, so the load goes on to the next file
// (here a scenario without checks, so nothing runs and the 3,000,000 points stay unrun).
TEST(SweepCli, CheckTakesForceForHugeGrids) {
  ScratchDir dir;
  const std::string big = dir.Write("big.yaml",
                                    "base: " + testing::DataPath("sweeps/sdof_method1.yaml") +
                                        "\ngrid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 3000}\n"
                                        "  controller.accel_time_s: {from: 0.1, to: 0.4, steps: 1000}\n"
                                        "checks: {residual_ratio: {max: 0.05}}\n");
  const std::string no_checks = testing::DataPath("no_checks.yaml");
  const CliResult refused = RunCli({"check", big, no_checks}, kSourceDir);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find(big + ":3:3: grid: the grid has 3,000,000 points"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("pass --force"), std::string::npos) << refused.err;

  const CliResult forced = RunCli({"check", big, no_checks, "--force"}, kSourceDir);
  EXPECT_EQ(forced.exit_code, 2);
  EXPECT_EQ(forced.err.find("3,000,000"), std::string::npos) << forced.err;
  EXPECT_NE(forced.err.find(no_checks + ": checks: no checks to evaluate"), std::string::npos) << forced.err;

  const CliResult help = RunCli({"check", "--help"}, kSourceDir);
  EXPECT_NE(help.out.find("--force"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("run a grid of more than 2,000,000 points"), std::string::npos) << help.out;
}

// Tests that a value with a comma and an error message with commas and quotes are quoted
// in results.csv (RFC 4180) and read back exactly.
TEST(SweepCli, CsvQuotesValuesAndErrors) {
  ScratchDir dir;
  const CliResult r = RunCli({"sweep", "tests/bench/data/sweeps/quoting.yaml", "--out", dir.File("q")}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = ReadText(dir.File("q/results.csv"));
  const std::string message =
      "tests/bench/data/sweeps/quoting.yaml:5:35: controller.feed_mm_min: expected a number, got "
      "\"6,000\" (a quoted string)";
  EXPECT_NE(text.find("\n1,\"6,000\",,error,\"tests/bench/data/sweeps/quoting.yaml:5:35: "
                      "controller.feed_mm_min: expected a number, got \"\"6,000\"\" (a quoted string)\"\n"),
            std::string::npos)
      << text;
  const auto rows = ReadCsv(dir.File("q/results.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][3], "ok");
  EXPECT_EQ(rows[2], (std::vector<std::string>{"1", "6,000", "", "error", message}));
}

// Tests that the plots are PNG files: metric vs a key with one line per value of another
// key, a heat map over two keys, and a metric vs the other key.
TEST(SweepCli, PlotsArePngs) {
  ScratchDir dir;
  const CliResult r = RunCli({"sweep", "tests/bench/data/sweeps/map.yaml", "--out", dir.File("map")}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no gnuplot warnings either
  for (const std::string name :
       {"residual_ratio-vs-frequency_hz-by-accel_time_s.png",
        "residual_ratio-over-frequency_hz-and-accel_time_s.png",
        "motion_time_s-vs-accel_time_s.png"}) {
    const std::string png = ReadText(dir.File("map/" + name));
    ASSERT_GT(png.size(), 1000u) << name;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << name;
    EXPECT_NE(r.out.find(name), std::string::npos) << r.out;
  }
}

// Tests that `check` on a sweep with a failing point exits 1, prints the point on its
// FAIL line and a summary per check, and names the point in the JUnit XML (one
// testcase per point and check).
TEST(SweepCli, CheckNamesTheFailingPoint) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const std::string file = "tests/bench/data/sweeps/failing_point.yaml";
  const CliResult r = RunCli({"check", file, "--junit", junit}, kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("FAIL " + file + " residual_ratio @ machine.modes[0].frequency_hz=24.5 = "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("FAIL " + file + " residual_ratio: 2 of 3 points pass (max 0.05); worst "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("PASS " + file + " peak_ratio: 3 of 3 points pass (max 1.1)"), std::string::npos) << r.out;
  ASSERT_EQ(std::system(("xmllint --noout " + testing::ShellQuoted(junit)).c_str()), 0);
  const std::string xml = ReadText(junit);
  EXPECT_NE(xml.find("tests=\"6\" failures=\"1\" errors=\"0\""), std::string::npos) << xml;
  // time: the point's run, measured (seconds, 3 decimals).
  EXPECT_TRUE(std::regex_search(
      xml, std::regex("<testcase classname=\"shapebench\\.failing_point\" "
                      "name=\"residual_ratio @ machine\\.modes\\[0\\]\\.frequency_hz=24\\.5\" time=\"[0-9]+\\.[0-9]{3}\">\n"
                      "      <failure type=\"CheckFailed\"")))
      << xml;
  EXPECT_TRUE(std::regex_search(
      xml, std::regex("name=\"residual_ratio @ machine\\.modes\\[0\\]\\.frequency_hz=25\" time=\"[0-9]+\\.[0-9]{3}\"/>")))
      << xml;
}

// Tests that a point that fails to run under `check` (method 4, t1 > T/6 at 35 Hz) is a
// JUnit <error> named after the point and exits 2 (bad input), the others checked.
TEST(SweepCli, CheckReportsAPointThatFailsToRun) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const CliResult r = RunCli(Args({"check", kNaturalPeriod, "--junit", junit, "--jobs", "2"}, kMethod4), kSourceDir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("error: --set:2:1: controller.pattern.t1_s: must be in [0, T/6]"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("residual_ratio: 200 of 201 points pass (max 0.05), 1 failed to run"), std::string::npos)
      << r.out;
  ASSERT_EQ(std::system(("xmllint --noout " + testing::ShellQuoted(junit)).c_str()), 0);
  const std::string xml = ReadText(junit);
  EXPECT_NE(xml.find("tests=\"201\" failures=\"0\" errors=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"run @ machine.modes[0].frequency_hz=35, controller.pattern.frequency_hz=35\""),
            std::string::npos)
      << xml;
}

// Tests that CVODE's cross-check, priced once per family of a natural-period sweep, still
// refuses every point that truly fails: at an explicit integrator.rtol of 3e-7 an undamped
// 15-35 Hz sweep has points that pass and points that fail; results.csv is the same bytes
// as with every point checked alone (SHAPEBENCH_CROSS_CHECK_FAMILY=0), and the 15 Hz
// point's error is the message `run` exits 3 with for that point.
TEST(SweepCli, FamilyCrossCheckStillRefusesAFailingPoint) {
  ScratchDir dir;
  const std::string base = std::string(kSourceDir) + "/benchmarks/cases/case1.yaml";
  const std::string file = dir.File("undamped.yaml");
  std::ofstream(file) << "base: " << base << "\ngrid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 60}\n"
                      << "plots: []\n";
  const std::vector<std::string> sets = {"--set", "integrator.method=cvode", "--set", "integrator.rtol=3e-7"};
  const CliResult family = RunCli(Args({"sweep", file, "--jobs", "2", "--out", dir.File("family")}, sets), kSourceDir);
  const CliResult alone = RunCli(Args({"sweep", file, "--jobs", "2", "--out", dir.File("alone")}, sets), kSourceDir,
                                 "SHAPEBENCH_CROSS_CHECK_FAMILY=0 ");
  EXPECT_EQ(family.exit_code, alone.exit_code) << family.err;
  EXPECT_EQ(ReadText(dir.File("family") + "/results.csv"), ReadText(dir.File("alone") + "/results.csv"));
  const std::vector<std::vector<std::string>> rows = ReadCsv(dir.File("family") + "/results.csv");
  ASSERT_EQ(rows.size(), 61u);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const std::size_t status = column("status");
  const std::size_t error = column("error");
  ASSERT_LT(error, rows[0].size());
  const auto ok = std::count_if(rows.begin() + 1, rows.end(), [&](const auto& r) { return r[status] == "ok"; });
  EXPECT_GT(ok, 0);
  EXPECT_LT(ok, 60);
  EXPECT_EQ(rows[1][status], "error");
  const CliResult run = RunCli(Args({"run", base, "--set", "machine.modes[0].frequency_hz=15"}, sets), kSourceDir);
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_NE(rows[1][error].find("CROSS_CHECK_FAILED"), std::string::npos) << rows[1][error];
  EXPECT_EQ(run.err, "error: " + rows[1][error] + "\n");
}

}  // namespace
}  // namespace shapebench::bench
