// RunOptions::record_trace off (what sweeps and checks run) gives the same metrics, bit for
// bit, as the run that records the trace: the single-axis samples of cosim.cc against the
// general loop, for every integrator and for the shipped scenarios.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "tests/support/general_path.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/same_metric_bits.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

using testing::ExpectSameBits;

void ExpectSameMetrics(const Scenario& scenario, const std::string& what) {
  const RunResult traced = RunScenario(scenario, testing::GeneralPath(true));
  const RunResult fast = RunScenario(scenario, testing::GeneralPath(false));
  EXPECT_FALSE(traced.trace.time_s.empty());
  EXPECT_TRUE(fast.trace.time_s.empty()) << what << ": no trace recorded";
  EXPECT_GT(fast.metrics.peak_ratio, 0.5) << what;
  ExpectSameBits(traced.metrics, fast.metrics, what);
  EXPECT_EQ(traced.simulated_s, fast.simulated_s) << what;
  if (scenario.integrator.method == model::IntegratorMethod::kCvode && fast.tail_in_closed_form) {
    // CVODE stops at the residual window's end when the tail is found in closed form.
    EXPECT_LT(fast.stats.steps, traced.stats.steps) << what;
  } else {
    EXPECT_EQ(traced.stats.steps, fast.stats.steps) << what;
  }
}

// Tests the patent's SDOF move (one axis: the single-axis samples) with each integrator,
// and moves in both directions along X and Y.
TEST(CosimFastPath, SingleAxisMoveMatchesTheTracedRun) {
  for (auto method : {model::IntegratorMethod::kExact, model::IntegratorMethod::kCvode,
                      model::IntegratorMethod::kAuto}) {
    for (double distance_mm : {213.0, -120.0}) {
      Scenario s = testing::SdofScenario(23.0, 0.02, method);
      s.move.distance_mm = distance_mm;
      ExpectSameMetrics(s, "sdof " + std::to_string(static_cast<int>(method)) + " " +
                               std::to_string(distance_mm));
    }
  }
  Scenario x = testing::SdofScenario(25.0, 0.0, model::IntegratorMethod::kExact);
  x.machine.axes[0] = x.machine.axes[1];
  x.move.axis = 0;
  ExpectSameMetrics(x, "x axis");
}

// Tests the shipped scenarios (programs on several axes, arcs, servo, stroke ends: the
// general loop either way, and whatever the single-axis test leaves to it).
TEST(CosimFastPath, ShippedScenariosMatchTheTracedRun) {
  const std::string dir = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/";
  for (const char* name : {"method1.yaml", "method2.yaml", "exponential.yaml", "pocket_corner.yaml",
                           "circle_test.yaml", "stroke_end.yaml", "um_zv.yaml"}) {
    const Scenario s = LoadScenario(dir + name, {});
    const RunResult traced = RunScenario(s, testing::GeneralPath(true));
    const RunResult fast = RunScenario(s, testing::GeneralPath(false));
    ExpectSameBits(traced.metrics, fast.metrics, name);
  }
}

// Tests `integrator.method: auto` from YAML: accepted, and (every plant being linear) the
// exact integrator's run, bit for bit, on the SDOF case and the servo-driven moving column.
TEST(CosimFastPath, MethodAutoIsTheExactRun) {
  const std::string scenarios = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/";
  for (const char* name : {"sdof_method1.yaml", "pocket_corner.yaml"}) {
    const std::vector<Override> servo = {{"drive.type", "servo"}};
    std::vector<Override> automatic = servo;
    automatic.push_back({"integrator.method", "auto"});
    std::vector<Override> exact = servo;
    exact.push_back({"integrator.method", "exact"});
    const Scenario a = LoadScenario(scenarios + name, automatic);
    EXPECT_EQ(a.integrator.method, model::IntegratorMethod::kAuto);
    const RunResult by_auto = RunScenario(a, RunOptions{false});
    const RunResult by_exact = RunScenario(LoadScenario(scenarios + name, exact), RunOptions{false});
    ExpectSameBits(by_auto.metrics, by_exact.metrics, name);
    EXPECT_EQ(by_auto.stats.rhs_evals, 0) << name << ": no CVODE";
  }
}

}  // namespace
}  // namespace shapebench::bench
