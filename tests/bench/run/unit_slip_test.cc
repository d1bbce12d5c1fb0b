// Values a run accepts that are almost surely a unit slip (bench/run/unit_slips.h, issue 32
// item 15): each a warning naming the key, the value and the likely slip; a plausible
// scenario none.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/run/unit_slips.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ScratchDir;

bool HasWarning(const RunResult& result, const std::string& part) {
  return std::any_of(result.warnings.begin(), result.warnings.end(),
                     [&](const std::string& warning) { return warning.find(part) != std::string::npos; });
}

std::string AllWarnings(const RunResult& result) {
  std::string text;
  for (const std::string& warning : result.warnings) text += warning + "\n";
  return text;
}

// Tests that the slips (period_s: 1, accel_time_s: 200, a mode at 0.01 Hz: here a
// static displacement of 127 mm) warn about each, naming key, value and
// the likely slip, and that the shipped demo and a mode just above the threshold do not.
TEST(UnitSlips, EachLikelySlipIsAWarningNamingKeyAndValue) {
  ScratchDir dir;
  const std::string path = dir.Write("slip.yaml",
                                     "machine: {modes: [{frequency_hz: 0.01, damping_ratio: 0.03, gain: 1.0}]}\n"
                                     "controller: {period_s: 1, feed_mm_min: 6000, accel_time_s: 200}\n"
                                     "move: {distance_mm: 100}\n");
  const RunResult slip = RunScenario(LoadScenario(path, {}), RunOptions{false});
  const std::string all = AllWarnings(slip);
  EXPECT_GT(slip.metrics.static_displacement_m, kUnitSlipStaticM);
  EXPECT_TRUE(HasWarning(slip, "controller.period_s: 1 s is longer than any CNC's interpolation period")) << all;
  EXPECT_TRUE(HasWarning(slip, "did you mean 1 ms (controller.period_s: 0.001)?")) << all;
  EXPECT_TRUE(HasWarning(slip, "controller.accel_time_s: 200 s is longer than any machine tool's acc/dec time"))
      << all;
  EXPECT_TRUE(HasWarning(slip, "did you mean 200 ms (controller.accel_time_s: 0.2)?")) << all;
  EXPECT_TRUE(HasWarning(slip, "machine.modes[0].frequency_hz: 0.01 Hz is below any machine structure's mode "
                               "(warned below 1 Hz)")) << all;
  EXPECT_TRUE(HasWarning(slip, "1/0.01 s is 100 Hz")) << all;
  EXPECT_TRUE(HasWarning(slip, "static_displacement_m: ")) << all;
  EXPECT_TRUE(HasWarning(slip, "warned above 10 mm")) << all;
  EXPECT_EQ(slip.warnings.size(), 4u) << all;

  const RunResult demo =
      RunScenario(LoadScenario(std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/demo.yaml", {}), RunOptions{false});
  EXPECT_TRUE(demo.warnings.empty()) << AllWarnings(demo);
  const std::string edge = dir.Write("edge.yaml",
                                     "machine: {modes: [{frequency_hz: 1.0, damping_ratio: 0.5, gain: 1.0e-4}]}\n"
                                     "controller: {period_s: 0.1, feed_mm_min: 6000, accel_time_s: 10}\n"
                                     "move: {distance_mm: 2000}\n");
  const RunResult at_thresholds = RunScenario(LoadScenario(edge, {}), RunOptions{false});
  EXPECT_TRUE(at_thresholds.warnings.empty()) << AllWarnings(at_thresholds);
}

// Tests that a lumped machine whose lowest mode is below the threshold is warned about as
// the machine's (no YAML frequency to name).
TEST(UnitSlips, LumpedMachineBelowTheThresholdIsNamedAsTheMachine) {
  ScratchDir dir;
  const std::string path = dir.Write("lumped.yaml",
                                     "machine:\n"
                                     "  bodies: [{name: column, mass_kg: 1000}]\n"
                                     "  elements: [{name: guides, from: column, to: driven, stiffness_n_m: 10.0, "
                                     "damping_n_s_m: 60}]\n"
                                     "  output: {body: column}\n"
                                     "controller: {period_s: 0.01, feed_mm_min: 6000, accel_time_s: 0.05}\n"
                                     "move: {distance_mm: 10}\n");
  const RunResult result = RunScenario(LoadScenario(path, {}), RunOptions{false});
  EXPECT_TRUE(HasWarning(result, "machine: its lowest mode is at 0.0159")) << AllWarnings(result);
}

}  // namespace
}  // namespace shapebench::bench
