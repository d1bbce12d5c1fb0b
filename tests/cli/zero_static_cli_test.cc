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
// and a static displacement of 0, and a peak deflection that the exact discretisation of
// the same model confirms (within 1e-5 of it: CVODE at its default rtol 1e-8 tracks the
// exact solution to ~1e-6 of the largest deflection, cvode_integrator_test.cc).
TEST(ZeroStaticCli, RunExitsZeroWithRatiosNotAvailable) {
  const CliResult table = RunCli({"run", kCancellingModes}, kSourceDir);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("\nstatic_displacement_m           0 m\n"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\npeak_ratio                      n/a\n"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\nresidual_ratio                  n/a\n"), std::string::npos) << table.out;
  const std::size_t peak_line = table.out.find("\npeak_deflection_m ");
  ASSERT_NE(peak_line, std::string::npos) << table.out;
  const std::string peak_shown = table.out.substr(peak_line + 1, table.out.find('\n', peak_line + 1) - peak_line - 1);
  EXPECT_NE(peak_shown.find(" um"), std::string::npos) << peak_shown;

  const CliResult json = RunCli({"run", kCancellingModes, "--json"}, kSourceDir);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json metrics = nlohmann::json::parse(json.out);
  EXPECT_EQ(metrics["static_displacement_m"], 0.0);
  for (const char* ratio : {"peak_ratio", "residual_ratio", "residual_peak_ratio", "cruise_residual_ratio"}) {
    EXPECT_TRUE(metrics[ratio].is_null()) << ratio;
  }
  EXPECT_TRUE(metrics["residual_amplitude_m"].is_number());
  const CliResult exact = RunCli({"run", kCancellingModes, "--json", "--set", "integrator.method=exact"}, kSourceDir);
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const double exact_peak = nlohmann::json::parse(exact.out)["peak_deflection_m"].get<double>();
  EXPECT_GT(exact_peak, 0.0);
  EXPECT_NEAR(metrics["peak_deflection_m"].get<double>(), exact_peak, 1e-5 * exact_peak);
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
  EXPECT_NE(check.out.find("PASS " + kCancellingModes + " peak_deflection_m = "), std::string::npos) << check.out;
}

}  // namespace
}  // namespace shapebench::bench
