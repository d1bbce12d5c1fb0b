// `sweep` and `check` under mpirun (bench/sweep/sweep_mpi.h, docs/scaling.md) and in a
// Slurm job array (bench/sweep/slurm_array.h), through the built CLI: the same bytes as
// --jobs 1 for any ranks x jobs, a rank lost mid-run then resumed, the same check verdict.
// The MPI cases need mpirun (openmpi-bin) and a shapebench built with MPI
// (libopenmpi-dev); `make test` installs both.
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/sweep/slurm_array.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::Args;
using testing::CliResult;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

const std::string kShippedNaturalPeriod = "configs/sweeps/natural_period.yaml";  // 603 points

// Why the MPI cases cannot run here ("" when they can).
std::string MpiMissing() {
#ifndef SHAPEBENCH_TESTS_WITH_MPI
  return "shapebench was built without MPI (libopenmpi-dev; `make test` installs it)";
#else
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) {
    return "mpirun not found (openmpi-bin; `make test` installs it)";
  }
  return "";
#endif
}

// The wrapper that starts the CLI on `ranks` ranks; root allowed as in CI (docs/scaling.md).
// Under AddressSanitizer (make test-sanitize) without leak detection: Open MPI does not
// free what MPI_Init allocates, and those are its leaks, not ours.
std::string Mpirun(int ranks, const std::string& env = "") {
  const std::string asan = testing::kUnderAddressSanitizer ? "ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" " : "";
  return asan + "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + env + " mpirun -n " +
         std::to_string(ranks) + " --oversubscribe ";
}

std::string MpiReference(const ScratchDir& dir) {
  const CliResult r = RunCli({"sweep", kShippedNaturalPeriod, "--jobs", "1", "--out", dir.File("jobs1")}, kSourceDir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir.File("jobs1");
}

// Tests that the shipped natural-period sweep on 3 ranks x 1 job and on 2 ranks x 2 jobs
// writes --jobs 1's results.csv and manifest.json byte for byte and reports the same
// summary line, with rows computed by the other ranks (SHAPEBENCH_MPI_STATS counts the
// result messages rank 0 received) and nothing else on stderr.
TEST(SweepMpi, RanksAndJobsWriteTheJobsOneFile) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  ScratchDir dir;
  const std::string reference = MpiReference(dir);
  int messages = 0;
  for (const auto& [ranks, jobs] : std::vector<std::pair<int, std::string>>{{3, "1"}, {2, "2"}}) {
    const std::string out = dir.File("ranks" + std::to_string(ranks));
    const CliResult r = RunCli({"sweep", kShippedNaturalPeriod, "--jobs", jobs, "--out", out}, kSourceDir,
                               Mpirun(ranks, "SHAPEBENCH_MPI_STATS=1"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference + "/results.csv")) << ranks << " ranks";
    EXPECT_EQ(ReadText(out + "/manifest.json"), ReadText(reference + "/manifest.json"));
    EXPECT_NE(r.out.find("sweep natural_period: 603 points, 603 ok, 0 error -> " + out), std::string::npos) << r.out;
    std::smatch stats;
    const std::regex line("^mpi: 603 points on " + std::to_string(ranks) +
                          " ranks in [^;]*; rank 0 busy [^;]*; ([0-9]+) messages, [0-9]+ bytes received\n$");
    ASSERT_TRUE(std::regex_match(r.err, stats, line)) << r.err;  // the only line: the other ranks are quiet
    messages += std::stoi(stats[1]);
  }
  // A rank starting late on a loaded machine may find its points taken: one of the two runs suffices.
  EXPECT_GT(messages, 0) << "rank 0 computed every point itself";
}

