// limits.max_work's and identify's defaults against what ships (docs/reliability.md#limits):
// at least ten times the costliest shipped run and fit, and a 2-hour program at a 1 ms
// period admitted. The counts are printed: the figures the docs give.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/measured/frf_identification.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "model/integrator.h"
#include "model/modal_identification.h"
#include "tests/support/shipped_scenarios.h"

namespace shapebench::bench {
namespace {

// Tests that the default limits.max_work admits every shipped scenario ten times over, with
// and without a trace (the general sampler then steps the whole tail), and a 2-hour program
// at a 1 ms period (7.2e6 periods) at the costliest shipped work per period, four times over.
TEST(WorkBudget, DefaultAdmitsTenTimesTheCostliestShippedRun) {
  double costliest = 0.0;
  double per_period = 0.0;
  std::string which;
  std::string densest;
  for (const std::string& file : testing::ShippedScenarios()) {
    const Scenario scenario = LoadScenario(file, {});
    EXPECT_EQ(scenario.limits.max_work, kDefaultMaxWork);
    for (const bool trace : {false, true}) {
      RunOptions options;
      options.record_trace = trace;
      const RunResult result = RunScenario(scenario, options);
      EXPECT_GT(result.work, 0.0) << file;
      const std::string name = scenario.name + (trace ? " (traced)" : "");
      if (result.work > costliest) {
        costliest = result.work;
        which = name;
      }
      const double periods = result.simulated_s / scenario.controller.period_s;
      if (result.work / periods > per_period) {
        per_period = result.work / periods;
        densest = name;
      }
    }
  }
  const double two_hours = per_period * 7200.0 / 0.001;
  std::cout << "costliest shipped run: " << which << ", " << costliest << " units of work; costliest a period: "
            << densest << ", " << per_period << " (a 2-hour program at 1 ms: " << two_hours << ")\n";
  EXPECT_LE(10.0 * costliest, static_cast<double>(kDefaultMaxWork)) << which;
  EXPECT_LE(4.0 * two_hours, static_cast<double>(kDefaultMaxWork)) << densest;
}

// Tests that the identification's default admits the shipped measurement's fit a thousand
// times over and refuses ten copies of it at order 200 (33-46 s before the limit).
TEST(WorkBudget, IdentificationDefaultAdmitsTheShippedFit) {
  FrfSelection selection;
  const IdentifiedFrfs shipped = IdentifyFrfFile(
      std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/measurements/column_y_accelerance.uff", selection);
  const int lines = static_cast<int>(shipped.identification.frequency_hz.size());
  const double work = model::IdentificationWork(lines, 1, shipped.identification.max_order);
  std::cout << "shipped fit: " << lines << " lines, order " << shipped.identification.max_order << ": " << work
            << " multiply-adds; ten copies at order 200: "
            << model::IdentificationWork(lines, 10, std::min(200, (lines - 2) / 4)) << "\n";
  EXPECT_LE(1000.0 * work, model::kDefaultIdentificationWork);
  EXPECT_GT(model::IdentificationWork(lines, 10, std::min(200, (lines - 2) / 4)), model::kDefaultIdentificationWork);
}

}  // namespace
}  // namespace shapebench::bench
