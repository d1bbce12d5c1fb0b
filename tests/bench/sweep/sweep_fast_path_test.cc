// The fast path of running a sweep's points (bench/sweep/sweep.cc RunPoint): the base
// scenario parsed once per thread (ParseCacheScope) and one command shared by the points
// whose swept keys the controller does not read. A point's metrics must stay, bit for bit,
// those of loading and running it on its own.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;

void ExpectSamePointBits(const Metrics& a, const Metrics& b, const std::string& what) {
  const auto x = a.Named();
  const auto y = b.Named();
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(std::memcmp(&x[i].second, &y[i].second, sizeof(double)), 0)
        << what << ": " << x[i].first << " " << x[i].second << " vs " << y[i].second;
  }
}

// Tests a grid over the plant (shared command) crossed with the pattern method and the
// feed (keys the controller reads: a command each), points visited out of order as the
// workers take them: every point's metrics equal an independent load and run of it.
TEST(SweepFastPath, PointsEqualIndependentRuns) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "sweep.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                        "\ngrid:\n  controller.pattern.method: [none, 1]\n"
                        "  controller.feed_mm_min: [24000, 30000]\n"
                        "  machine.modes[0].frequency_hz: {from: 20, to: 30, steps: 5}\n"
                        "  machine.modes[0].damping_ratio: [0, 0.03]\n");
  const std::vector<Override> sets = {{"integrator.method", "exact"}};
  const Sweep sweep = LoadSweep(path, sets);
  ASSERT_EQ(sweep.points, 40u);
  std::vector<std::uint64_t> order;
  for (std::uint64_t p = 0; p < sweep.points; ++p) order.push_back(p);
  for (std::uint64_t p = 0; p < sweep.points; p += 7) order.push_back(p);  // revisits
  for (std::uint64_t p = sweep.points; p-- > 0;) order.push_back(p);       // backwards
  for (const std::uint64_t p : order) {
    const PointOutcome outcome = RunPoint(sweep, sets, p);
    ASSERT_TRUE(outcome.ok()) << outcome.error;
    const SweepPoint point = MakePoint(sweep, p, sets);
    const Metrics alone = RunScenario(LoadScenario(sweep.base, point.overrides)).metrics;
    ExpectSamePointBits(outcome.metrics, alone, point.Label());
  }
}

// Tests that a point whose value is invalid still reports its error at the value in the
// sweep file (a load inside the parse cache has no positions: it is loaded again without).
TEST(SweepFastPath, ErrorsStillLocated) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "sweep.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                        "\ngrid:\n  controller.pattern.k1: [0.675, 0.2]\n"
                        "  controller.pattern.method: [3]\n");
  const Sweep sweep = LoadSweep(path, {});
  EXPECT_TRUE(RunPoint(sweep, {}, 0).ok()) << RunPoint(sweep, {}, 0).error;
  const PointOutcome bad = RunPoint(sweep, {}, 1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error.rfind(path + ":3:", 0), 0u) << bad.error;
  EXPECT_NE(bad.error.find("controller.pattern.k1"), std::string::npos) << bad.error;
}

}  // namespace
}  // namespace shapebench::bench
