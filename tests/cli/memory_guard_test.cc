// limits.max_memory_mb and the G-code limits: hostile inputs are refused before their
// memory is allocated (docs/reliability.md, guard rails). The CLI runs under an address
// space cap (prlimit), so a run that allocates first and refuses later fails here.
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
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
  EXPECT_NE(result.err.find("more than limits.max_simulated_s allows; reading stopped here"), std::string::npos)
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

}  // namespace
}  // namespace shapebench::bench
