// limits.max_work and identify --max-work (docs/reliability.md#limits): work is counted,
// never timed, so these small budgets fire the same way on any host and at any --jobs.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

bool Says(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Tests that a run over its work budget stops with exit 3 saying what it did, the limit and
// the key that raises it, on CVODE and on the exact path, and that the same run fits a
// larger budget.
TEST(WorkLimit, RunOverBudgetExits3NamingTheLimit) {
  const std::string scenario = DataPath("sweeps/sdof_method1.yaml");
  ScratchDir dir;
  for (const char* method : {"cvode", "exact"}) {
    // With a trace (--out): the exact path then simulates its tail, which an untraced run
    // takes in closed form with less work (4330 units here, within the budget).
    const CliResult over = RunCli({"run", scenario, "--set", std::string("integrator.method=") + method, "--set",
                                   "integrator.cross_check=off", "--set", "limits.max_work=4350", "--out",
                                   dir.File(method)},
                                  kSourceDir);
    EXPECT_EQ(over.exit_code, 3) << method << over.err;
    EXPECT_EQ(over.err.rfind("error: solver failed: WORK_LIMIT: scenario 'sdof_method1' stopped at t = ", 0), 0u)
        << over.err;
    EXPECT_TRUE(Says(over.err, "units of work, more than limits.max_work (4350): ")) << over.err;
    EXPECT_TRUE(Says(over.err, " output samples")) << over.err;
    EXPECT_TRUE(Says(over.err, "raise limits.max_work (e.g. --set limits.max_work=100000) to run it on")) << over.err;
    const CliResult within = RunCli({"run", scenario, "--set", std::string("integrator.method=") + method, "--set",
                                     "integrator.cross_check=off", "--set", "limits.max_work=2000000"},
                                    kSourceDir);
    EXPECT_EQ(within.exit_code, 0) << method << within.err;
  }
  const CliResult cvode = RunCli({"run", scenario, "--set", "integrator.method=cvode", "--set",
                                  "integrator.cross_check=off", "--set", "limits.max_work=4350"},
                                 kSourceDir);
  EXPECT_TRUE(Says(cvode.err, "CVODE steps and right-hand-side evaluations")) << cvode.err;
  const CliResult zero = RunCli({"run", scenario, "--set", "limits.max_work=0"}, kSourceDir);
  EXPECT_EQ(zero.exit_code, 2) << zero.err;
  EXPECT_TRUE(Says(zero.err, "--set:1:1: limits.max_work: must be >= 1")) << zero.err;
}

// Tests that limits.max_wall_s (off by default) stops a run past it with exit 3 naming the
// key and that the host decided it, and that it takes only a number >= 0.
TEST(WorkLimit, WallClockLimitStopsARunPastIt) {
  const std::string scenario = DataPath("sweeps/sdof_method1.yaml");
  const CliResult over = RunCli({"run", scenario, "--set", "limits.max_wall_s=1e-9"}, kSourceDir);
  EXPECT_EQ(over.exit_code, 3) << over.err;
  EXPECT_EQ(over.err.rfind("error: solver failed: WALL_LIMIT: scenario 'sdof_method1' stopped at t = ", 0), 0u)
      << over.err;
  EXPECT_TRUE(Says(over.err, "s of wall-clock time, more than limits.max_wall_s (1e-09 s): this host's speed and "
                            "load decided it (limits.max_work is the same everywhere); raise limits.max_wall_s, or "
                            "set it to 0 (no limit), to run it on\n"))
      << over.err;
  EXPECT_EQ(RunCli({"run", scenario, "--set", "limits.max_wall_s=0"}, kSourceDir).exit_code, 0);
  const CliResult bad = RunCli({"run", scenario, "--set", "limits.max_wall_s=-1"}, kSourceDir);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_TRUE(Says(bad.err, "--set:1:1: limits.max_wall_s: must be >= 0 s (0: no wall-clock limit)")) << bad.err;
}

// Tests that a run whose least work (periods x (output samples + the exact path's extremum
// grid)) exceeds the budget is refused before it starts: a 1e8 Hz mode on the exact path at
// a 1 ms period (133 s before item 1's fix and this limit) costs 4e5 passes a period.
TEST(WorkLimit, EstimateRefusesBeforeStarting) {
  ScratchDir dir;
  const std::string scenario = dir.Write(
      "fast.yaml",
      "machine:\n  modes:\n    - {frequency_hz: 1.0e8, damping_ratio: 0.03, gain: 1.0}\n"
      "controller: {period_s: 0.001, feed_mm_min: 30000, accel_time_s: 0.3}\n"
      "move: {distance_mm: 100}\nintegrator: {method: exact}\n");
  const CliResult refused = RunCli({"run", scenario, "--set", "limits.max_work=100000000"}, kSourceDir);
  EXPECT_EQ(refused.exit_code, 3) << refused.err;
  EXPECT_EQ(refused.err,
            "error: solver failed: WORK_LIMIT: scenario 'fast' would do at least 196342553 units of work, more than "
            "limits.max_work (100000000): 491 periods (the motion and its residual window) x (64 output samples + "
            "399819 passes of the exact path's in-tick extremum search (its grid: a quarter of the fastest pole's "
            "period a step)) a period; nothing was run: raise limits.max_work (e.g. --set "
            "limits.max_work=10000000000) to run it\n");
  // The output samples alone: a budget below them refuses any integrator at once.
  const CliResult samples = RunCli({"run", DataPath("sweeps/sdof_method1.yaml"), "--set", "limits.max_work=10"},
                                   kSourceDir);
  EXPECT_EQ(samples.exit_code, 3) << samples.err;
  EXPECT_TRUE(Says(samples.err, "would do at least ")) << samples.err;
  EXPECT_TRUE(Says(samples.err, "more than limits.max_work (10): ")) << samples.err;
}

// Tests that a sweep point over its budget becomes an error row naming the limit while the
// other points run, and that the rows are the same bytes on one job and on two.
TEST(WorkLimit, SweepPointOverBudgetIsAnErrorRow) {
  ScratchDir dir;
  const std::string sweep = dir.Write(
      "sweep.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                        "\ngrid:\n  limits.max_work: [4350, 2000000, 4360]\nmetrics: [peak_ratio]\n");
  const std::vector<std::string> cvode = {"--set", "integrator.method=cvode", "--set", "integrator.cross_check=off"};
  std::vector<std::string> args = {"sweep", sweep, "--jobs", "1", "--out", dir.File("one")};
  args.insert(args.end(), cvode.begin(), cvode.end());
  const CliResult one = RunCli(args, kSourceDir);
  EXPECT_EQ(one.exit_code, 0) << one.err;
  const std::string rows = ReadText(dir.File("one/results.csv"));
  EXPECT_TRUE(Says(rows, "error,\"solver failed: WORK_LIMIT: scenario 'sdof_method1' stopped at t = ")) << rows;
  EXPECT_TRUE(Says(rows, "more than limits.max_work (4350): ")) << rows;
  EXPECT_TRUE(Says(rows, "more than limits.max_work (4360): ")) << rows;
  EXPECT_TRUE(Says(rows, ",ok,")) << rows;
  args = {"sweep", sweep, "--jobs", "2", "--out", dir.File("two")};
  args.insert(args.end(), cvode.begin(), cvode.end());
  const CliResult two = RunCli(args, kSourceDir);
  EXPECT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(ReadText(dir.File("two/results.csv")), rows);
}

// Tests that identify refuses a fit whose estimated work exceeds --max-work before fitting
// (exit 3, naming the option and the sizes, nothing written), that --max-work takes only a
// number >= 1, that the shipped measurement fits the default, and that an frf_file
// machine's max_work bounds its identification the same way.
TEST(WorkLimit, IdentifyOverBudgetExits3) {
  ScratchDir dir;
  const std::string uff = "configs/measurements/column_y_accelerance.uff";
  const CliResult over = RunCli({"identify", uff, "--max-work", "1e6", "--out", dir.File("o")}, kSourceDir);
  EXPECT_EQ(over.exit_code, 3) << over.err;
  EXPECT_TRUE(Says(over.err, "error: solver failed: WORK_LIMIT: " + uff + ": identifying 1 FRF of ")) << over.err;
  EXPECT_TRUE(Says(over.err, " lines up to order 30 would take about ")) << over.err;
  EXPECT_TRUE(Says(over.err, "more than --max-work (1e+06); nothing was fitted: raise --max-work (e.g. to ")) << over.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("o/modes.json")));
  const CliResult bad = RunCli({"identify", uff, "--max-work", "0x10", "--out", dir.File("o")}, kSourceDir);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_TRUE(Says(bad.err, "--max-work: expected a number >= 1")) << bad.err;
  const CliResult shipped = RunCli({"identify", uff, "--out", dir.File("o")}, kSourceDir);
  EXPECT_EQ(shipped.exit_code, 0) << shipped.err;
  // An frf_file machine's identification, bounded by its own key.
  const CliResult machine =
      RunCli({"run", "configs/scenarios/measured_frf.yaml", "--set", "machine.max_work=1000"}, kSourceDir);
  EXPECT_EQ(machine.exit_code, 3) << machine.err;
  EXPECT_TRUE(Says(machine.err, "more than machine.max_work (1e+03); nothing was fitted: raise machine.max_work"))
      << machine.err;
}