// Tests that a run whose rank 2 dies (SIGKILL after 40 points) exits non-zero leaving a
// partial file of complete rows, and that resuming it, once on 2 ranks and once without
// MPI, ends with --jobs 1's results.csv byte for byte.
TEST(SweepMpi, LostRankThenResumeGivesTheSameFile) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  ScratchDir dir;
  const std::string reference = ReadText(MpiReference(dir) + "/results.csv");
  for (const std::string resume_ranks : {"2", "none"}) {
    const std::string out = dir.File("killed" + resume_ranks);
    const CliResult killed = RunCli({"sweep", kShippedNaturalPeriod, "--jobs", "1", "--out", out}, kSourceDir,
                                    Mpirun(3, "SHAPEBENCH_TEST_MPI_DIE=2:40"));
    EXPECT_NE(killed.exit_code, 0) << killed.out;
    ASSERT_FALSE(std::filesystem::exists(out + "/results.csv"));
    const std::string partial = ReadText(out + "/results.csv.partial");
    ASSERT_LT(partial.size(), reference.size());
    EXPECT_EQ(partial, reference.substr(0, partial.size()));  // the rows written are the right ones

    const CliResult resumed =
        RunCli({"sweep", kShippedNaturalPeriod, "--out", out}, kSourceDir, resume_ranks == "2" ? Mpirun(2) : "");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    EXPECT_NE(resumed.out.find("done before)"), std::string::npos) << resumed.out;
    EXPECT_EQ(ReadText(out + "/results.csv"), reference) << "resumed on " << resume_ranks;
  }
}

// Tests that `check` on 3 ranks prints what it prints without MPI and exits the same:
// the natural-period sweep (0, all pass); a scenario, a sweep with a failing point and the
// natural-period sweep in one command (1: the ranks follow rank 0 from sweep to sweep);
// method 4 where the 35 Hz point fails to run (2, its error on stderr).
TEST(SweepMpi, CheckGivesTheSameVerdict) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  const std::vector<std::vector<std::string>> cases = {
      {"check", kShippedNaturalPeriod},
      {"check", "configs/scenarios/sdof_method1.yaml", "tests/bench/data/sweeps/failing_point.yaml", kShippedNaturalPeriod},
      {"check", "tests/bench/data/sweeps/natural_period.yaml", "--set", "controller.pattern.method=4", "--set",
       "controller.pattern.t1_s=0.00477"}};
  const int expected_codes[] = {0, 1, 2};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const CliResult plain = RunCli(Args(cases[i], {"--jobs", "1"}), kSourceDir);
    const CliResult mpi = RunCli(Args(cases[i], {"--jobs", "1"}), kSourceDir, Mpirun(3));
    EXPECT_EQ(plain.exit_code, expected_codes[i]) << plain.err;
    EXPECT_EQ(mpi.exit_code, plain.exit_code) << mpi.err;
    EXPECT_EQ(mpi.out, plain.out);
    // mpirun adds its own lines about a non-zero exit after rank 0's.
    EXPECT_EQ(mpi.err.substr(0, plain.err.size()), plain.err);
  }
}

// Tests that the shipped sampled yield study (seed 42, 500 normal samples crossed with two
// methods) draws the same points on 1, 2 and 3 ranks: results.csv and manifest.json equal
// --jobs 1's byte for byte, and `check` prints the same yields and Wilson intervals.
TEST(SweepMpi, SampledSweepIsTheSameOnAnyNumberOfRanks) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  const std::string yield = "configs/sweeps/moving_column_yield.yaml";
  ScratchDir dir;
  const CliResult plain = RunCli({"sweep", yield, "--jobs", "1", "--out", dir.File("jobs1")}, kSourceDir);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const CliResult plain_check = RunCli({"check", yield, "--jobs", "1"}, kSourceDir);
  ASSERT_EQ(plain_check.exit_code, 1) << plain_check.err;  // method 1's yield misses 0.95
  for (const int ranks : {1, 2, 3}) {
    const std::string out = dir.File("ranks" + std::to_string(ranks));
    const CliResult r = RunCli({"sweep", yield, "--jobs", "1", "--out", out}, kSourceDir, Mpirun(ranks));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(dir.File("jobs1") + "/results.csv")) << ranks << " ranks";
    EXPECT_EQ(ReadText(out + "/manifest.json"), ReadText(dir.File("jobs1") + "/manifest.json")) << ranks;
    const CliResult check = RunCli({"check", yield, "--jobs", "1"}, kSourceDir, Mpirun(ranks));
    EXPECT_EQ(check.exit_code, 1) << check.err;
    EXPECT_EQ(check.out, plain_check.out) << ranks << " ranks";
  }
}

