// Outputs that appear complete or not at all: PNGs checked before they are committed,
// `run --out` directories filled under a temporary name, temporary files of killed
// processes cleaned up by the next write.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bench/output/gnuplot.h"
#include "tests/support/bench_test_support.h"
#include "common/atomic_file.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;
using testing::ShellQuoted;


// A minimal PNG byte by byte: signature, IHDR of a 1x1 grey image, IDAT, IEND (CRCs as
// checked with zlib.crc32).
std::string MinimalPng() {
  const unsigned char bytes[] = {
      0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',
      0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 1, 0, 0, 0, 1, 8, 0, 0, 0, 0, 0x3a, 0x7e, 0x9b, 0x55,
      0, 0, 0, 10, 'I', 'D', 'A', 'T', 0x78, 0x9c, 0x63, 0x60, 0, 0, 0, 2, 0, 1, 0x48, 0xaf, 0xa4, 0x71,
      0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  return std::string(reinterpret_cast<const char*>(bytes), sizeof(bytes));
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Names of entries in `dir` that say they are temporary.
std::size_t TempEntries(const std::filesystem::path& dir) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    count += entry.path().filename().string().find(".tmp.") != std::string::npos ? 1 : 0;
  }
  return count;
}

// A PID no process has: a child that has exited and been reaped.
pid_t DeadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

// Tests that the PNG check accepts a whole PNG and names what is wrong with one cut short
// (the disk filled while gnuplot wrote it), one with no signature and an empty one.
TEST(AtomicOutput, PngCheckFindsATruncatedFile) {
  ScratchDir dir;
  const std::string png = MinimalPng();
  WriteBytes(dir.File("whole.png"), png);
  WriteBytes(dir.File("cut.png"), png.substr(0, png.size() - 5));
  WriteBytes(dir.File("text.png"), "set terminal png\n" + png.substr(8));
  WriteBytes(dir.File("empty.png"), "");
  EXPECT_EQ(PngDefect(dir.File("whole.png")), "");
  EXPECT_NE(PngDefect(dir.File("cut.png")).find("truncated"), std::string::npos);
  EXPECT_NE(PngDefect(dir.File("text.png")).find("no PNG signature"), std::string::npos);
  EXPECT_NE(PngDefect(dir.File("empty.png")), "");
  EXPECT_NE(PngDefect(dir.File("missing.png")), "");
}

// Tests that committing a truncated PNG is refused with a message naming the file and
// leaves nothing under the final name (nor the temporary file), and a whole one commits.
TEST(AtomicOutput, CommitRefusesATruncatedPng) {
  ScratchDir dir;
  const std::string final_path = dir.File("plot.png");
  {
    TempFile temp(final_path);
    WriteBytes(temp.path(), MinimalPng().substr(0, 40));
    try {
      CommitPng(temp, final_path);
      ADD_FAILURE() << "a truncated PNG was committed";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(final_path), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
    }
  }
  EXPECT_FALSE(std::filesystem::exists(final_path));
  EXPECT_EQ(TempEntries(dir.path()), 0u);
  {
    TempFile temp(final_path);
    WriteBytes(temp.path(), MinimalPng());
    CommitPng(temp, final_path);
  }
  EXPECT_EQ(ReadText(final_path), MinimalPng());
}

// Tests that a PNG gnuplot leaves cut short while exiting 0 (as when the disk fills) is not
// committed by RunGnuplot: it throws, nothing appears under the final name.
TEST(AtomicOutput, RunGnuplotRefusesATruncatedPlot) {
  ScratchDir dir;
  const std::string final_path = dir.File("cut.png");
  EXPECT_THROW(RunGnuplot(final_path,
                          [](std::FILE* gnuplot, const std::string& output_path) {
                            std::fprintf(gnuplot, "set terminal png\nset output %s\nplot x\nunset output\n",
                                         GnuplotQuoted(output_path).c_str());
                            std::fprintf(gnuplot, "system %s\n",
                                         GnuplotQuoted("truncate -s 100 " + ShellQuoted(output_path)).c_str());
                          }),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(final_path));
  EXPECT_EQ(TempEntries(dir.path()), 0u);
}

