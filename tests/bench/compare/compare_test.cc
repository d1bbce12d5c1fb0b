// `compare` as a library (bench/compare/): the arithmetic of a change against hand-computed
// values, gates, the did-you-mean of an unknown metric, the sides' --set options, sweeps
// compared point by point against independent runs, and grids that must match.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bench/compare/compare.h"
#include "bench/compare/compare_runs.h"
#include "bench/compare/compare_sweep.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "tests/support/bench_test_support.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;

const MetricInfo& Info(const std::string& name) {
  const MetricInfo* info = FindMetric(name);
  EXPECT_NE(info, nullptr) << name;
  return *info;
}

// The message of the std::runtime_error `call` throws ("" when it throws none).
template <typename Call>
std::string ErrorText(Call call) {
  try {
    call();
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// Tests that the tables show values and changes in engineering units and a change within
// the metric's noise floor (rounding: 1e-14 relative, 0.1 pm) as "same", not as a change.
TEST(CompareArithmetic, TablesShowEngineeringUnitsAndSameWithinNoise) {
  MetricChange c = CompareMetric(Info("residual_amplitude_m"), 8.70475e-05, 8.70475e-05 * (1.0 + 1e-14));
  EXPECT_EQ(ChangeText(c), "same");
  EXPECT_EQ(RelativeText(c), "same");
  c = CompareMetric(Info("stroke_overshoot_m"), 0.0, 1e-13);
  EXPECT_EQ(ChangeText(c), "same");
  c = CompareMetric(Info("residual_amplitude_m"), 8e-05, 9e-05);
  EXPECT_EQ(ChangeText(c), "+10 um");
  EXPECT_EQ(RelativeText(c), "+12.5%");
  c = CompareMetric(Info("motion_time_s"), 0.726, 0.746);
  EXPECT_EQ(ChangeText(c), "+20 ms");
  c = CompareMetric(Info("peak_ratio"), 2.0, 1.5);
  EXPECT_EQ(ChangeText(c), "-0.5");
  c = CompareMetric(Info("peak_ratio"), NAN, 1.5);
  EXPECT_EQ(ChangeText(c), "n/a");
}

// Tests that a change, its relative amount against max(|baseline|, the unit's floor), the
// worsening and the verdict are what hand arithmetic gives: a ratio 2 -> 1.5 is -25%; a
// length 4 um -> 5 um +25%; from 0 m to 0.5 nm +50% of the 1 nm floor; a settling time
// from 0 to 2 us +200% of the 1 us floor; a signed radial error -2 um -> +1 um changes by
// +150% but is better (its magnitude halves); a stroke alarm false -> true +100%; 4 -> 5
// clamps +25%; a higher-is-better metric 2 -> 1.5 is worse by 25%.
TEST(CompareArithmetic, RelativeChangeMatchesHandComputedValues) {
  MetricChange c = CompareMetric(Info("peak_ratio"), 2.0, 1.5);
  EXPECT_DOUBLE_EQ(c.change, -0.5);
  EXPECT_DOUBLE_EQ(c.relative_change, -0.25);
  EXPECT_DOUBLE_EQ(c.worsening, -0.25);
  EXPECT_EQ(c.better, Verdict::kCandidate);

  c = CompareMetric(Info("residual_amplitude_m"), 4e-6, 5e-6);
  EXPECT_DOUBLE_EQ(c.relative_change, 0.25);
  EXPECT_DOUBLE_EQ(c.worsening, 0.25);
  EXPECT_EQ(c.better, Verdict::kBaseline);

  c = CompareMetric(Info("stroke_overshoot_m"), 0.0, 5e-10);
  EXPECT_DOUBLE_EQ(c.change, 5e-10);
  EXPECT_DOUBLE_EQ(c.relative_change, 0.5);
  EXPECT_EQ(c.better, Verdict::kBaseline);

  c = CompareMetric(Info("settling_time_s"), 0.0, 2e-6);
  EXPECT_DOUBLE_EQ(c.relative_change, 2.0);

  c = CompareMetric(Info("radial_error_m"), -2e-6, 1e-6);
  EXPECT_DOUBLE_EQ(c.change, 3e-6);
  EXPECT_DOUBLE_EQ(c.relative_change, 1.5);
  EXPECT_DOUBLE_EQ(c.worsening, -0.5);
  EXPECT_EQ(c.better, Verdict::kCandidate);

  c = CompareMetric(Info("stroke_alarm"), 0.0, 1.0);
  EXPECT_DOUBLE_EQ(c.relative_change, 1.0);
  EXPECT_EQ(c.better, Verdict::kBaseline);

  c = CompareMetric(Info("short_block_clamps"), 4.0, 5.0);
  EXPECT_DOUBLE_EQ(c.relative_change, 0.25);

  const MetricInfo higher{"margin", "1", Better::kHigher, "", &Metrics::peak_ratio};
  c = CompareMetric(higher, 2.0, 1.5);
  EXPECT_DOUBLE_EQ(c.relative_change, -0.25);
  EXPECT_DOUBLE_EQ(c.worsening, 0.25);
  EXPECT_EQ(c.better, Verdict::kBaseline);

  c = CompareMetric(Info("peak_ratio"), 1.25, 1.25);
  EXPECT_EQ(c.better, Verdict::kSame);
  EXPECT_EQ(c.worsening, 0.0);
  const double nan = NAN;
  for (const auto& [baseline, candidate] : {std::pair{nan, 1.0}, std::pair{1.0, nan}, std::pair{nan, nan}}) {
    c = CompareMetric(Info("cruise_residual_ratio"), baseline, candidate);
    EXPECT_EQ(c.better, Verdict::kNotComparable);
    EXPECT_TRUE(std::isnan(c.relative_change));
    EXPECT_TRUE(std::isnan(c.worsening));
  }
  EXPECT_EQ(FormatPercent(-0.25), "-25%");
  EXPECT_EQ(FormatPercent(0.123456), "+12.35%");
  EXPECT_EQ(FormatPercent(0.0), "0%");
}

// Tests that a gate passes up to its relative amount inclusive and fails beyond it, fails
// on a metric undefined (n/a) on either side, and says so in its detail.
TEST(CompareGates, PassWithinTheirRelativeAmountOnly) {
  const Gate gate = ParseGate("residual_ratio=0.25");
  EXPECT_EQ(gate.info, FindMetric("residual_ratio"));
  EXPECT_DOUBLE_EQ(gate.max_worsening, 0.25);
  const MetricChange quarter = CompareMetric(*gate.info, 2.0, 2.5);  // exactly 25% worse
  EXPECT_TRUE(GatePasses(gate, quarter));
  EXPECT_FALSE(GatePasses(ParseGate("residual_ratio=0.2"), quarter));
  EXPECT_EQ(GateDetail(ParseGate("residual_ratio=0.2"), quarter), "worse by 25% (gate 20%)");
  const MetricChange better = CompareMetric(*gate.info, 2.5, 2.0);
  EXPECT_TRUE(GatePasses(ParseGate("residual_ratio=0"), better));
  EXPECT_EQ(GateDetail(ParseGate("residual_ratio=0"), better), "better by 20% (gate 0%)");
  EXPECT_FALSE(GatePasses(ParseGate("residual_ratio=0"), CompareMetric(*gate.info, 2.0, 2.0 + 1e-15)));

  const Gate cruise = ParseGate("cruise_residual_ratio=10");
  EXPECT_FALSE(GatePasses(cruise, CompareMetric(*cruise.info, 0.5, NAN)));
  EXPECT_FALSE(GatePasses(cruise, CompareMetric(*cruise.info, NAN, NAN)));
  EXPECT_EQ(GateDetail(cruise, CompareMetric(*cruise.info, 0.5, NAN)),
            "candidate n/a: not comparable (gate 1000%)");
}

// Tests that an unknown metric in --gate names the closest metric names and lists every
// allowed one, and that a REL that is not a number >= 0 is refused.
TEST(CompareGates, UnknownMetricNamesTheClosestAndTheAllowed) {
  std::string error = ErrorText([] { ParseGate("residual_ration=0"); });
  EXPECT_NE(error.find("unknown metric 'residual_ration'; did you mean residual_ratio?"), std::string::npos)
      << error;
  EXPECT_NE(error.find("allowed: static_displacement_m, peak_deflection_m,"), std::string::npos) << error;
  error = ErrorText([] { ParseGate("residual=0.1"); });
  EXPECT_NE(error.find("did you mean residual_amplitude_m or residual_ratio or residual_peak_m or residual_peak_ratio or "
                       "cruise_residual_ratio?"),
            std::string::npos)
      << error;
  error = ErrorText([] { ParseGate("zzzz=0.1"); });
  EXPECT_EQ(error.find("did you mean"), std::string::npos) << error;
  EXPECT_NE(error.find("allowed: "), std::string::npos) << error;
  for (const char* bad : {"peak_ratio=-1", "peak_ratio=abc", "peak_ratio=nan", "peak_ratio=", "peak_ratio",
                          "=0.1", "peak_ratio=1e999"}) {
    EXPECT_FALSE(ErrorText([&] { ParseGate(bad); }).empty()) << bad;
  }
  EXPECT_EQ(ClosestNames("peak_ratoi", MetricNames()), std::vector<std::string>{"peak_ratio"});
}

// Tests that --set applies to both sides first, --baseline-set and --candidate-set to
// theirs after it; an error in an override is located at the option that gave it; and a
// request with nothing to tell the sides apart is refused.
TEST(CompareRuns, SidesTakeTheirOptionsAndLocateTheirErrors) {
  CompareRequest request;
  request.baseline_file = DataPath("shaped_method1.yaml");
  request.sets = {"controller.feed_mm_min=3000"};
  request.candidate_sets = {"controller.pattern.method=zvd"};
  const CompareSide baseline = BaselineSide(request);
  const CompareSide candidate = CandidateSide(request);
  EXPECT_EQ(baseline.Label(), request.baseline_file + " --set controller.feed_mm_min=3000");
  EXPECT_EQ(candidate.Label(),
            request.baseline_file + " --set controller.feed_mm_min=3000 --set controller.pattern.method=zvd");

  request.candidate_sets = {"controller.pattern.method=3", "controller.pattern.k1=2"};
  try {
    CompareScenarios(request, {});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.file(), "--candidate-set");
    EXPECT_EQ(error.line(), 2);
    EXPECT_EQ(error.key_path(), "controller.pattern.k1");
  }
  EXPECT_EQ(CandidateSide(request).Relabeled(std::string("--set:3:1: controller.pattern.k1: bad")),
            "--candidate-set:2:1: controller.pattern.k1: bad");
  request.candidate_sets.clear();
  EXPECT_NE(ErrorText([&] { CandidateSide(request); }).find("nothing to compare"), std::string::npos);
}

// Tests that two scenarios compare to the metrics of their own runs, bit for bit.
TEST(CompareRuns, ScenariosCompareTheirOwnRunsMetrics) {
  CompareRequest request;
  request.baseline_file = DataPath("unshaped_fails.yaml");
  request.candidate_file = DataPath("shaped_method1.yaml");
  const ScenarioComparison comparison = CompareScenarios(request, {ParseGate("peak_ratio=0")});
  const Metrics baseline = RunScenario(LoadScenario(request.baseline_file, {})).metrics;
  const Metrics candidate = RunScenario(LoadScenario(request.candidate_file, {})).metrics;
  ASSERT_EQ(comparison.changes.size(), MetricTable().size());
  for (std::size_t m = 0; m < MetricTable().size(); ++m) {
    const MetricInfo& info = MetricTable()[m];
    const MetricChange& change = comparison.changes[m];
    EXPECT_EQ(change.info, &info);
    if (std::isnan(baseline.*info.field)) {
      EXPECT_TRUE(std::isnan(change.baseline)) << info.name;
    } else {
      EXPECT_EQ(change.baseline, baseline.*info.field) << info.name;
      EXPECT_EQ(change.candidate, candidate.*info.field) << info.name;
    }
  }
  EXPECT_TRUE(comparison.passed());  // method 1 halves the unshaped step's peak
  EXPECT_EQ(comparison.changes[2].better, Verdict::kCandidate);
  EXPECT_FALSE(comparison.baseline_run.trace.time_s.empty());  // for the overlay plot
}

// Tests that two sweeps compare point by point: the counts per metric, the worst point and
// every row of points.csv agree with runs of each point's scenario made independently; a
// gate fails when any point fails it.
TEST(CompareSweeps, PointByPointAgreesWithIndependentRuns) {
  CompareRequest request;
  request.baseline_file = DataPath("sweeps/failing_point.yaml");
  request.candidate_sets = {"controller.pattern.method=zvd"};
  const ComparedSweeps sweeps = LoadComparedSweeps(request);
  std::ostringstream csv;
  std::ostringstream err;
  const SweepComparison comparison = CompareSweeps(
      sweeps, {ParseGate("residual_ratio=0.01"), ParseGate("motion_time_s=0.01")}, 2, &csv, err);
  EXPECT_TRUE(err.str().empty()) << err.str();
  ASSERT_EQ(comparison.points, 3u);
  EXPECT_EQ(comparison.failed_points, 0u);

  const std::vector<std::string> frequencies = {"24.5", "25", "25.5"};
  std::vector<std::vector<MetricChange>> expected;
  for (const std::string& frequency : frequencies) {
    const std::string base = DataPath("sweeps/sdof_method1.yaml");
    const Override mode{"machine.modes[0].frequency_hz", frequency};
    const Metrics b = RunScenario(LoadScenario(base, {mode})).metrics;
    const Metrics c = RunScenario(LoadScenario(base, {mode, {"controller.pattern.method", "zvd"}})).metrics;
    expected.push_back(CompareMetrics(b, c));
  }
  std::istringstream rows(csv.str());
  CsvReader reader(rows);
  std::vector<std::string> fields;
  ASSERT_TRUE(reader.Next(&fields));
  EXPECT_EQ(fields.front(), "point");
  for (std::size_t m = 0; m < MetricTable().size(); ++m) {
    const SweepMetricSummary& summary = comparison.metrics[m];
    std::uint64_t candidate_better = 0;
    double worst = -INFINITY;
    std::size_t worst_point = 0;
    for (std::size_t p = 0; p < 3; ++p) {
      const MetricChange& change = expected[p][m];
      candidate_better += change.better == Verdict::kCandidate ? 1 : 0;
      if (change.worsening > worst) worst = change.worsening, worst_point = p;
    }
    EXPECT_EQ(summary.candidate_better, candidate_better) << summary.info->name;
    if (std::isfinite(worst)) {
      ASSERT_TRUE(summary.has_worst) << summary.info->name;
      EXPECT_EQ(summary.worst.point, worst_point) << summary.info->name;
      EXPECT_EQ(summary.worst.change.worsening, worst) << summary.info->name;
    }
  }
  for (std::size_t p = 0; p < 3; ++p) {
    for (std::size_t m = 0; m < MetricTable().size(); ++m) {
      ASSERT_TRUE(reader.Next(&fields));
      EXPECT_EQ(fields[0], std::to_string(p));
      EXPECT_EQ(fields[1], frequencies[p]);
      EXPECT_EQ(fields[2], MetricTable()[m].name);
      EXPECT_EQ(fields[3], ExactDouble(expected[p][m].baseline));
      EXPECT_EQ(fields[4], ExactDouble(expected[p][m].candidate));
      EXPECT_EQ(fields[7], VerdictName(expected[p][m].better));
    }
  }
  EXPECT_FALSE(reader.Next(&fields));
  // ZVD leaves less residual vibration than method 1 off 25 Hz (at 25 Hz both leave
  // rounding noise, far below the 1e-6 floor of a ratio), and its move takes T/2 longer.
  ASSERT_EQ(comparison.gates.size(), 2u);
  EXPECT_TRUE(comparison.gates[0].passed());
  EXPECT_FALSE(comparison.gates[1].passed());
  EXPECT_EQ(comparison.gates[1].failed, 3u);
  EXPECT_FALSE(comparison.passed());
}

// Tests that sweeps of different grids are refused with the first difference named: the
// number of axes, an axis' key, the number of values, a value.
TEST(CompareSweeps, DifferentGridsAreRefused) {
  ScratchDir dir;
  const std::string base = DataPath("sweeps/sdof_method1.yaml");
  const auto sweep = [&](const std::string& name, const std::string& grid) {
    return LoadSweep(dir.Write(name, "base: " + base + "\ngrid:\n" + grid), {});
  };
  const Sweep three = sweep("a.yaml", "  machine.modes[0].frequency_hz: [24.5, 25, 25.5]\n");
  EXPECT_NO_THROW(CheckSameGrid(three, sweep("b.yaml", "  machine.modes[0].frequency_hz: [24.5, 25, 25.5]\n")));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"  machine.modes[0].frequency_hz: [24.5, 25, 26]\n", "value 2 is 25.5 in the baseline, 26 in the candidate"},
      {"  machine.modes[0].frequency_hz: [24.5, 25]\n", "has 3 values in the baseline, 2 in the candidate"},
      {"  controller.accel_time_s: [0.2, 0.3, 0.4]\n",
       "axis 1 is machine.modes[0].frequency_hz in the baseline, controller.accel_time_s in the candidate"},
      {"  machine.modes[0].frequency_hz: [24.5, 25, 25.5]\n  controller.accel_time_s: [0.2]\n",
       "1 axis in the baseline, 2 in the candidate"}};
  for (const auto& [grid, difference] : cases) {
    const std::string error = ErrorText([&] { CheckSameGrid(three, sweep("c.yaml", grid)); });
    EXPECT_NE(error.find("grids differ ("), std::string::npos) << error;
    EXPECT_NE(error.find(difference + "): "), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace shapebench::bench