// Tests that ranks started on different sweeps are refused before the first point, exit
// 2, rank 0 naming the first rank that differs and what differs: MPMD with rank 0 on the
// natural-period sweep and ranks 1 and 2 on it with --set controller.feed_mm_min=20000,
// for `check` (nothing printed on stdout) and `sweep` (no manifest, no row written);
// and rank 1 running `check` where rank 0 runs `sweep`.
TEST(SweepMpi, RanksRunningAnotherSweepAreRefused) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  ScratchDir dir;
  const std::string binary = testing::ShellQuoted(SHAPEBENCH_BINARY);
  const std::vector<std::string> other_set = {"--set", "controller.feed_mm_min=20000"};
  for (const std::string command : {"check", "sweep"}) {
    SCOPED_TRACE(command);
    const std::string out = dir.File(command + "_out");
    std::vector<std::string> args = {command, kShippedNaturalPeriod, "--jobs", "1"};
    if (command == "sweep") args = Args(args, {"--out", out});
    std::string rank0;
    for (const std::string& arg : args) rank0 += " " + testing::ShellQuoted(arg);
    const CliResult r = RunCli(Args(args, other_set), kSourceDir, Mpirun(1) + binary + rank0 + " : -n 2 ");
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_NE(r.err.find("error: MPI rank 1 of 3 does not run what rank 0 runs: --set options "
                         "\"controller.feed_mm_min=20000\" on rank 1, none on rank 0; sweep hash"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("(rank 2 differs from rank 0 too); every rank must run the same command"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(std::filesystem::exists(out + "/manifest.json"));
    EXPECT_FALSE(std::filesystem::exists(out + "/results.csv.partial"));
  }
  const std::string out = dir.File("mixed");
  const CliResult mixed = RunCli({"check", kShippedNaturalPeriod, "--jobs", "1"}, kSourceDir,
                                 Mpirun(1) + binary + " sweep " + kShippedNaturalPeriod + " --jobs 1 --out " +
                                     testing::ShellQuoted(out) + " : -n 1 ");
  EXPECT_EQ(mixed.exit_code, 2) << mixed.err;
  EXPECT_NE(mixed.err.find("error: MPI rank 1 of 2 does not run what rank 0 runs: command \"check\" on rank 1, "
                           "\"sweep\" on rank 0"),
            std::string::npos)
      << mixed.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/manifest.json"));
}

// Tests that a sweep resumed on 3 ranks takes the rows of results.csv.ahead without
// handing their points to any rank: 50 rows in order and 11 ahead (points 60-69 and 300)
// then a torn row; those points set to hang on every rank, the run ends (exit 0),
// reports 61 done before and writes --jobs 1's results.csv byte for byte.
TEST(SweepMpi, ResumeHandsNoRowAheadToAnyRank) {
  if (const std::string missing = MpiMissing(); !missing.empty()) GTEST_SKIP() << missing;
  ScratchDir dir;
  const std::string reference = MpiReference(dir);
  const std::string out = dir.File("ahead");
  const std::string hang =
      testing::WriteSweepDirWithRowsAhead(reference, out, 50, {61, 60, 300, 62, 63, 64, 65, 66, 67, 68, 69});
  const CliResult r = RunCli({"sweep", kShippedNaturalPeriod, "--jobs", "1", "--out", out}, kSourceDir,
                             "timeout -k 10 120 env " + Mpirun(3, "SHAPEBENCH_TEST_HANG_POINT=" + hang));
  ASSERT_EQ(r.exit_code, 0) << r.err;  // 124 (137: killed by -k): a point ahead was run again, and hung
  EXPECT_NE(r.out.find("(61 done before)"), std::string::npos) << r.out;
  EXPECT_EQ(ReadText(out + "/results.csv"), ReadText(reference + "/results.csv"));
  EXPECT_FALSE(std::filesystem::exists(out + "/results.csv.ahead"));
}

// Tests that a Slurm array task without --shard runs shard ID-MIN of COUNT into
// DIR/shard-I-of-N, that both tasks merge to --jobs 1's file, that an explicit --shard
// wins (and --out is used as given), and that an id that is no shard is refused (exit 2).
TEST(SweepSlurm, ArrayTaskDefaultsTheShard) {
  ScratchDir dir;
  const std::string reference = MpiReference(dir);
  for (const std::string id : {"3", "4"}) {  // --array=3-4
    const CliResult r = RunCli({"sweep", kShippedNaturalPeriod, "--jobs", "1", "--out", dir.File("array")}, kSourceDir,
                               "SLURM_ARRAY_TASK_ID=" + id + " SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=3 ");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("(shard " + std::to_string(std::stoi(id) - 3) + "/2 of 603)"), std::string::npos) << r.out;
  }
  ASSERT_TRUE(std::filesystem::exists(dir.File("array/shard-0-of-2/results.csv")));
  const CliResult merged = RunCli({"merge", "--out", dir.File("merged"), dir.File("array/shard-0-of-2"),
                                   dir.File("array/shard-1-of-2")},
                                  kSourceDir);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(ReadText(dir.File("merged/results.csv")), ReadText(reference + "/results.csv"));

  const CliResult explicit_shard =
      RunCli({"sweep", kShippedNaturalPeriod, "--shard", "1/3", "--out", dir.File("explicit")}, kSourceDir,
             "SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=2 ");
  ASSERT_EQ(explicit_shard.exit_code, 0) << explicit_shard.err;
  EXPECT_NE(explicit_shard.out.find("(shard 1/3 of 603)"), std::string::npos) << explicit_shard.out;
  EXPECT_TRUE(std::filesystem::exists(dir.File("explicit/results.csv")));

  const CliResult bad = RunCli({"sweep", kShippedNaturalPeriod, "--out", dir.File("bad")}, kSourceDir,
                               "SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_COUNT=2 ");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("pass --shard I/N explicitly"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("bad")));
}

