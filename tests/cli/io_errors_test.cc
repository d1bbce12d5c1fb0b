// Every I/O failure names its file and the OS's cause (the errno of the failing call),
// and running out of memory says what was running and which limit bounds it
// (docs/reliability.md, errors and exit codes). /dev/full is reached through a symbolic
// link in a scratch directory: a rename over the link never touches the device.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/output/gnuplot.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_plot.h"
#include "tests/support/bench_test_support.h"
#include "common/atomic_file.h"
#include "common/fd_stream.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;
using testing::ShellQuoted;

constexpr const char* kNoSpace = "No space left on device";

bool IsCharacterDevice(const std::string& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0 && S_ISCHR(info.st_mode);
}

// A symbolic link to /dev/full in `dir`.
std::string FullDisk(const ScratchDir& dir, const std::string& name) {
  const std::string link = dir.File(name);
  fs::create_directories(fs::path(link).parent_path());
  fs::create_symlink("/dev/full", link);
  return link;
}

// Runs the CLI with stdout going to /dev/full; stderr captured.
CliResult RunCliStdoutFull(const std::vector<std::string>& args) {
  ScratchDir capture;
  std::string command = "cd " + ShellQuoted(kSourceDir) + " && " + ShellQuoted(SHAPEBENCH_BINARY);
  for (const auto& arg : args) command += " " + ShellQuoted(arg);
  command += " >/dev/full 2>" + ShellQuoted(capture.File("err"));
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = ReadText(capture.File("err"));
  return result;
}

