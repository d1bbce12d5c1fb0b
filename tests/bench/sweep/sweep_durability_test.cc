// How a sweep's files reach the disk (common/atomic_file.h's Durability): synced by
// default (the manifest, its directory and the rows: three syncs), not at all with
// `sweep --no-sync`, and the same bytes either way.
#include <cstdint>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "tests/support/bench_test_support.h"
#include "common/atomic_file.h"
#include "tests/support/sweep_file.h"

namespace shapebench::bench {
namespace {

using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;
using testing::SweepFile;

constexpr const char* kGrid = "grid:\n  machine.modes[0].frequency_hz: {from: 20, to: 30, steps: 9}\nplots: []\n";

// Tests that a synced write syncs the file and then its directory, and an unsynced one
// neither, with the same bytes and no temporary file left beside it.
TEST(Durability, AtomicWriteSyncsFileAndDirectoryOrNothing) {
  ScratchDir dir;
  const std::uint64_t before = SyncCount();
  WriteFileAtomically(dir.File("synced.txt"), [](std::ostream& out) { out << "rows\n"; });
  EXPECT_EQ(SyncCount() - before, 2u);
  const std::uint64_t middle = SyncCount();
  WriteFileAtomically(dir.File("unsynced.txt"), [](std::ostream& out) { out << "rows\n"; }, Durability::kUnsynced);
  EXPECT_EQ(SyncCount() - middle, 0u);
  EXPECT_EQ(ReadText(dir.File("synced.txt")), "rows\n");
  EXPECT_EQ(ReadText(dir.File("unsynced.txt")), "rows\n");
  int entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.File(""))) {
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
    ++entries;
  }
  EXPECT_EQ(entries, 2);
}

// The syncs a fresh sweep made, and its manifest and results.
struct SweepFiles {
  std::uint64_t syncs = 0;
  std::string manifest;
  std::string results;
};

SweepFiles RunInto(const Sweep& sweep, const std::string& out, int jobs, Durability durability) {
  SweepRunOptions options;
  options.out_dir = out;
  options.jobs = jobs;
  options.durability = durability;
  const std::uint64_t before = SyncCount();
  const SweepRunSummary summary = RunSweep(sweep, {}, options);
  EXPECT_EQ(summary.ok, sweep.points);
  return {SyncCount() - before, ReadText(out + "/manifest.json"), ReadText(out + "/results.csv")};
}

// Tests that a fresh sweep syncs its manifest, the manifest's directory and its rows
// (three syncs), then results.mat and its directory (two), on one job and on two (where
// the manifest is written by the calling thread), that kUnsynced syncs none, and that both
// write the same bytes.
TEST(Durability, SweepSyncsFiveTimesOrNeverWithTheSameBytes) {
  const SweepFile file(kGrid);
  const Sweep sweep = file.Load();
  ScratchDir dir;
  for (const int jobs : {1, 2}) {
    const std::string tag = std::to_string(jobs);
    const SweepFiles synced = RunInto(sweep, dir.File("synced" + tag), jobs, Durability::kSynced);
    const SweepFiles unsynced = RunInto(sweep, dir.File("unsynced" + tag), jobs, Durability::kUnsynced);
    EXPECT_EQ(synced.syncs, 5u) << jobs << " jobs";
    EXPECT_EQ(unsynced.syncs, 0u) << jobs << " jobs";
    EXPECT_EQ(unsynced.manifest, synced.manifest);
    EXPECT_EQ(unsynced.results, synced.results);
    EXPECT_NE(synced.results.find("\n8,"), std::string::npos) << "nine points, the last numbered 8";
  }
}

// Tests that `sweep --no-sync` writes the same manifest.json and results.csv as `sweep`,
// and that a --no-sync sweep run again finds them finished (it resumes as any sweep does).
TEST(Durability, NoSyncFlagSameFilesAndResumes) {
  const SweepFile file(kGrid);
  ScratchDir dir;
  const testing::CliResult synced = RunCli({"sweep", file.path(), "--jobs", "2", "--out", dir.File("a")}, dir.File(""));
  ASSERT_EQ(synced.exit_code, 0) << synced.err;
  const testing::CliResult unsynced =
      RunCli({"sweep", file.path(), "--jobs", "2", "--no-sync", "--out", dir.File("b")}, dir.File(""));
  ASSERT_EQ(unsynced.exit_code, 0) << unsynced.err;
  EXPECT_EQ(ReadText(dir.File("b/results.csv")), ReadText(dir.File("a/results.csv")));
  EXPECT_EQ(ReadText(dir.File("b/manifest.json")), ReadText(dir.File("a/manifest.json")));
  const testing::CliResult again =
      RunCli({"sweep", file.path(), "--no-sync", "--out", dir.File("b")}, dir.File(""));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("(9 done before)"), std::string::npos) << again.out;
}

}  // namespace
}  // namespace shapebench::bench
