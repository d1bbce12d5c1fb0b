// The output directories of `shapebench sweep` and `merge` through the built CLI
// (bench/sweep/output_dir.h, bench/sweep/sweep_runner.h): one writer at a time, merge
// never over another sweep's or an unfinished run's files, shard rows checked as a
// resumed sweep checks its own, and FIFOs, devices and absurd manifests refused fast.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::LimitChildMemory;
using testing::ReadText;
using testing::Args;
using testing::RunCli;
using testing::ScratchDir;

const std::string kOutputDirNaturalPeriod = "tests/bench/data/sweeps/natural_period.yaml";
const std::vector<std::string> kOutputDirMethod4 = {"--set", "controller.pattern.method=4", "--set",
                                           "controller.pattern.t1_s=0.00477"};

// Runs the CLI with at most 1 GiB of address space and `seconds` of time (then SIGKILL):
// a reader stuck on a FIFO or filling memory from /dev/zero fails instead of hanging.
struct Bounded {
  int exit_code = -1;
  bool timed_out = false;
  std::string err;
};

Bounded RunBounded(const std::vector<std::string>& args, int seconds) {
  ScratchDir capture;
  const std::string err_file = capture.File("err");
  const pid_t pid = fork();
  if (pid == 0) {
    LimitChildMemory(1ul << 30);
    const int null = open("/dev/null", O_WRONLY);
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(null, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    if (chdir(kSourceDir.c_str()) != 0) _exit(127);
    std::string binary = SHAPEBENCH_BINARY;
    std::vector<std::string> copies = args;
    std::vector<char*> argv = {binary.data()};
    for (auto& arg : copies) argv.push_back(arg.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  Bounded result;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!result.timed_out && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.err = ReadText(err_file);
  return result;
}

// Runs shards 0/2 and 1/2 of the method-4 natural-period sweep into DIR/shard0, shard1.
void RunShards(const ScratchDir& dir) {
  for (const std::string shard : {"0", "1"}) {
    const CliResult r = RunCli(
        Args({"sweep", kOutputDirNaturalPeriod, "--shard", shard + "/2", "--out", dir.File("shard" + shard)}, kOutputDirMethod4),
        kSourceDir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
}

// Replaces `from` by `to` once in a file (which must hold it).
void Edit(const std::string& path, const std::string& from, const std::string& to) {
  std::string text = ReadText(path);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << path << " lacks " << from;
  text.replace(at, from.size(), to);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// Tests that while another process holds the output directory's lock (as a running
// sweep does), a sweep and a merge into that directory exit 2 naming the directory and
// the holder's PID and write no rows; and that once it is released, sequential runs work
// and resume as before (the second finds every point done).
TEST(SweepOutputDir, SecondWriterIsRefusedNamingTheHolder) {
  ScratchDir dir;
  const std::string out = dir.File("out");
  fs::create_directories(out);
  const int fd = open((out + "/.shapebench.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string pid = std::to_string(getpid());
  ASSERT_EQ(write(fd, pid.data(), pid.size()), static_cast<ssize_t>(pid.size()));

  const CliResult second = RunCli({"sweep", kOutputDirNaturalPeriod, "--out", out}, kSourceDir);
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find(out), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("pid " + pid), std::string::npos) << second.err;
  EXPECT_FALSE(fs::exists(out + "/results.csv.partial"));
  EXPECT_FALSE(fs::exists(out + "/results.csv"));

  RunShards(dir);
  const CliResult merge = RunCli({"merge", out, dir.File("shard0"), dir.File("shard1")}, kSourceDir);
  EXPECT_EQ(merge.exit_code, 2) << merge.err;
  EXPECT_NE(merge.err.find("pid " + pid), std::string::npos) << merge.err;
  EXPECT_FALSE(fs::exists(out + "/results.csv"));
  close(fd);

  const CliResult first = RunCli({"sweep", kOutputDirNaturalPeriod, "--out", out}, kSourceDir);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const CliResult again = RunCli({"sweep", kOutputDirNaturalPeriod, "--out", out}, kSourceDir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("(201 done before)"), std::string::npos) << again.out;
}

// Tests that merge refuses (exit 2, files untouched) an output directory holding another
// sweep's finished results and one holding an unfinished run's results.csv.partial, and
// still merges into an empty directory and again into its own merged result.
TEST(SweepOutputDir, MergeRefusesDirectoriesItWouldDestroy) {
  ScratchDir dir;
  RunShards(dir);
  const std::string other = dir.File("other");
  ASSERT_EQ(RunCli({"sweep", kOutputDirNaturalPeriod, "--out", other}, kSourceDir).exit_code, 0);
  const std::string other_rows = ReadText(other + "/results.csv");
  const CliResult foreign = RunCli({"merge", other, dir.File("shard0"), dir.File("shard1")}, kSourceDir);
  EXPECT_EQ(foreign.exit_code, 2) << foreign.err;
  EXPECT_NE(foreign.err.find(other + " is not empty"), std::string::npos) << foreign.err;
  EXPECT_EQ(ReadText(other + "/results.csv"), other_rows);

  const std::string whole = dir.File("whole");
  ASSERT_EQ(RunCli(Args({"sweep", kOutputDirNaturalPeriod, "--out", whole}, kOutputDirMethod4), kSourceDir).exit_code, 0);
  const std::string unfinished = dir.File("unfinished");
  fs::create_directories(unfinished);
  fs::copy_file(whole + "/manifest.json", unfinished + "/manifest.json");
  const std::string rows = ReadText(whole + "/results.csv").substr(0, 5000);
  std::ofstream(unfinished + "/results.csv.partial", std::ios::binary) << rows;
  const CliResult partial = RunCli({"merge", unfinished, dir.File("shard0"), dir.File("shard1")}, kSourceDir);
  EXPECT_EQ(partial.exit_code, 2) << partial.err;
  EXPECT_NE(partial.err.find("results.csv.partial"), std::string::npos) << partial.err;
  EXPECT_EQ(ReadText(unfinished + "/results.csv.partial"), rows);

  for (int round = 0; round < 2; ++round) {
    const CliResult merged = RunCli({"merge", dir.File("merged"), dir.File("shard0"), dir.File("shard1")}, kSourceDir);
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    EXPECT_EQ(ReadText(dir.File("merged/results.csv")), ReadText(whole + "/results.csv"));
  }
}

// Tests that merge refuses (exit 2, naming the shard file and row) a shard row with a
// status other than ok or error and one whose key value is not the grid's, rows a resumed
// sweep would not keep.
TEST(SweepOutputDir, MergeChecksEveryRowAgainstTheGrid) {
  ScratchDir dir;
  RunShards(dir);
  const std::string results = dir.File("shard1/results.csv");
  const std::string good = ReadText(results);
  // Shard 1's second row is point 3, at 15.3 Hz.
  ASSERT_NE(good.find("\n3,15.3,15.3,"), std::string::npos);

  Edit(results, ",ok,\n3,15.3,15.3,", ",GARBAGE,\n3,15.3,15.3,");  // the first row's status
  const CliResult garbage = RunCli({"merge", dir.File("m1"), dir.File("shard0"), dir.File("shard1")}, kSourceDir);
  EXPECT_EQ(garbage.exit_code, 2) << garbage.err;
  EXPECT_NE(garbage.err.find(results + ": row 1 (point 1): status 'GARBAGE'"), std::string::npos) << garbage.err;
  EXPECT_FALSE(fs::exists(dir.File("m1/results.csv")));

  std::ofstream(results, std::ios::binary | std::ios::trunc) << good;
  Edit(results, "\n3,15.3,15.3,", "\n3,15.3,99,");
  const CliResult key = RunCli({"merge", dir.File("m2"), dir.File("shard0"), dir.File("shard1")}, kSourceDir);
  EXPECT_EQ(key.exit_code, 2) << key.err;
  EXPECT_NE(key.err.find(results + ": row 2 (point 3): key value '99', not the grid's '15.3'"), std::string::npos)
      << key.err;
  EXPECT_FALSE(fs::exists(dir.File("m2/results.csv")));
}

// Tests that a FIFO manifest.json (in a shard and in a sweep's --out), a shard
// results.csv that is a symbolic link to /dev/zero and a shard manifest claiming 10^9
// shards each fail fast with exit 2 and a message saying why, within 1 GiB of memory.
TEST(SweepOutputDir, FifosDevicesAndAbsurdCountsFailFast) {
  ScratchDir dir;
  RunShards(dir);
  const std::string fifo_dir = dir.File("fifo");
  fs::create_directories(fifo_dir);
  ASSERT_EQ(mkfifo((fifo_dir + "/manifest.json").c_str(), 0644), 0);
  const Bounded shard_fifo = RunBounded({"merge", dir.File("m1"), fifo_dir, dir.File("shard1")}, 15);
  EXPECT_FALSE(shard_fifo.timed_out);
  EXPECT_EQ(shard_fifo.exit_code, 2) << shard_fifo.err;
  EXPECT_NE(shard_fifo.err.find(fifo_dir + "/manifest.json: not a regular file"), std::string::npos)
      << shard_fifo.err;
  const Bounded out_fifo = RunBounded({"sweep", kOutputDirNaturalPeriod, "--out", fifo_dir}, 15);
  EXPECT_FALSE(out_fifo.timed_out);
  EXPECT_EQ(out_fifo.exit_code, 2) << out_fifo.err;
  EXPECT_NE(out_fifo.err.find("not a regular file"), std::string::npos) << out_fifo.err;

  fs::copy(dir.File("shard1"), dir.File("zero"));
  fs::remove(dir.File("zero/results.csv"));
  fs::create_symlink("/dev/zero", dir.File("zero/results.csv"));
  const Bounded zero = RunBounded({"merge", dir.File("m2"), dir.File("shard0"), dir.File("zero")}, 15);
  EXPECT_FALSE(zero.timed_out);
  EXPECT_EQ(zero.exit_code, 2) << zero.err;
  EXPECT_NE(zero.err.find(dir.File("zero/results.csv") + ": not a regular file"), std::string::npos) << zero.err;

  fs::copy(dir.File("shard1"), dir.File("huge"));
  Edit(dir.File("huge/manifest.json"), "\"count\": 2", "\"count\": 1000000000");
  Edit(dir.File("huge/manifest.json"), "\"index\": 1", "\"index\": 0");
  const Bounded huge = RunBounded({"merge", dir.File("m3"), dir.File("huge"), dir.File("shard1")}, 15);
  EXPECT_FALSE(huge.timed_out);
  EXPECT_EQ(huge.exit_code, 2) << huge.err;
  EXPECT_NE(huge.err.find("shards of different --shard N"), std::string::npos) << huge.err;
}

}  // namespace
}  // namespace shapebench::bench
