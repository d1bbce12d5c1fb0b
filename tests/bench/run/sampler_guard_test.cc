// The guard of the run core's samplers (bench/run/sampler.h): on every golden scenario,
// each sampler that takes the run defines the same metrics as the general sampler, so a
// metric added to one path cannot go NaN on a fast path unnoticed.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "tests/support/shipped_scenarios.h"

namespace shapebench::bench {
namespace {

// The names of the metrics (both tables) a run defines.
std::set<std::string> Defined(const Metrics& m) {
  std::set<std::string> names;
  for (const MetricInfo& info : MetricTable()) {
    if (!std::isnan(m.*info.field)) names.emplace(info.name);
  }
  for (const MetricInfo& info : NonlinearMetricTable()) {
    if (!std::isnan(m.*info.field)) names.emplace(info.name);
  }
  return names;
}

RunResult RunWith(const Scenario& scenario, SamplerKind fastest) {
  RunOptions options;
  options.record_trace = false;
  options.fastest_sampler = fastest;
  return RunScenario(scenario, options);
}

class SamplerGuard : public ::testing::TestWithParam<std::string> {};

// Tests that every sampler that takes the scenario defines exactly the general sampler's
// metrics, and that its peak agrees with the general sampler's to 1e-9 (the closed form
// is the general exact path's to rounding: 1e-11 of the deflection, see
// single_mode_run_test.cc; the others are bit for bit).
TEST_P(SamplerGuard, EverySamplerDefinesTheGeneralSamplersMetrics) {
  const Scenario scenario = LoadScenario(GetParam(), {});
  const RunResult general = RunWith(scenario, SamplerKind::kGeneral);
  ASSERT_EQ(general.sampler, SamplerKind::kGeneral);
  const std::set<std::string> expected = Defined(general.metrics);
  EXPECT_TRUE(expected.count("peak_deflection_m"));
  for (const SamplerKind kind : kAllSamplers) {
    const RunResult run = RunWith(scenario, kind);
    if (run.sampler != kind) continue;  // the run does not qualify for it
    EXPECT_EQ(Defined(run.metrics), expected) << SamplerName(kind);
    EXPECT_NEAR(run.metrics.peak_deflection_m, general.metrics.peak_deflection_m,
                1e-9 * general.metrics.peak_deflection_m)
        << SamplerName(kind);
  }
}

std::string ScenarioName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = std::filesystem::path(info.param).stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Golden, SamplerGuard, ::testing::ValuesIn(testing::ShippedScenarios()), ScenarioName);

// Tests that the golden scenarios exercise every sampler (the guard above is not empty
// for any of them) and that a run takes the fastest that qualifies by default.
TEST(SamplerGuard, GoldenScenariosExerciseEverySampler) {
  std::set<SamplerKind> taken;
  for (const std::string& file : testing::ShippedScenarios()) {
    const Scenario scenario = LoadScenario(file, {});
    for (const SamplerKind kind : kAllSamplers) {
      if (RunWith(scenario, kind).sampler == kind) taken.insert(kind);
    }
    const RunResult by_default = RunScenario(scenario, RunOptions{false});
    for (const SamplerKind kind : kAllSamplers) {
      if (kind > by_default.sampler) {
        EXPECT_NE(RunWith(scenario, kind).sampler, kind) << file << ": " << SamplerName(kind) << " qualifies";
      }
    }
  }
  for (const SamplerKind kind : kAllSamplers) EXPECT_TRUE(taken.count(kind)) << SamplerName(kind);
}

}  // namespace
}  // namespace shapebench::bench
