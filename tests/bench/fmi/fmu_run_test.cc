// Whole runs with the test plant FMU as the machine (machine: {fmu: ...}): the metrics the
// native run of the same single mode gives, the n/a metrics of an FMU without documented
// outputs, and the load-time errors located at their keys.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/fmi/fmu_machine.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/test_fmu.h"

namespace shapebench::bench::fmu_run_test {
namespace {

using testing::ScratchDir;
using testing::TestPlantFmu;
using testing::TestPlantScenario;

Metrics RunFile(const std::string& path, const std::vector<Override>& overrides, RunResult* out = nullptr) {
  RunResult result = RunScenario(LoadScenario(path, overrides));
  if (out != nullptr) *out = result;
  return result.metrics;
}

// Tests that `machine: {fmu: FILE}` alone (the variables found by the default names), FMI
// 2.0 and 3.0, gives the native exact run of the same mode {25 Hz, 0.03, gain 1}: static
// displacement, peak (the step peaks carry the in-tick tops) and residual amplitude within
// 1e-9 of the static displacement, the deflection at every tick of the motion within 1e-12
// of it, and no warning.
TEST(FmuRun, DefaultNamesGiveTheNativeSingleModeRun) {
  ScratchDir dir;
  const std::string native = dir.Write("native.yaml", TestPlantScenario("{modes: [{frequency_hz: 25, damping_ratio: 0.03, gain: 1}]}"));
  RunResult native_result;
  const Metrics want = RunFile(native, {}, &native_result);
  for (int version : {2, 3}) {
    const std::string path = dir.Write("fmu" + std::to_string(version) + ".yaml",
                                       TestPlantScenario("{fmu: " + TestPlantFmu(version) + "}"));
    RunResult result;
    const Metrics got = RunFile(path, {}, &result);
    const double scale = want.static_displacement_m;
    ASSERT_GT(scale, 0.0);
    EXPECT_NEAR(got.static_displacement_m, want.static_displacement_m, 1e-9 * scale) << version;
    EXPECT_NEAR(got.peak_deflection_m, want.peak_deflection_m, 1e-9 * scale) << version;
    EXPECT_NEAR(got.peak_ratio, want.peak_ratio, 1e-9) << version;
    EXPECT_NEAR(got.residual_amplitude_m, want.residual_amplitude_m, 1e-9 * scale) << version;
    EXPECT_NEAR(got.residual_ratio, want.residual_ratio, 1e-9) << version;
    EXPECT_EQ(got.motion_time_s, want.motion_time_s);
    EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
    const std::size_t motion = static_cast<std::size_t>(std::lround(want.motion_time_s / 1e-3));
    ASSERT_GT(result.trace.time_s.size(), motion);
    ASSERT_GT(native_result.trace.time_s.size(), motion);
    double worst = 0.0;
    for (std::size_t i = 0; i <= motion; ++i) {
      EXPECT_EQ(result.trace.time_s[i], native_result.trace.time_s[i]);
      worst = std::max(worst, std::abs(result.trace.deflection_m[i] - native_result.trace.deflection_m[i]));
    }
    EXPECT_LE(worst, 1e-12 * scale) << version;
  }
}

// Tests that an explicit mapping of the deflection alone (on axis x, the move along x)
// runs, with static_displacement_m, the ratios, settling_time_s and the residual amplitude
// n/a and a warning naming each reason, the peak deflection as the native run's from the
// communication points only (within 2% of it: no in-step tops).
TEST(FmuRun, WithoutDocumentedOutputsTheirMetricsAreNotAvailable) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "mapped.yaml",
      TestPlantScenario("{fmu: " + TestPlantFmu(2) +
                        ", inputs: {x: base_accel_y}, outputs: {deflection: {x: deflection_y}}}"));
  RunResult result;
  const Metrics got = RunFile(path, {}, &result);
  EXPECT_TRUE(std::isnan(got.static_displacement_m));
  EXPECT_TRUE(std::isnan(got.peak_ratio));
  EXPECT_TRUE(std::isnan(got.settling_time_s));
  EXPECT_TRUE(std::isnan(got.residual_amplitude_m));
  EXPECT_GT(got.peak_deflection_x_m, 0.0);
  EXPECT_EQ(got.peak_deflection_y_m, 0.0);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_NE(result.warnings[0].find("maps no static_compliance output"), std::string::npos) << result.warnings[0];
  EXPECT_NE(result.warnings[1].find("maps no residual_amplitude output"), std::string::npos) << result.warnings[1];
  const std::string native =
      dir.Write("native.yaml", TestPlantScenario("{modes: [{frequency_hz: 25, damping_ratio: 0.03, gain: 1}]}"));
  const Metrics want = RunFile(native, {});
  EXPECT_NEAR(got.peak_deflection_m, want.peak_deflection_m, 0.02 * want.peak_deflection_m);
}

