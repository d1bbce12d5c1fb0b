// A valid model whose static deflections cancel (static displacement 0) through the
// built CLI: `run` exits 0 with its ratios n/a, `check` fails a check on a ratio naming why.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::RunCli;

const std::string kCancellingModes = "tests/bench/data/reliability/cancelling_modes.yaml";

// Tests that `run` of the cancelling model (25 Hz gain 0.1, 50 Hz gain -0.4, magnitude
// view, CVODE) exits 0 (it exited 3, NON_FINITE_STATE: peak_ratio overflowed to infinity),
// its table showing the ratios as n/a and the peak deflection, --json giving null ratios
// and a static displacement of 0.
TEST(ZeroStaticCli, RunExitsZeroWithRatiosNotAvailable) {
  const CliResult table = RunCli({"run", kCancellingModes}, kSourceDir);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("\nstatic_displacement_m           0 m\n"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\npeak_ratio                      n/a\n"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\nresidual_ratio                  n/a\n"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\npeak_deflection_m               13.5"), std::string::npos) << table.out;

  const CliResult json = RunCli({"run", kCancellingModes, "--json"}, kSourceDir);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json metrics = nlohmann::json::parse(json.out);
  EXPECT_EQ(metrics["static_displacement_m"], 0.0);
  for (const char* ratio : {"peak_ratio", "residual_ratio", "residual_peak_ratio", "cruise_residual_ratio"}) {
    EXPECT_TRUE(metrics[ratio].is_null()) << ratio;
  }
  EXPECT_GT(metrics["peak_deflection_m"].get<double>(), 1e-5);
  EXPECT_TRUE(metrics["residual_amplitude_m"].is_number());
}

// Tests that `check` of it exits 1: its peak_ratio check fails saying that the ratio is n/a
// because the static displacement is 0, and its check on peak_deflection_m passes.
TEST(ZeroStaticCli, CheckOnARatioFailsNamingTheReason) {
  const CliResult check = RunCli({"check", kCancellingModes}, kSourceDir);
  EXPECT_EQ(check.exit_code, 1) << check.err;
  EXPECT_NE(check.out.find("FAIL " + kCancellingModes +
                           " peak_ratio = n/a (max 2): peak_ratio is n/a because the static displacement is 0"),
            std::string::npos)
      << check.out;
  EXPECT_NE(check.out.find("PASS " + kCancellingModes + " peak_deflection_m = 13.5"), std::string::npos) << check.out;
}

}  // namespace
}  // namespace shapebench::bench
