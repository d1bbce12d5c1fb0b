// `shapebench compare` through the built CLI (docs/compare.md): exit codes of gates, bad
// input and solver trouble; the table, --json and --out; sweeps point by point.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/output/gnuplot.h"
#include "bench/scenario/metrics.h"
#include "tests/support/bench_test_support.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

using testing::Args;
using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const std::vector<std::string> kUnshaped = {"--set", "controller.pattern.method=none"};

// Tests that on configs/demo.yaml a residual_ratio gate of 0 passes (exit 0) when the
// candidate is ZVD and the baseline unshaped, and fails (exit 1) the other way round, with
// a PASS or FAIL line naming the gate; the table has every metric with its unit, better
// direction and verdict.
TEST(CompareCli, GateFailsForTheWorseAndPassesForTheBetter) {
  const CliResult better = RunCli({"compare", "configs/demo.yaml", "--baseline-set", "controller.pattern.method=none",
                                   "--candidate-set", "controller.pattern.method=zvd", "--gate", "residual_ratio=0"},
                                  kSourceDir);
  EXPECT_EQ(better.exit_code, 0) << better.err;
  EXPECT_TRUE(better.err.empty()) << better.err;
  EXPECT_NE(better.out.find("PASS gate residual_ratio=0: better by 99.47% (gate 0%)"), std::string::npos)
      << better.out;
  for (const std::string& name : MetricNames()) {
    EXPECT_NE(better.out.find("\n" + name + " "), std::string::npos) << name;
  }
  EXPECT_NE(better.out.find("baseline   configs/demo.yaml --set controller.pattern.method=none\n"),
            std::string::npos)
      << better.out;
  // The metric column is as wide as the longest metric name and two blanks.
  std::size_t width = 0;
  for (const MetricInfo& info : MetricTable()) width = std::max(width, info.name.size());
  EXPECT_NE(better.out.find("motion_time_s" + std::string(width + 2 - 13, ' ') +
                            "s      lower   700 ms      740 ms        +40 ms"),  // engineering units
            std::string::npos)
      << better.out;

  const CliResult worse = RunCli({"compare", "configs/demo.yaml", "--baseline-set", "controller.pattern.method=zvd",
                                  "--candidate-set", "controller.pattern.method=none", "--gate", "residual_ratio=0",
                                  "--gate", "motion_time_s=0.1"},
                                 kSourceDir);
  EXPECT_EQ(worse.exit_code, 1) << worse.err;
  EXPECT_NE(worse.out.find("FAIL gate residual_ratio=0: worse by "), std::string::npos) << worse.out;
  EXPECT_NE(worse.out.find("PASS gate motion_time_s=0.1: better by 5.405% (gate 10%)"), std::string::npos)
      << worse.out;
}

// Tests that --json holds, per metric, each side's value exactly as `run --json` prints it
// for that side (two files: CANDIDATE given), the change and the relative change as
// fractions, and the gates with their verdict.
TEST(CompareCli, JsonHoldsEachRunsMetricsAndTheChanges) {
  const std::string baseline = DataPath("unshaped_fails.yaml");
  const std::string candidate = DataPath("shaped_method1.yaml");
  const CliResult r =
      RunCli({"compare", baseline, candidate, "--json", "--gate", "peak_ratio=0", "--gate", "radial_error_m=1"},
             kSourceDir);
  ASSERT_EQ(r.exit_code, 1) << r.err;  // radial_error_m is n/a without an arc: its gate fails
  const auto json = nlohmann::json::parse(r.out);
  const auto base_run = nlohmann::json::parse(RunCli({"run", baseline, "--json"}, kSourceDir).out);
  const auto cand_run = nlohmann::json::parse(RunCli({"run", candidate, "--json"}, kSourceDir).out);
  EXPECT_EQ(json["kind"], "scenarios");
  EXPECT_EQ(json["baseline"]["file"], baseline);
  EXPECT_EQ(json["candidate"]["file"], candidate);
  ASSERT_EQ(json["metrics"].size(), MetricTable().size());
  for (const auto& row : json["metrics"]) {
    const std::string name = row["name"];
    EXPECT_EQ(row["baseline"], base_run[name]) << name;
    EXPECT_EQ(row["candidate"], cand_run[name]) << name;
    if (base_run[name].is_number_float() && cand_run[name].is_number_float()) {
      const double b = base_run[name], c = cand_run[name];
      EXPECT_DOUBLE_EQ(row["change"].get<double>(), c - b) << name;
      if (std::fabs(b) >= 1.0) {  // above every floor
        EXPECT_DOUBLE_EQ(row["relative_change"].get<double>(), (c - b) / std::fabs(b)) << name;
      }
    }
  }
  ASSERT_EQ(json["gates"].size(), 2u);
  EXPECT_EQ(json["gates"][0]["passed"], true);
  EXPECT_EQ(json["gates"][1]["passed"], false);
  EXPECT_EQ(json["gates"][1]["detail"], "n/a in both runs: not comparable (gate 100%)");
  EXPECT_EQ(json["passed"], false);
}