// Tests that a write into a directory removes temporary files and directories left there by
// a process that no longer exists (killed by SIGKILL), and keeps those of a live process
// (this one) and files that only look alike.
TEST(AtomicOutput, StaleTempFilesOfDeadProcessesAreRemoved) {
  ScratchDir dir;
  const std::string dead = std::to_string(DeadPid());
  const std::string live = std::to_string(getpid());
  dir.Write(".results.csv.tmp." + dead + ".AbC123", "half");
  dir.Write(".tmp." + dead + ".Zz9Zz9", "half");
  dir.Write(".out.tmp." + dead + ".q1w2e3/metrics.json", "{}");
  dir.Write(".results.csv.tmp." + live + ".XyZ789", "mine");
  dir.Write(".notes.tmp.keep", "not ours");
  dir.Write("data.tmp." + dead + ".AbC123", "not hidden");
  WriteFileAtomically(dir.File("results.csv"), [](std::ostream& out) { out << "a\n"; });
  EXPECT_FALSE(std::filesystem::exists(dir.File(".results.csv.tmp." + dead + ".AbC123")));
  EXPECT_FALSE(std::filesystem::exists(dir.File(".tmp." + dead + ".Zz9Zz9")));
  EXPECT_FALSE(std::filesystem::exists(dir.File(".out.tmp." + dead + ".q1w2e3")));
  EXPECT_TRUE(std::filesystem::exists(dir.File(".results.csv.tmp." + live + ".XyZ789")));
  EXPECT_TRUE(std::filesystem::exists(dir.File(".notes.tmp.keep")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("data.tmp." + dead + ".AbC123")));
  EXPECT_EQ(ReadText(dir.File("results.csv")), "a\n");
}

// Tests that a temporary file carries the writer's PID in its name, so a later write can
// tell whether its owner still runs.
TEST(AtomicOutput, TempNamesCarryThePid) {
  ScratchDir dir;
  TempFile temp(dir.File("x.csv"));
  const std::string name = std::filesystem::path(temp.path()).filename().string();
  EXPECT_EQ(name.rfind(".x.csv.tmp." + std::to_string(getpid()) + ".", 0), 0u) << name;
}

// Tests that `run --out DIR` whose plotting fails (no gnuplot on PATH) exits non-zero and
// leaves no DIR behind (not even metrics.json and trace.csv), nor a temporary directory,
// and its message names DIR/deflection.png, not the temporary name.
TEST(AtomicOutput, FailedRunOutLeavesNoDirectory) {
  ScratchDir dir;
  const std::string out = dir.File("out");
  const std::string command = "cd " + ShellQuoted(kSourceDir) + " && PATH=" + ShellQuoted(dir.File("no-bin")) +
                              " " + ShellQuoted(SHAPEBENCH_BINARY) + " run " +
                              ShellQuoted(DataPath("shaped_method1.yaml")) + " --out " + ShellQuoted(out) +
                              " >/dev/null 2>" + ShellQuoted(dir.File("err.txt"));
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0);
  const std::string err = ReadText(dir.File("err.txt"));
  EXPECT_NE(err.find("cannot write " + out + "/deflection.png: gnuplot failed"), std::string::npos) << err;
  EXPECT_EQ(err.find(".tmp."), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(TempEntries(dir.path()), 0u);
}

// Tests that a good `run --out DIR` gives the whole DIR (four files, no temporary entries
// beside it), and that into an existing directory it adds its files and keeps the others.
TEST(AtomicOutput, GoodRunOutGivesTheWholeDirectory) {
  ScratchDir dir;
  const std::string out = dir.File("out");
  const CliResult r = RunCli({"run", DataPath("shaped_method1_xy.yaml"), "--out", out}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"metrics.json", "trace.csv", "deflection.png", "path.png"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + name)) << name;
  }
  EXPECT_EQ(PngDefect(out + "/path.png"), "");
  EXPECT_EQ(TempEntries(dir.path()), 0u);
  EXPECT_EQ(TempEntries(out), 0u);
  const std::string kept = dir.Write("existing/notes.txt", "mine");
  const CliResult again = RunCli({"run", DataPath("shaped_method1.yaml"), "--out", dir.File("existing")}, kSourceDir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(ReadText(kept), "mine");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.File("existing/metrics.json")));
}

}  // namespace
}  // namespace shapebench::bench
