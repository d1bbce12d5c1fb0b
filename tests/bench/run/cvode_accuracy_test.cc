// The promise of docs/accuracy.md: a CVODE run of a linear plant whose ratio metrics are
// further than kCvodeMetricAccuracy from the exact path's is refused (or warned about),
// never reported silently. The oracle is the exact discretisation (matrix exponential) of
// the same plant, run through the same master.
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "model/cvode_cross_check.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

const std::string kScenarios = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/";

struct Setting {
  const char* scenario;
  const char* rtol;
  const char* lmm;
  const char* drive;  // "" keeps the scenario's
};

std::string Name(const ::testing::TestParamInfo<Setting>& info) {
  std::string name = std::string(info.param.scenario) + "_" + info.param.rtol + "_" + info.param.lmm +
                     (*info.param.drive != '\0' ? std::string("_") + info.param.drive : "");
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

double WorstRatioError(const Metrics& a, const Metrics& b) {
  double worst = 0.0;
  for (auto field : {&Metrics::peak_ratio, &Metrics::residual_ratio, &Metrics::cruise_residual_ratio}) {
    if (std::isnan(a.*field) && std::isnan(b.*field)) continue;
    worst = std::max(worst, std::abs(a.*field - b.*field));
  }
  return worst;
}

class AccuracyPromise : public ::testing::TestWithParam<Setting> {};

// Tests that at this setting the CVODE run either is refused by the cross-check
// (CROSS_CHECK_FAILED) or has its peak, residual and cruise-residual ratios within
// kCvodeMetricAccuracy of the exact path's.
TEST_P(AccuracyPromise, RefusedOrWithinTheDocumentedAccuracy) {
  const Setting& s = GetParam();
  std::vector<Override> cvode = {{"integrator.method", "cvode"}, {"integrator.rtol", s.rtol},
                                 {"integrator.lmm", s.lmm}};
  std::vector<Override> exact = {{"integrator.method", "exact"}};
  if (*s.drive != '\0') {
    cvode.push_back({"drive.type", s.drive});
    exact.push_back({"drive.type", s.drive});
  }
  const std::string file = kScenarios + s.scenario + ".yaml";
  const RunResult reference = RunScenario(LoadScenario(file, exact), RunOptions{false});
  try {
    const RunResult run = RunScenario(LoadScenario(file, cvode), RunOptions{false});
    EXPECT_LE(WorstRatioError(run.metrics, reference.metrics), model::kCvodeMetricAccuracy)
        << "a wrong number the cross-check let through";
  } catch (const model::SolverError& error) {
    EXPECT_EQ(error.flag_name(), "CROSS_CHECK_FAILED") << error.what();
  }
}

std::vector<Setting> Settings() {
  std::vector<Setting> settings;
  for (const char* scenario : {"method1", "method3_mode_start", "exponential", "fig2_pulse", "long_step",
                               "pocket_corner", "stroke_end"}) {
    for (const char* rtol : {"1e-6", "3e-7", "1e-7", "3e-8", "1e-8"}) {
      for (const char* lmm : {"adams", "bdf"}) settings.push_back({scenario, rtol, lmm, ""});
    }
  }
  for (const char* rtol : {"1e-6", "1e-7", "1e-8"}) {
    for (const char* lmm : {"adams", "bdf"}) settings.push_back({"pocket_corner", rtol, lmm, "servo"});
  }
  return settings;
}

INSTANTIATE_TEST_SUITE_P(ShippedScenarios, AccuracyPromise, ::testing::ValuesIn(Settings()), Name);

// Tests that the shipped scenarios' own integrator settings pass the cross-check (a refusal
// there would be a false alarm on the settings the docs recommend).
TEST(CrossCheck, ShippedSettingsPass) {
  for (const char* name : {"method1", "method2", "method3", "method4", "exponential", "fig2_pulse", "long_step",
                           "pocket_corner", "pocket_gcode", "stroke_end", "um_zv"}) {
    const Scenario scenario = LoadScenario(kScenarios + name + ".yaml", {{"integrator.method", "cvode"}});
    const RunResult run = RunScenario(scenario, RunOptions{false});
    EXPECT_TRUE(run.warnings.empty()) << name;
  }
}

// Tests that a 1e6 Hz mode at the 1 ms period under Adams (before: residual 1058 against
// 0.25 exact, after 20 s) is refused by the cross-check, naming BDF as a way out.
TEST(CrossCheck, StiffModeUnderAdamsIsRefused) {
  const std::string file = std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/bench/data/accuracy/stiff_mode.yaml";
  try {
    RunScenario(LoadScenario(file, {{"integrator.lmm", "adams"}}), RunOptions{false});
    ADD_FAILURE() << "no refusal";
  } catch (const model::SolverError& error) {
    EXPECT_EQ(error.flag_name(), "CROSS_CHECK_FAILED");
    EXPECT_NE(std::string(error.what()).find("integrator.lmm: bdf"), std::string::npos) << error.what();
  }
}

// Tests that under `integrator.cross_check: warn` a failing check runs, with the check's
// message as a warning, and that `off` runs without one.
TEST(CrossCheck, WarnRunsWithTheMessageAndOffIsSilent) {
  const std::string file = kScenarios + "method1.yaml";
  const RunResult warned = RunScenario(
      LoadScenario(file, {{"integrator.method", "cvode"}, {"integrator.rtol", "1e-6"}, {"integrator.cross_check", "warn"}}),
      RunOptions{false});
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_NE(warned.warnings[0].find("disagrees with the exact discretisation"), std::string::npos);
  const RunResult off = RunScenario(
      LoadScenario(file, {{"integrator.method", "cvode"}, {"integrator.rtol", "1e-6"}, {"integrator.cross_check", "off"}}),
      RunOptions{false});
  EXPECT_TRUE(off.warnings.empty());
  EXPECT_EQ(std::memcmp(&off.metrics.peak_ratio, &warned.metrics.peak_ratio, sizeof(double)), 0)
      << "the check does not change the run";
}

// Tests the reproductions of the review at the command line: rtol 1e-2 (peak_ratio 37.2
// against 1.04) is refused as bad input naming the allowed range; the servo-driven pocket
// corner at rtol 1e-6 exits 3 with CROSS_CHECK_FAILED.
TEST(CrossCheckCli, LooseTolerancesAreRefused) {
  const auto loose = testing::RunCli({"run", "configs/demo.yaml", "--set", "integrator.rtol=1e-2"},
                                     SHAPEBENCH_SOURCE_DIR);
  EXPECT_EQ(loose.exit_code, 2) << loose.err;
  EXPECT_NE(loose.err.find("integrator.rtol: must be in [1e-12, 1e-6]"), std::string::npos) << loose.err;
  const auto servo = testing::RunCli({"run", "configs/scenarios/pocket_corner.yaml", "--set", "drive.type=servo",
                                      "--set", "integrator.rtol=1e-6"},
                                     SHAPEBENCH_SOURCE_DIR);
  EXPECT_EQ(servo.exit_code, 3) << servo.err;
  EXPECT_NE(servo.err.find("error: solver failed: CROSS_CHECK_FAILED: "), std::string::npos) << servo.err;
  EXPECT_EQ(servo.out, "") << "no metrics printed";
}

// Tests that a default rtol (the scenario leaves `rtol` out) is tightened where it fails
// the cross-check, and a written one is not (issue 32 item 11): the demo at period_s 1e-5
// is refused under the default 1e-8 (1.7e-5 on the pulse, 1.9e-4 projected over the run,
// against 5e-5); it now runs at a tighter rtol it reports, its ratio metrics within
// kCvodeMetricAccuracy of the exact path's (what a passed cross-check promises), while the
// same run with `integrator.rtol: 1e-8` written is still refused. (The other
// reproduction, exponential.yaml at 1e-4, passes at 1e-8 on this main: the check pulse
// changed since it was filed.)
TEST(CrossCheck, DefaultRtolIsTightenedWhereItFailsAndAWrittenOneIsNot) {
  const std::string file = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/demo.yaml";
  const Scenario shipped = LoadScenario(file, {});
  EXPECT_FALSE(shipped.integrator.rtol_given);
  EXPECT_TRUE(LoadScenario(file, {{"integrator.rtol", "1e-8"}}).integrator.rtol_given);
  EXPECT_EQ(RunScenario(shipped, RunOptions{false}).integrator_rtol_used, 1e-8);  // passes as it is

  const RunResult tightened = RunScenario(LoadScenario(file, {{"controller.period_s", "1e-5"}}), RunOptions{false});
  EXPECT_LT(tightened.integrator_rtol_used, 1e-8);
  EXPECT_GE(tightened.integrator_rtol_used, model::kTightestRtol);
  EXPECT_TRUE(tightened.warnings.empty());
  const RunResult exact = RunScenario(
      LoadScenario(file, {{"controller.period_s", "1e-5"}, {"integrator.method", "exact"}}), RunOptions{false});
  EXPECT_TRUE(std::isnan(exact.integrator_rtol_used));
  EXPECT_LE(WorstRatioError(tightened.metrics, exact.metrics), model::kCvodeMetricAccuracy);

  try {
    RunScenario(LoadScenario(file, {{"controller.period_s", "1e-5"}, {"integrator.rtol", "1e-8"}}), RunOptions{false});
    ADD_FAILURE() << "a written rtol 1e-8 was tightened";
  } catch (const model::SolverError& error) {
    EXPECT_EQ(error.flag_name(), "CROSS_CHECK_FAILED");
    EXPECT_EQ(std::string(error.what()).find("tightened"), std::string::npos) << error.what();
  }
}

// Tests that `run` reports the rtol CVODE ran with, in its table and its JSON, and null
// (no table line) on the exact path.
TEST(CrossCheckCli, RunReportsTheRtolUsed) {
  const auto table = testing::RunCli({"run", "configs/demo.yaml"}, SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("\nintegrator_rtol_used            1e-08\n"), std::string::npos) << table.out;
  const auto json = testing::RunCli({"run", "configs/demo.yaml", "--json", "--set", "integrator.rtol=1e-9"},
                                    SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\n  \"integrator_rtol_used\": 1e-09,\n")  /* the *_source keys follow */, std::string::npos) << json.out;
  const auto exact = testing::RunCli({"run", "configs/demo.yaml", "--set", "integrator.method=exact"},
                                     SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_EQ(exact.out.find("integrator_rtol_used"), std::string::npos) << exact.out;
}

}  // namespace
}  // namespace shapebench::bench
