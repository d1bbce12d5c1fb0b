// limits.max_memory_mb and the G-code limits: hostile inputs are refused before their
// memory is allocated (docs/reliability.md, guard rails). The CLI runs under an address
// space cap (prlimit), so a run that allocates first and refuses later fails here.
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/run_memory.h"
#include "tests/support/bench_test_support.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::ScratchDir;
using testing::ShellQuoted;

constexpr const char* kAddressSpaceCap = "1500000000";  // bytes, for the CLI's whole process

// Runs the CLI under `prlimit --as=kAddressSpaceCap`, capturing stdout and stderr. Under
// AddressSanitizer an address-space cap stops the sanitizer itself from starting: its RSS
// limit bounds the child instead (bench_test_support.h, kUnderAddressSanitizer).
CliResult RunCliCapped(const std::vector<std::string>& args) {
  const std::string cap = testing::kUnderAddressSanitizer
                              ? "ASAN_OPTIONS=\"$ASAN_OPTIONS:hard_rss_limit_mb=" +
                                    std::to_string(std::stoull(kAddressSpaceCap) >> 20) + "\" "
                              : std::string("prlimit --as=") + kAddressSpaceCap + " ";
  return testing::RunCli(args, kSourceDir, cap);
}

// Tests that a G-code file of five million short lines (X1 / X0, the path far longer
// than limits allow) is refused while it is parsed: exit 2, quickly, under a 1.5 GB
// address space cap, located at the line where reading stopped and naming the limit.
TEST(MemoryGuard, HugeGcodeProgramIsRefusedWhileParsing) {
  ScratchDir dir;
  {
    std::ofstream gcode(dir.File("big.nc"));
    gcode << "G90 G1 F6000\n";
    for (int i = 0; i < 2'500'000; ++i) gcode << "X1\nX0\n";
  }
  const std::string scenario = dir.Write("big.yaml", "drive: {type: kinematic}\nprogram_file: big.nc\n");
  const auto start = std::chrono::steady_clock::now();
  const CliResult result = RunCliCapped({"run", scenario, "--out", dir.File("o")});
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find(dir.File("big.nc") + ":"), std::string::npos) << result.err;
  // The binding limit: the memory budget's ticks (2983 s at 1 ms) before 4 hours of max_simulated_s.
  EXPECT_NE(result.err.find("more than limits.max_memory_mb allows; reading stopped here"), std::string::npos)
      << result.err;

  // A block cap from the memory budget stops a program of zero-time blocks (G4 P0) too.
  {
    std::ofstream gcode(dir.File("still.nc"));
    for (int i = 0; i < 2'000'000; ++i) gcode << "G4 P0\n";
  }
  const std::string still = dir.Write("still.yaml", "drive: {type: kinematic}\nprogram_file: still.nc\n");
  const CliResult blocks = RunCliCapped({"run", still, "--set", "limits.max_memory_mb=64"});
  EXPECT_EQ(blocks.exit_code, 2) << blocks.err;
  EXPECT_NE(blocks.err.find("blocks by this line, more than limits.max_memory_mb"), std::string::npos)
      << blocks.err;
}

// Tests that a tiny interpolation period within limits.max_ticks but beyond the memory
// budget is refused at load (exit 2, under the 1.5 GB cap) naming limits.max_memory_mb,
// and that raising the budget lets the load pass the memory check.
TEST(MemoryGuard, TinyPeriodBeyondTheMemoryBudgetIsRefused) {
  const std::string scenario = DataPath("shaped_method1.yaml");
  const auto start = std::chrono::steady_clock::now();
  const CliResult result =
      RunCliCapped({"run", scenario, "--set", "controller.period_s=8.7e-8", "--set", "move.distance_mm=30"});
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("limits.max_memory_mb: scenario 'shaped_method1' would need at least "),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("more than limits.max_memory_mb (1024 MB a run"), std::string::npos) << result.err;

  const CliResult bad = RunCliCapped({"run", scenario, "--set", "limits.max_memory_mb=0"});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("limits.max_memory_mb: must be >= 1"), std::string::npos) << bad.err;
}