// Tests that --out DIR holds compare.txt (the printed table), compare.json and a complete
// deflection.png, and that bad input leaves no directory behind.
TEST(CompareCli, OutWritesTableJsonAndOverlayPlot) {
  ScratchDir dir;
  const std::string out = dir.File("cmp");
  const std::vector<std::string> args = {"compare", "configs/demo.yaml", "--candidate-set",
                                         "controller.pattern.method=zvd"};
  const CliResult r = RunCli(Args(args, {"--out", out}), kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // stdout: the table as compare.txt holds it, then a "wrote" line per file.
  EXPECT_EQ(r.out, ReadText(out + "/compare.txt") + "wrote " + out + "/compare.txt\nwrote " + out +
                       "/compare.json\nwrote " + out + "/deflection.png\n");
  EXPECT_EQ(nlohmann::json::parse(ReadText(out + "/compare.json")),
            nlohmann::json::parse(RunCli(Args(args, {"--json"}), kSourceDir).out));
  EXPECT_EQ(PngDefect(out + "/deflection.png"), "");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out), std::filesystem::directory_iterator()), 3);

  const std::string bad = dir.File("bad");
  const CliResult refused =
      RunCli(Args(args, {"--candidate-set", "controller.pattern.bogus=1", "--out", bad}), kSourceDir);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("error: --candidate-set:2:1: controller.pattern."), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 1);
}

// Tests that two sweeps compare point by point: the worst point per metric printed, the gate
// failing when any point fails it (exit 1), --json with the counts, and --out's points.csv
// with a row per point and metric.
TEST(CompareCli, SweepsComparePointByPoint) {
  ScratchDir dir;
  const std::vector<std::string> args = {"compare", DataPath("sweeps/failing_point.yaml"), "--baseline-set",
                                         "controller.pattern.method=zvd", "--gate", "residual_ratio=0.01"};
  const CliResult r = RunCli(Args(args, {"--jobs", "2", "--out", dir.File("out")}), kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("points     3\n"), std::string::npos) << r.out;
  // Method 1 leaves 11% at 24.5 Hz and 25.5 Hz, ZVD far less: the worst point is one of them.
  EXPECT_NE(r.out.find("FAIL gate residual_ratio=0.01: 1 of 3 points pass; worst: worse by "), std::string::npos)
      << r.out;
  const auto json = nlohmann::json::parse(RunCli(Args(args, {"--json"}), kSourceDir).out);
  EXPECT_EQ(json["kind"], "sweeps");
  EXPECT_EQ(json["points"], 3);
  EXPECT_EQ(json["gates"][0]["failed_points"], 2);
  const auto& residual = json["metrics"][4];
  EXPECT_EQ(residual["name"], "residual_ratio");
  EXPECT_EQ(residual["baseline_better"].get<int>() + residual["candidate_better"].get<int>() +
                residual["same"].get<int>(),
            3);
  EXPECT_EQ(residual["worst"]["favours"], "baseline");
  const std::string csv = ReadText(dir.File("out/points.csv"));
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), 1 + 3 * MetricTable().size());
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "point,machine.modes[0].frequency_hz,metric,baseline,candidate,change,relative_change,favours,error");
}

