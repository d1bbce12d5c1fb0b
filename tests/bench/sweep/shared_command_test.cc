// The command a sweep's points share between points and threads
// (bench/sweep/shared_command.h): generated once per distinct controller input, and the
// sweep's results.csv the same bytes as a sweep that generates a command for every point
// (SHAPEBENCH_SHARE_COMMAND=0).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/sweep/shared_command.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

// results.csv of `shapebench sweep FILE --jobs 2`, with or without a shared command.
std::string SweepResults(const std::string& file, bool share, const ScratchDir& dir, const std::string& name) {
  const std::string out = dir.File(name);
  const testing::CliResult run =
      RunCli({"sweep", file, "--jobs", "2", "--out", out}, dir.File(""), share ? "" : "SHAPEBENCH_SHARE_COMMAND=0 ");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return ReadText(out + "/results.csv");
}

// Tests that every shipped sweep, a sweep of controller keys only (no two points share a
// command), a grid of both and a grid over the move (each length its own program and path,
// shared with the command) give results.csv byte for byte the same with and without the
// shared command.
TEST(SharedCommand, ResultsSameWithoutSharing) {
  ScratchDir dir;
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/sweeps")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  ASSERT_GE(files.size(), 2u);
  files.push_back(dir.Write("controller_only.yaml",
                            "base: " + DataPath("sweeps/sdof_method1.yaml") +
                                "\ngrid:\n  controller.accel_time_s: {from: 0.1, to: 0.4, steps: 7}\n"
                                "  controller.pattern.method: [none, 1, 3]\nplots: []\n"));
  files.push_back(dir.Write("damped_mixed.yaml",
                            "base: " + DataPath("sweeps/sdof_method1.yaml") +
                                "\ngrid:\n  machine.modes[0].frequency_hz: {from: 18, to: 32, steps: 15}\n"
                                "  controller.feed_mm_min: [24000, 30000]\n"
                                "  machine.modes[0].damping_ratio: [0, 0.02]\nplots: []\n"));
  files.push_back(dir.Write("move_lengths.yaml",
                            "base: " + DataPath("sweeps/sdof_method1.yaml") +
                                "\ngrid:\n  move.distance_mm: [20, 50, 120]\n"
                                "  machine.modes[0].frequency_hz: {from: 18, to: 32, steps: 8}\nplots: []\n"));
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string shared = SweepResults(files[i], true, dir, "shared" + std::to_string(i));
    const std::string alone = SweepResults(files[i], false, dir, "alone" + std::to_string(i));
    EXPECT_GT(shared.size(), 100u) << files[i];
    EXPECT_EQ(shared, alone) << files[i];
  }
}

// Tests that a grid over the plant only generates one command for all its points and both
// threads, and that a grid over a controller key generates one per distinct value.
TEST(SharedCommand, GeneratedOncePerControllerInput) {
  if (!SharedCommandCache::Enabled()) GTEST_SKIP() << "SHAPEBENCH_SHARE_COMMAND=0 in the environment";
  ScratchDir dir;
  auto generated_by = [&](const std::string& grid, const std::string& name) {
    const std::string path =
        dir.Write(name + ".yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") + "\ngrid:\n" + grid + "plots: []\n");
    const Sweep sweep = LoadSweep(path, {});
    SweepRunOptions options;
    options.out_dir = dir.File(name);
    options.jobs = 2;
    const std::uint64_t before = SharedCommandCache::Instance().generated();
    const SweepRunSummary summary = RunSweep(sweep, {}, options);
    EXPECT_EQ(summary.ok, sweep.points) << name;
    return SharedCommandCache::Instance().generated() - before;
  };
  EXPECT_EQ(generated_by("  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 40}\n"
                         "  machine.modes[0].damping_ratio: [0, 0.02]\n",
                         "plant"),
            1u);
  EXPECT_EQ(generated_by("  controller.accel_time_s: [0.1, 0.2, 0.3]\n"
                         "  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 10}\n",
                         "mixed"),
            3u);
  EXPECT_EQ(generated_by("  controller.accel_time_s: {from: 0.1, to: 0.4, steps: 6}\n", "controller"), 6u);
}

// Tests that the cache hands every caller of one key the same command, generated once, and
// that a generation that throws is not kept: the next caller generates again.
TEST(SharedCommand, FailedGenerationIsNotKept) {
  SharedCommandCache& cache = SharedCommandCache::Instance();
  const std::uint64_t sweep_id = 0xfeedULL << 40;  // no loaded sweep has it
  const std::uint64_t before = cache.generated();
  int calls = 0;
  auto fail = [&](controller::Program*) -> controller::MultiAxisCommand {
    ++calls;
    throw std::runtime_error("no command");
  };
  EXPECT_THROW(cache.Get(sweep_id, "k", fail), std::runtime_error);
  EXPECT_THROW(cache.Get(sweep_id, "k", fail), std::runtime_error);
  EXPECT_EQ(calls, 2);
  auto make = [&](controller::Program*) {
    ++calls;
    controller::MultiAxisCommand command;
    command.period_s = 0.001;
    for (auto& axis : command.axes) axis.velocity_m_s = {0.0, 0.0};  // one tick at rest
    return command;
  };
  const auto first = cache.Get(sweep_id, "k", make);
  const auto second = cache.Get(sweep_id, "k", make);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(first.get(), second.get());
  EXPECT_EQ(cache.generated() - before, 1u);
  EXPECT_NE(cache.Get(sweep_id, "other", make).get(), first.get());
}

}  // namespace
}  // namespace shapebench::bench
