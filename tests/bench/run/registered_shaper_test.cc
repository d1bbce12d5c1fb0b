// A shaper that exists only in this file, registered with controller::RegisterShaper and
// used by name from a scenario file: one file is all a new shaper needs
// (controller/shaper_registry.h). The loader, the run, the `pattern` report and the
// located YAML errors all read the registry.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/output/pattern_report.h"
#include "bench/run/run_scenario.h"
#include "tests/support/bench_test_support.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

using controller::Impulse;
using testing::ScratchDir;

constexpr double kF = 25.0;  // the scenario's mode and the design frequency, Hz

// The ZV shaper written out (undamped): half the step at 0, half at T/2; the vibration
// the second half starts cancels the first's.
controller::ShaperEntry TestZv() {
  controller::ShaperEntry entry;
  entry.key = "test_zv";
  entry.name = "Test ZV";
  entry.description = "two halves T/2 apart, written in this test";
  entry.kind = controller::ShaperKind::kImpulse;
  entry.design = [](const controller::PatternConfig&, double frequency_hz) {
    return std::vector<Impulse>{{0.0, 0.5}, {0.5 / frequency_hz, 0.5}};
  };
  return entry;
}

// Registered before main, the way a shaper of another program would be.
const bool kTestZvRegistered = (controller::RegisterShaper(TestZv()), true);

std::string ScenarioText(const std::string& method) {
  return "machine:\n"
         "  modes:\n"
         "    - {frequency_hz: 25.0, damping_ratio: 0.0, gain: 1.0}\n"
         "drive: {type: kinematic}\n"
         "controller:\n"
         "  period_s: 0.001\n"
         "  feed_mm_min: 30000\n"
         "  accel_time_s: 0.3\n"
         "  pattern: {method: " + method + ", frequency_hz: 25.0}\n"
         "  post_interp: {type: none}\n"
         "move: {distance_mm: 213}\n"
         "integrator: {method: exact}\n";
}

// Tests a shaper defined only in this file end to end: its impulses leave no vibration
// at the design frequency by the residual formula (the oracle), and a scenario file
// naming it (`method: test_zv`) loads and runs with a residual below 1e-6 of static,
// where the same scenario unshaped leaves more than its static deflection.
TEST(RegisteredShaper, RunsFromAScenarioFile) {
  ASSERT_TRUE(kTestZvRegistered);
  controller::PatternConfig config;
  config.method = "test_zv";
  config.frequency_hz = kF;
  EXPECT_LT(controller::ResidualVibration(controller::ShaperImpulses(config), kF), 1e-15);

  ScratchDir dir;
  const Scenario shaped = LoadScenario(dir.Write("shaped.yaml", ScenarioText("test_zv")), {});
  EXPECT_EQ(shaped.controller.pattern.method, "test_zv");
  const Scenario unshaped = LoadScenario(dir.Write("unshaped.yaml", ScenarioText("none")), {});
  const double shaped_residual = RunScenario(shaped).metrics.residual_ratio;
  const double unshaped_residual = RunScenario(unshaped).metrics.residual_ratio;
  EXPECT_LT(shaped_residual, 1e-6);
  EXPECT_GT(unshaped_residual, 1.0);
}

// Tests that the `pattern` report names a registered shaper by its key and description,
// and lists its impulses.
TEST(RegisteredShaper, PatternReportDescribesIt) {
  ScratchDir dir;
  const Scenario s = LoadScenario(dir.Write("s.yaml", ScenarioText("test_zv")), {});
  std::ostringstream out;
  PrintPatternReport(out, s);
  EXPECT_NE(out.str().find("  method test_zv (two halves T/2 apart, written in this test)\n"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("  0.02           0.5\n"), std::string::npos) << out.str();
}

// Tests that an unknown method in a scenario file is located at the value and lists every
// registered key in registry order, the test's own after the built-ins.
TEST(RegisteredShaper, UnknownMethodListsTheRegistry) {
  ScratchDir dir;
  const std::string path = dir.Write("bad.yaml", "controller:\n  pattern: {method: test_zvv}\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadScenario(path, {}); }), path, 2, 21,
                       "controller.pattern.method",
                       "expected one of none|1|2|3|4|zv|zvd|zvdd|mzv|mzv_n|ei|ei_2hump|ei_3hump|um_zv|custom|test_zv, "
                       "got 'test_zvv'");
}

}  // namespace
}  // namespace shapebench::bench
