// The `pattern` report's numbers (bench/output/pattern_report.h), which the report prints
// and the Python module returns, and the run helpers the CLI shares with the module
// (bench/run/located_run.h): against closed forms of the shapers.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/located_run.h"
#include "bench/output/pattern_report.h"
#include "bench/output/report.h"
#include "model/integrator.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

using testing::SdofScenario;

// Tests that an undamped ZVD at 25 Hz is its closed form 1/4, 1/2, 1/4 at 0, T/2, T (to
// 1e-15: the design's own rounding), its profile table one coefficient per tick up to T
// summing to 1, and its residual at the design frequency zero (below 1e-12) stepped and on
// the grid, while the uncorrected rounding equals the stepped one (T/2 and T are ticks).
TEST(PatternData, ZvdIsItsClosedForm) {
  Scenario s = SdofScenario();
  s.controller.pattern.method = "zvd";
  const PatternData data = ComputePattern(s.controller);
  ASSERT_TRUE(data.shapes);
  ASSERT_EQ(data.impulses.size(), 3u);
  const double times[] = {0.0, 0.02, 0.04};
  const double amplitudes[] = {0.25, 0.5, 0.25};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(data.impulses[i].time_s, times[i], 1e-15);
    EXPECT_NEAR(data.impulses[i].amplitude, amplitudes[i], 1e-15);
  }
  EXPECT_EQ(data.period_s, 0.001);
  EXPECT_EQ(data.table.size(), 41u);
  double sum = 0.0;
  for (const double alpha : data.table) sum += alpha;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  ASSERT_EQ(data.residuals.size(), 1u);
  EXPECT_EQ(data.residuals[0].frequency_hz, 25.0);
  EXPECT_LT(data.residuals[0].stepped, 1e-12);
  EXPECT_LT(data.residuals[0].profile_table, 1e-12);
  EXPECT_NEAR(data.residuals[0].rounded, data.residuals[0].stepped, 1e-12);
}

// Tests that method none is the unshaped step: impulse 1 at 0, table {1}, and a residual
// of the whole unshaped step (1) at the design frequency.
TEST(PatternData, NoneIsTheUnshapedStep) {
  Scenario s = SdofScenario();
  s.controller.pattern.method = "none";
  const PatternData data = ComputePattern(s.controller);
  EXPECT_FALSE(data.shapes);
  ASSERT_EQ(data.impulses.size(), 1u);
  EXPECT_EQ(data.impulses[0].time_s, 0.0);
  EXPECT_EQ(data.impulses[0].amplitude, 1.0);
  EXPECT_EQ(data.table, std::vector<double>{1.0});
  ASSERT_EQ(data.residuals.size(), 1u);
  EXPECT_NEAR(data.residuals[0].stepped, 1.0, 1e-15);
}

// Tests that method 1 (a/2 for T/2, then a: para. 38) leaves nothing at the machine's one
// 25 Hz mode, listed as axis y mode 1 with its participation 1, and lengthens the move by
// its duration T/2 = 20 ms on the 1 ms grid (0.726 s unshaped, 0.746 s shaped).
TEST(PatternData, MethodOneAtTheMachinesModeAndItsTimePenalty) {
  Scenario s = SdofScenario();
  s.controller.pattern.method = "1";
  const std::vector<ModeResidual> modes = MachineModeResiduals(s);
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_EQ(modes[0].axis, s.machine.driven_axis);
  EXPECT_EQ(modes[0].mode, 1u);
  EXPECT_NEAR(modes[0].frequency_hz, 25.0, 1e-9);
  EXPECT_NEAR(modes[0].participation, 1.0, 1e-12);
  EXPECT_LT(modes[0].stepped, 1e-12);
  EXPECT_LT(modes[0].profile_table, 1e-12);
  const PatternMotionTimes times = MotionTimesWithAndWithoutPattern(s);
  EXPECT_TRUE(times.why_not.empty()) << times.why_not;
  EXPECT_NEAR(times.unshaped_s, 0.726, 1e-12);
  EXPECT_NEAR(times.shaped_s - times.unshaped_s, 0.020, 1e-12);
}

// Tests that a move too short for its pattern has no motion times, and says why (the
// planner's field and message) instead of throwing.
TEST(PatternData, MotionTimesOfAnUnplannableMoveSayWhy) {
  Scenario s = SdofScenario();
  s.controller.pattern.method = "1";
  s.move.distance_mm = 0.01;
  const PatternMotionTimes times = MotionTimesWithAndWithoutPattern(s);
  EXPECT_TRUE(std::isnan(times.shaped_s));
  EXPECT_TRUE(std::isnan(times.unshaped_s));
  EXPECT_NE(times.why_not.find(": "), std::string::npos) << times.why_not;
}

// Tests the one text of a solver failure (the CLI's exit-3 line after "error: ", a sweep
// row's error) and the trace's column names (trace.csv's header, the module's keys).
TEST(LocatedRun, SolverFailureTextAndTraceColumns) {
  EXPECT_EQ(SolverFailureText(model::SolverError("CV_TOO_MUCH_WORK", "at t = 0.1")),
            "solver failed: CV_TOO_MUCH_WORK: at t = 0.1");
  const std::vector<std::string>& columns = TraceColumns();
  ASSERT_EQ(columns.size(), 16u);
  EXPECT_EQ(columns.front(), "t_s");
  EXPECT_EQ(columns[4], "deflection_m");
  EXPECT_EQ(columns[14], "block");
  EXPECT_EQ(columns.back(), "planned_feed_mm_min");
}

}  // namespace
}  // namespace shapebench::bench