// Tests that machine.fmu_parameters.NAME is a key --set takes: a stiffness four times the
// default quarters the static displacement (m/k), and the run differs from the default's.
TEST(FmuRun, FmuParametersTakeSet) {
  ScratchDir dir;
  const std::string path = dir.Write("fmu.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(3) + "}"));
  const Metrics base = RunFile(path, {});
  const Metrics stiff = RunFile(path, {{"machine.fmu_parameters.stiffness_n_m", "98696.04401089359"}});
  EXPECT_NEAR(stiff.static_displacement_m, 0.25 * base.static_displacement_m, 1e-12 * base.static_displacement_m);
  EXPECT_NE(stiff.peak_ratio, base.peak_ratio);
}

// Tests that the load-time errors are located at their keys and say what is allowed: a
// variable the FMU lacks (its outputs listed, with the closest name), a parameter that is
// an output, an input of the wrong causality, a missing .fmu, and the servo drive closed
// across the boundary of an FMU without the drive's position and velocity outputs, without a
// velocity loop or with a force limit.
TEST(FmuRun, BadKeysAreLocatedConfigErrors) {
  ScratchDir dir;
  const std::string fmu = TestPlantFmu(2);
  const struct {
    std::string machine;
    std::vector<Override> overrides;
    std::string key;
    std::string part;
  } cases[] = {
      {"{fmu: " + fmu + ", outputs: {deflection: {y: deflection_m}}}", {}, "machine.outputs.deflection.y",
       "has no variable 'deflection_m'"},
      {"{fmu: " + fmu + ", outputs: {deflection: {y: deflection_m}}}", {}, "machine.outputs.deflection.y",
       "its outputs: deflection_y, velocity_y, deflection_peak_y, residual_amplitude_y"},
      {"{fmu: " + fmu + "}", {{"machine.fmu_parameters.deflection_y", "1"}}, "machine.fmu_parameters.deflection_y",
       "has causality output, not parameter"},
      {"{fmu: " + fmu + ", inputs: {y: deflection_y}}", {}, "machine.inputs.y", "base_acceleration wants input"},
      {"{fmu: " + dir.File("missing.fmu") + "}", {}, "machine.fmu", "cannot be opened as an FMU"},
      {"{fmu: " + fmu + "}", {{"drive.type", "servo"}}, "drive", "maps no drive_position output for axis y"},
      {"{fmu: " + fmu + "}", {{"drive.type", "servo"}, {"drive.velocity_loop_hz", "0"}}, "drive.velocity_loop_hz",
       "needs a velocity loop (velocity_loop_hz > 0)"},
      {"{fmu: " + fmu + "}", {{"drive.type", "servo"}, {"drive.force_limit_n", "500"}}, "drive.force_limit_n",
       "put the servo inside the FMU"},
  };
  for (const auto& c : cases) {
    const std::string path = dir.Write("bad.yaml", TestPlantScenario(c.machine));
    try {
      LoadScenario(path, c.overrides);
      ADD_FAILURE() << c.machine;
    } catch (const ConfigError& error) {
      EXPECT_EQ(error.key_path(), c.key) << error.what();
      EXPECT_NE(error.message().find(c.part), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace shapebench::bench::fmu_run_test