// Tests that writing a file onto a full device fails naming the file and "No space left
// on device" (not "write failed"), and writes into the device rather than replacing it.
TEST(IoErrors, WritingToAFullDeviceNamesTheCause) {
  if (!IsCharacterDevice("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  ScratchDir dir;
  const std::string link = FullDisk(dir, "report.xml");
  try {
    WriteFileAtomically(link, [](std::ostream& out) { out << std::string(100000, 'x'); });
    ADD_FAILURE() << "no error writing to /dev/full";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "cannot write " + link + ": " + kNoSpace);
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(IsCharacterDevice("/dev/full"));
}

// Tests that the CLI reports a full disk with the file and the cause, exit 2: a JUnit
// report, a file of `run --out`, and stdout itself (which used to fail silently, exit 0).
TEST(IoErrors, CliNamesTheFileAndTheCauseOfAFullDisk) {
  if (!IsCharacterDevice("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  ScratchDir dir;
  const std::string scenario = "configs/scenarios/method1.yaml";
  const std::string junit = FullDisk(dir, "junit.xml");
  const CliResult check = RunCli({"check", scenario, "--junit", junit}, kSourceDir);
  EXPECT_EQ(check.exit_code, 2) << check.err;
  EXPECT_NE(check.err.find("error: cannot write " + junit + ": " + kNoSpace), std::string::npos) << check.err;

  const std::string metrics = FullDisk(dir, "out/metrics.json");
  const CliResult run = RunCli({"run", scenario, "--out", dir.File("out")}, kSourceDir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("error: cannot write " + metrics + ": " + kNoSpace), std::string::npos) << run.err;

  const CliResult json = RunCliStdoutFull({"run", scenario, "--json"});
  EXPECT_EQ(json.exit_code, 2) << json.err;
  EXPECT_EQ(json.err, std::string("error: cannot write standard output: ") + kNoSpace + "\n");
  EXPECT_TRUE(IsCharacterDevice("/dev/full"));
}

// Tests that --report and --junit take /dev/stdout alike (issue 32 item 16: --report was
// refused) when stdout is a file: the report follows the lines already printed, /dev/stdout
// stays the link it was (a rename over it would replace it), and /dev/fd/N of a closed
// descriptor is refused before anything runs, naming the cause; as root, also run as
// nobody (who cannot write in /dev).
TEST(IoErrors, ReportAndJunitGoToStandardOutput) {
  const std::string scenario = "configs/scenarios/method1.yaml";
  const CliResult report = RunCli({"check", scenario, "--report", "/dev/stdout"}, kSourceDir);
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_EQ(report.out.rfind("PASS " + scenario, 0), 0u) << report.out.substr(0, 200);
  EXPECT_NE(report.out.find("<!DOCTYPE html>"), std::string::npos);
  EXPECT_EQ(report.out.substr(report.out.size() - 8), "</html>\n");
  const CliResult junit = RunCli({"check", scenario, "--junit", "/dev/stdout"}, kSourceDir);
  ASSERT_EQ(junit.exit_code, 0) << junit.err;
  EXPECT_EQ(junit.out.rfind("PASS " + scenario, 0), 0u);
  EXPECT_NE(junit.out.find("<testsuites"), std::string::npos);
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
  // Not root: /dev is not writable, and the check probed it (the refusal the issue met).
  if (geteuid() == 0 && fs::exists("/usr/bin/setpriv")) {
    ScratchDir dir;
    const std::string command = "cd " + ShellQuoted(kSourceDir) +
                                " && /usr/bin/setpriv --reuid=65534 --regid=65534 --clear-groups " +
                                ShellQuoted(SHAPEBENCH_BINARY) + " check " + scenario + " --report /dev/stdout >" +
                                ShellQuoted(dir.File("out")) + " 2>" + ShellQuoted(dir.File("err"));
    EXPECT_EQ(std::system(command.c_str()), 0) << ReadText(dir.File("err"));
    EXPECT_NE(ReadText(dir.File("out")).find("</html>"), std::string::npos) << ReadText(dir.File("err"));
  }
  const CliResult closed = RunCli({"run", scenario, "--report", "/dev/fd/917"}, kSourceDir);
  EXPECT_EQ(closed.exit_code, 2);
  EXPECT_EQ(closed.err, "error: --report /dev/fd/917: cannot write there: Bad file descriptor\n");
}

// Tests that reading a directory as a file says why: the sweep plots' results.csv and a
// PNG read back (which used to read a directory as an empty file).
TEST(IoErrors, ReadingADirectoryNamesTheCause) {
  ScratchDir dir;
  const std::string results = dir.File("results.csv");
  fs::create_directories(results);
  const Sweep sweep = LoadSweep(DataPath("sweeps/failing_point.yaml"), {});
  try {
    WriteSweepPlots(dir.File("plots"), SweepLayout::Of(sweep), results);
    ADD_FAILURE() << "no error reading a directory";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "cannot read " + results + ": Is a directory");
  }
  EXPECT_EQ(PngDefect(results), "cannot read it back: Is a directory");
  EXPECT_EQ(PngDefect(dir.File("missing.png")), "cannot read it back: No such file or directory");
}

// Tests that a line-buffered FdStreamBuf (stdout on a terminal) writes each line as it
// ends, a fully buffered one only when flushed, and that a failed write keeps its errno.
TEST(IoErrors, FdStreamBufWritesLinesAndKeepsTheErrno) {
  int pipe_fds[2];
  ASSERT_EQ(pipe2(pipe_fds, O_NONBLOCK), 0);
  char text[16] = {};
  {
    FdStreamBuf lines(pipe_fds[1], /*line_buffered=*/true);
    std::ostream out(&lines);
    out << "one" << '\n' << "two";
    EXPECT_EQ(read(pipe_fds[0], text, sizeof text), 4);
    EXPECT_EQ(std::string(text, 4), "one\n");
  }  // the destructor writes "two"
  EXPECT_EQ(read(pipe_fds[0], text, sizeof text), 3);
  {
    FdStreamBuf block(pipe_fds[1]);
    std::ostream out(&block);
    out << "three\n";
    EXPECT_EQ(read(pipe_fds[0], text, sizeof text), -1);  // nothing yet (EAGAIN)
    out.flush();
    EXPECT_EQ(read(pipe_fds[0], text, sizeof text), 6);
    EXPECT_EQ(block.error(), 0);
  }
  close(pipe_fds[0]);
  close(pipe_fds[1]);
  FdStreamBuf closed(-1);  // no descriptor: EBADF, kept
  std::ostream out(&closed);
  out << "x" << std::flush;
  EXPECT_FALSE(out.good());
  EXPECT_EQ(closed.error(), EBADF);
}

// The CLI under a 500 MB address-space cap, where a run that passes the memory guard
// (limits.max_memory_mb raised far above the machine) cannot allocate its command.
CliResult RunCliWithLittleMemory(const std::vector<std::string>& args, const std::string& work_dir) {
  return RunCli(args, work_dir, "prlimit --as=500000000 ");
}

// Tests that running out of memory names what ran and the limit that bounds it, exit 2
// (as the memory guard's refusal), never "std::bad_alloc": in a run, and in a sweep,
// which stops there keeping the rows before (no row for the point, which is not at fault).
TEST(IoErrors, OutOfMemoryNamesTheRunAndItsLimit) {
  // AddressSanitizer's allocator reports and aborts instead of throwing std::bad_alloc,
  // and an address-space cap stops it from starting (bench_test_support.h).
  if (testing::kUnderAddressSanitizer) GTEST_SKIP() << "no std::bad_alloc under AddressSanitizer";
  const std::string scenario = DataPath("shaped_method1.yaml");
  const CliResult run = RunCliWithLittleMemory(
      {"run", scenario, "--set", "controller.period_s=8.7e-8", "--set", "move.distance_mm=30", "--set",
       "limits.max_memory_mb=100000"},
      kSourceDir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(run.err.rfind("error: out of memory while running scenario 'shaped_method1' (" + scenario +
                              "); limits.max_memory_mb is 100000 MB a run, more than this process could get",
                          0),
            0u)
      << run.err;
  EXPECT_EQ(run.err.find("bad_alloc"), std::string::npos) << run.err;

  ScratchDir dir;
  dir.Write("oom.yaml", "base: " + scenario +
                            "\ngrid:\n  controller.period_s: [0.001, 1.0e-8, 0.001]\n"
                            "metrics: [residual_ratio]\nplots: []\n");
  const CliResult sweep = RunCliWithLittleMemory(
      {"sweep", "oom.yaml", "--jobs", "1", "--out", "out", "--set", "move.distance_mm=30", "--set",
       "limits.max_memory_mb=100000", "--set", "limits.max_ticks=1000000000"},
      dir.path().string());
  EXPECT_EQ(sweep.exit_code, 2) << sweep.err;
  EXPECT_EQ(sweep.err.rfind("error: out of memory while running sweep 'oom' (oom.yaml) into out; 1 run at a "
                            "time (--jobs 1), each up to its limits.max_memory_mb",
                            0),
            0u)
      << sweep.err;
  EXPECT_FALSE(fs::exists(dir.File("out/results.csv")));
  const std::string rows = ReadText(dir.File("out/results.csv.partial"));
  const std::string header = "point,controller.period_s,residual_ratio,status,error\n";
  ASSERT_EQ(rows.rfind(header, 0), 0u) << rows;
  const std::string kept = rows.substr(header.size());
  EXPECT_EQ(kept.rfind("0,0.001,", 0), 0u) << rows;  // point 0, and nothing of point 1
  EXPECT_EQ(std::count(kept.begin(), kept.end(), '\n'), 1) << rows;
  EXPECT_NE(kept.find(",ok,\n"), std::string::npos) << rows;
}

}  // namespace
}  // namespace shapebench::bench
