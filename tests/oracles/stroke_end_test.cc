// EP0646852's stroke-end deceleration on the moving column: the conventional overshoot
// F^2 / (2 a), the bound with the function on, the arc crossing between its end points,
// and the errors for bad values.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ScratchDir;

const std::string kMachine = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/machines/moving_column.yaml";
constexpr double kStrokeFeed = 0.5;          // 30 m/min
constexpr double kStrokeAccel = 0.5 / 0.3;   // 0.17 G
constexpr double kMinute = 100.0 / 60000.0;
constexpr double kDt = 0.001;

std::string Scenario(bool enabled, const std::string& program) {
  return "machine: " + kMachine + "\n"
         "controller:\n  feed_mm_min: 30000\n  accel_time_s: 0.3\n"
         "  stroke_end: {enabled: " + (enabled ? "true" : "false") + ", minute_feed_mm_min: 100}\n"
         "program:\n" + program;
}

RunResult RunYaml(const std::string& yaml, std::vector<Override> sets = {}) {
  ScratchDir dir;
  return RunScenario(LoadScenario(dir.Write("s.yaml", yaml), sets));
}

// The Y stroke ends at 150 mm; the line asks for 300 mm.
const std::string kLine = "  - {g: 1, y: 300, f: 30000}\n";

std::vector<Override> Stroke(const std::string& limits) { return {Override{"machine.stroke", limits}}; }

// Tests the conventional behaviour: full feed until the tool reaches the stroke end, then
// the normal deceleration: overshoot F^2 / (2 a) = 75 mm within 5%, and the alarm.
TEST(StrokeEndTest, ConventionalOvershootIsTheStoppingDistance) {
  const RunResult r = RunYaml(Scenario(false, kLine), Stroke("{y: [-10, 150]}"));
  EXPECT_EQ(r.metrics.stroke_alarm, 1.0);
  const double expected = kStrokeFeed * kStrokeFeed / (2 * kStrokeAccel);
  EXPECT_NEAR(r.metrics.stroke_overshoot_m, expected, 0.05 * expected);
}

// Tests the function on: the overshoot stays within the minute feed's stopping distance
// plus one period's travel at the minute feed, and the tool reaches within one period's
// travel of the stroke end (the whole stroke is used).
TEST(StrokeEndTest, DecelerationUsesTheWholeStroke) {
  const RunResult r = RunYaml(Scenario(true, kLine), Stroke("{y: [-10, 150]}"));
  EXPECT_EQ(r.metrics.stroke_alarm, 1.0);
  const double bound = kMinute * kMinute / (2 * kStrokeAccel) + kMinute * kDt;
  EXPECT_LE(r.metrics.stroke_overshoot_m, bound);
  double furthest = -1.0;
  for (const Eigen::Vector3d& p : r.command.Positions()) furthest = std::max(furthest, p.y());
  EXPECT_GE(furthest, 0.150 - kMinute * kDt);
  // And it arrives slowly: at the stroke end the commanded speed is the minute feed.
  std::printf("stroke end on: overshoot %.3g um (bound %.3g um), furthest y %.6f mm\n",
              r.metrics.stroke_overshoot_m * 1e6, bound * 1e6, furthest * 1e3);
}

// Tests that an arc whose end points are inside the stroke but whose curve leaves it is
// caught along the curve: a CW half circle R50 from (100, 100) to (200, 100) peaks at
// y = 150 > 140; the same bound holds with the function on, and without it the tool runs
// through at the arc's feed.
TEST(StrokeEndTest, ArcCrossingBetweenItsEndPoints) {
  const std::string arc = "  - {g: 1, x: 100, y: 100, f: 30000}\n  - {g: 2, x: 200, y: 100, r: 50}\n";
  auto yaml = [&](bool enabled) { return Scenario(enabled, arc); };
  const RunResult on = RunYaml(yaml(true), Stroke("{y: [-10, 140]}"));
  EXPECT_EQ(on.metrics.stroke_alarm, 1.0);
  EXPECT_LE(on.metrics.stroke_overshoot_m, kMinute * kMinute / (2 * kStrokeAccel) + kMinute * kDt);
  const RunResult off = RunYaml(yaml(false), Stroke("{y: [-10, 140]}"));
  EXPECT_EQ(off.metrics.stroke_alarm, 1.0);
  EXPECT_GT(off.metrics.stroke_overshoot_m, 1e-3);
  const RunResult inside = RunYaml(yaml(true), Stroke("{y: [-10, 160]}"));
  EXPECT_EQ(inside.metrics.stroke_alarm, 0.0);
  EXPECT_EQ(inside.metrics.stroke_overshoot_m, 0.0);
}

ConfigError StrokeLoadError(const std::string& yaml, std::vector<Override> sets) {
  ScratchDir dir;
  return testing::ErrorOf([&] { LoadScenario(dir.Write("s.yaml", yaml), sets); });
}

// Tests that bad values exit 2 naming the key: a negative ratio, a ratio above 1, a
// minute feed <= 0 or above the feed, and a stroke with min >= max.
TEST(StrokeEndTest, BadValuesNameTheKey) {
  const std::string base = Scenario(true, kLine);
  EXPECT_EQ(StrokeLoadError(base, {{"controller.short_block", "{mode: ratio, ratio_line: -0.5}"}}).key_path(),
            "controller.short_block.ratio_line");
  EXPECT_EQ(StrokeLoadError(base, {{"controller.short_block", "{mode: ratio, ratio_arc: 1.5}"}}).key_path(),
            "controller.short_block.ratio_arc");
  EXPECT_EQ(StrokeLoadError(base, {{"controller.stroke_end.minute_feed_mm_min", "0"}}).key_path(),
            "controller.stroke_end.minute_feed_mm_min");
  EXPECT_EQ(StrokeLoadError(base, {{"controller.stroke_end.minute_feed_mm_min", "40000"}}).key_path(),
            "controller.stroke_end.minute_feed_mm_min");
  const ConfigError stroke = StrokeLoadError(base, Stroke("{y: [150, 150]}"));
  EXPECT_EQ(stroke.key_path(), "machine.stroke.y") << stroke.what();
  EXPECT_NE(stroke.message().find("min < max"), std::string::npos) << stroke.what();
}

}  // namespace
}  // namespace shapebench::bench