// Tests that a run given without the loader (as a sweep's points are) is still refused on
// its planned length before the per-tick command is allocated, naming limits.max_memory_mb.
TEST(MemoryGuard, PlannedCommandBeyondTheBudgetIsRefusedBeforeInterpolating) {
  Scenario scenario;
  scenario.drive.type = model::DriveType::kKinematic;
  scenario.move.distance_mm = 1000.0;
  scenario.limits.max_memory_mb = 1;  // about 2,900 periods; the move takes more
  try {
    RunScenario(scenario, RunOptions{false});
    ADD_FAILURE() << "no ValidationError";
  } catch (const ValidationError& error) {
    EXPECT_EQ(error.field(), "limits.max_memory_mb");
    EXPECT_NE(std::string(error.what()).find("the command takes "), std::string::npos) << error.what();
  }
  scenario.limits.max_memory_mb = 1024;
  EXPECT_NO_THROW(RunScenario(scenario, RunOptions{false}));
}

// The peak resident memory (bytes) of one CLI run, from its own rusage (wait4).
double PeakResidentBytes(const std::vector<std::string>& args) {
  const pid_t pid = testing::SpawnCli(args, kSourceDir);
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1.0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // kB on Linux
}

// A zig-zag of `passes` 100 mm lines along Y, 1 mm apart, at 6000 mm/min (about 1 s a pass).
std::string ZigZagScenario(const ScratchDir& dir, const std::string& name, int passes) {
  std::string gcode = "G21 G90 G1 F6000\n";
  for (int i = 0; i < passes; ++i) {
    gcode += "Y" + std::string(i % 2 == 0 ? "100" : "0") + " X" + std::to_string(i + 1) + "\n";
  }
  dir.Write(name + ".nc", gcode + "M30\n");
  return dir.Write(name + ".yaml", "machine: {modes: [{frequency_hz: 25, damping_ratio: 0.02, gain: 1}], rigid: [x]}\n"
                                   "drive: {type: kinematic}\n"
                                   "controller: {feed_mm_min: 6000, accel_time_s: 0.05}\n"
                                   "program_file: " + name + ".nc\n");
}

// Tests that limits.max_memory_mb's estimate per interpolation period
// (bench/scenario/run_memory.h kRunBytesPerTick, the trace counted at one sample a period)
// bounds what a run without a trace measurably uses: the peak resident memory of `run`
// (no --out: no trace) grows from a 40 s to a 160 s program (at least 120,000 more periods)
// by at most the estimate per added period (about 116 bytes measured; a traced run's, about
// 1.06 KB, is stated in docs/reliability.md, not bounded).
TEST(MemoryGuard, EstimatePerPeriodBoundsTheMeasuredUse) {
  ScratchDir dir;
  const std::string small = ZigZagScenario(dir, "small", 40);
  const std::string large = ZigZagScenario(dir, "large", 160);
  const double small_bytes = PeakResidentBytes({"run", small, "--json"});
  const double large_bytes = PeakResidentBytes({"run", large, "--json"});
  ASSERT_GT(small_bytes, 0.0);
  ASSERT_GT(large_bytes, 0.0);
  constexpr double kAddedPeriods = 120'000.0;  // 120 passes of about 1 s
  const double per_period = (large_bytes - small_bytes) / kAddedPeriods;
  std::cout << "untraced: " << per_period << " bytes a period (estimate " << kRunBytesPerTick << ")\n";
  EXPECT_LE(per_period, kRunBytesPerTick);
  EXPECT_GT(per_period, 0.25 * (kCommandBytesPerTick + kSampleBytesPerTick));  // the measure measures
}
}  // namespace
}  // namespace shapebench::bench