// Tests the shard of a task for the ways an array's ids are spaced: MIN and STEP
// (--array=10-16:2), COUNT from MAX when unset, no array, and ids that are no shard.
TEST(SweepSlurm, ShardFromTheArrayVariables) {
  const auto shard = [](std::map<std::string, std::string> env) {
    return SlurmArrayShard([env](const char* name) {
      const auto it = env.find(name);
      return it == env.end() ? nullptr : it->second.c_str();
    });
  };
  EXPECT_FALSE(shard({}).has_value());
  const auto stepped = shard({{"SLURM_ARRAY_TASK_ID", "14"}, {"SLURM_ARRAY_TASK_MIN", "10"},
                              {"SLURM_ARRAY_TASK_STEP", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}});
  ASSERT_TRUE(stepped.has_value());
  EXPECT_EQ(stepped->index, 2u);
  EXPECT_EQ(stepped->count, 4u);
  const auto from_max = shard({{"SLURM_ARRAY_TASK_ID", "7"}, {"SLURM_ARRAY_TASK_MAX", "7"}});
  ASSERT_TRUE(from_max.has_value());
  EXPECT_EQ(from_max->index, 7u);
  EXPECT_EQ(from_max->count, 8u);
  EXPECT_EQ(ArrayShardDir("out", *stepped), "out/shard-2-of-4");
  EXPECT_THROW(shard({{"SLURM_ARRAY_TASK_ID", "13"}, {"SLURM_ARRAY_TASK_MIN", "10"}, {"SLURM_ARRAY_TASK_STEP", "2"},
                      {"SLURM_ARRAY_TASK_COUNT", "4"}}),
               std::runtime_error);
  EXPECT_THROW(shard({{"SLURM_ARRAY_TASK_ID", "1"}}), std::runtime_error);  // no COUNT nor MAX
  EXPECT_THROW(shard({{"SLURM_ARRAY_TASK_ID", "x"}, {"SLURM_ARRAY_TASK_COUNT", "2"}}), std::runtime_error);
  // A negative id is named as negative, not as "not a whole number" (issue 32 item 16).
  try {
    shard({{"SLURM_ARRAY_TASK_ID", "-1"}, {"SLURM_ARRAY_TASK_COUNT", "2"}});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("SLURM_ARRAY_TASK_ID='-1' is negative"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace shapebench::bench