// Tests that a sweep point that fails to run on one side (method 4's t1 above T/6 at 35 Hz)
// is an error line naming the side, its option and the point, the other points are still
// compared, and the exit code is 2 (bad input outranks a failed gate).
TEST(CompareCli, SweepPointThatFailsOnASideExits2) {
  const CliResult r = RunCli({"compare", DataPath("sweeps/natural_period.yaml"), "--candidate-set",
                              "controller.pattern.method=4", "--candidate-set", "controller.pattern.t1_s=0.00477",
                              "--gate", "motion_time_s=0"},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("error: --candidate-set:2:1: controller.pattern.t1_s: must be in [0, T/6]"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("(candidate " + DataPath("sweeps/natural_period.yaml") +
                       " @ machine.modes[0].frequency_hz=35, controller.pattern.frequency_hz=35)\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.out.find("points     201 (1 failed to run on a side, compared on 200)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PASS gate motion_time_s=0: 200 of 200 points pass"), std::string::npos) << r.out;
}

// Tests that sweeps of different grids, a sweep against a scenario and a request with
// nothing to compare exit 2 with a message saying why, before anything runs.
TEST(CompareCli, MismatchedInputsExit2) {
  CliResult r = RunCli({"compare", DataPath("sweeps/failing_point.yaml"), DataPath("sweeps/map.yaml")}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: compare: the sweeps' grids differ (1 axis in the baseline, 2 in the candidate)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = RunCli({"compare", DataPath("sweeps/failing_point.yaml"), "configs/demo.yaml"}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give two scenarios or two sweeps"), std::string::npos) << r.err;
  r = RunCli({"compare", "configs/demo.yaml"}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nothing to compare"), std::string::npos) << r.err;
}

// Tests that a gate's REL is a decimal number >= 0: "0x10" (read as 16, a 1600% gate),
// "inf" and "nan" exit 2 naming the gate (issue 32 item 16).
TEST(CompareCli, GateTakesDecimalNumbersOnly) {
  for (const char* rel : {"0x10", "inf", "nan", "-0.1"}) {
    const std::string gate = std::string("residual_ratio=") + rel;
    const CliResult r = RunCli({"compare", "configs/demo.yaml", "--candidate-set", "controller.pattern.method=zvd",
                                "--gate", gate},
                               kSourceDir);
    EXPECT_EQ(r.exit_code, 2) << rel;
    EXPECT_NE(r.err.find("error: --gate " + gate + ": REL must be a number >= 0"), std::string::npos) << r.err;
  }
}

// Tests that a gate on an unknown metric exits 2 before anything runs, suggesting the
// closest names and listing the allowed ones.
TEST(CompareCli, UnknownGateMetricExits2WithDidYouMean) {
  const CliResult r = RunCli({"compare", "configs/demo.yaml", "--candidate-set", "controller.pattern.method=zvd",
                              "--gate", "peak_ration=0.1"},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error: --gate peak_ration=0.1: unknown metric 'peak_ration'; did you mean peak_ratio? "
                       "allowed: static_displacement_m, "),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// Tests that a solver failure on either side exits 3, and that --help describes the command.
TEST(CompareCli, SolverTroubleExits3AndHelpDescribesTheOptions) {
  const CliResult r = RunCli(
      {"compare", "configs/demo.yaml", "--candidate-set", "integrator.max_num_steps=1", "--gate", "peak_ratio=0"},
      kSourceDir);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("error: solver failed: CV_TOO_MUCH_WORK"), std::string::npos) << r.err;
  const CliResult help = RunCli({"compare", "--help"}, kSourceDir);
  EXPECT_EQ(help.exit_code, 0);
  for (const char* option : {"BASELINE.yaml", "CANDIDATE.yaml", "--set", "--baseline-set", "--candidate-set",
                             "--gate", "--json", "--out", "--jobs"}) {
    EXPECT_NE(help.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace shapebench::bench