// Tests that --max-work bounds every part of an identification, the trials of poles the
// diagram missed too (they made the hammer test's whole file run over 15 minutes): with a
// budget the diagram and the first refinement fit in, the default and the automatic run
// on it stop at those trials with exit 3, naming the part, the budget and the work spent,
// writing nothing, within seconds.
TEST(WorkLimit, IdentifyChargesTheMissedPoleTrials) {
  ScratchDir dir;
  const std::string uff = "tests/data/uff/real/pyfrf_hammer_h1_accelerance.uff";
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, std::vector<std::string>{"--band", "auto", "--max-order", "auto"}}) {
    std::vector<std::string> args = {"identify", uff, "--max-work", "3e8", "--out", dir.File("o")};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto start = std::chrono::steady_clock::now();
    const CliResult over = RunCli(args, kSourceDir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(over.exit_code, 3) << over.err;
    EXPECT_TRUE(Says(over.err, "error: solver failed: WORK_LIMIT: " + uff + ": trying ")) << over.err;
    EXPECT_TRUE(Says(over.err, " candidates for a pole the diagram missed (")) << over.err;
    EXPECT_TRUE(Says(over.err, "more than --max-work (3e+08; ")) << over.err;
    EXPECT_TRUE(Says(over.err, " spent before it); stopped, no mode is reported: raise --max-work (e.g. to "))
        << over.err;
    EXPECT_FALSE(std::filesystem::exists(dir.File("o/modes.json")));
    EXPECT_LT(seconds, 30.0);  // 0.05-0.2 s of CPU; generous for a loaded host
  }
}

}  // namespace
}  // namespace shapebench::bench
