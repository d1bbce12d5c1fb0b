// The single-mode closed forms (bench/run/closed_form_sampler.h): a run of one mode along one
// line without a trace. Checked against two independent answers:
// - an oracle written here in extended precision (long double: 64-bit mantissa) from the
//   model's closed form, the same ticks of the same command: the peak, the residual
//   amplitude and the cruise probe within 1e-12 (the kernel's rounding over ~1,200
//   periods is about 1e-14; the general path's balanced matrix exponential drifts by up
//   to 6e-11 over an undamped run, which is why the general path is not the oracle);
// - the general exact path (RunOptions::single_mode false) on every metric, within 2e-10
//   of the static displacement for the deflections and ratios (that drift, with margin),
//   settling_time_s within one output sample.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <variant>

#include <gtest/gtest.h>

#include "bench/run/command_samples.h"
#include "bench/run/run_scenario.h"
#include "controller/controller.h"
#include "tests/support/general_path.h"
#include "tests/support/long_double_mode.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

// What the oracle computes, in SI.
struct OracleRun {
  double peak_m = 0.0;
  double residual_m = 0.0;    // the free vibration's amplitude at motion end
  double static_m = 0.0;
};

// q'' + 2 zeta w q' + w^2 q = -a held over each tick, deflection = q (gain 1): the
// transition from the exponential's closed form in long double, the extremum inside a tick
// where q' changes sign found by bisection on q' (not the kernel's atan2 formula).
OracleRun Oracle(const Scenario& s) {
  using Real = testing::LongDoubleMode::Real;
  const controller::MultiAxisCommand command = GenerateScenarioCommand(s, s.RunProgram());
  const CommandSamples samples = SampleCommand(command);
  const model::ModalMode& mode = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form).modes.front();
  const testing::LongDoubleMode m(mode);
  const Real h = static_cast<Real>(s.controller.period_s);
  OracleRun run;
  Real q = 0;
  Real v = 0;
  Real peak = 0;
  // The motion and the residual window (three natural periods, run_window.h).
  const std::size_t window = static_cast<std::size_t>(std::ceil(3.0 / mode.frequency_hz / s.controller.period_s));
  for (std::size_t k = 1; k <= samples.motion_ticks + window; ++k) {
    const Real a = samples.AccelAt(k)(1);
    Real q1 = 0;
    Real v1 = 0;
    m.Step(q, v, a, h, &q1, &v1);
    peak = std::max(peak, std::max(std::abs(q1), m.Inside(q, v, a, h)));
    q = q1;
    v = v1;
    if (k == samples.motion_ticks) run.residual_m = static_cast<double>(m.Amplitude(q, v));
  }
  run.peak_m = static_cast<double>(peak);
  run.static_m = samples.max_accel_m_s2 / static_cast<double>(m.w() * m.w());
  return run;
}

// Tests that the peak over the motion and the residual window and the residual amplitude
// at motion end are the extended-precision oracle's within 1e-12 of the static
// displacement, across the sweeps' natural periods, undamped and damped.
TEST(SingleModeRun, PeakAndResidualMatchTheExtendedPrecisionOracle) {
  for (double zeta : {0.0, 0.02}) {
    for (double hz : {15.0, 19.7, 25.0, 29.1797089854493, 35.0}) {
      Scenario s = testing::SdofScenario(hz, zeta);
      s.controller.feed_mm_min = 6000;
      s.controller.accel_time_s = 0.05;
      s.move.distance_mm = 100;
      const RunResult run = RunScenario(s, RunOptions{false});
      const OracleRun oracle = Oracle(s);
      const std::string what = std::to_string(hz) + " Hz zeta " + std::to_string(zeta);
      ASSERT_TRUE(run.single_mode) << what;
      EXPECT_NEAR(run.metrics.static_displacement_m, oracle.static_m, 1e-15 * oracle.static_m) << what;
      EXPECT_NEAR(run.metrics.peak_deflection_m, oracle.peak_m, 1e-12 * oracle.static_m) << what;
      EXPECT_NEAR(run.metrics.residual_amplitude_m, oracle.residual_m, 1e-12 * oracle.static_m) << what;
    }
  }
}

void ExpectNearGeneral(const Scenario& s, const std::string& what) {
  const RunResult fast = RunScenario(s, RunOptions{false});
  const RunResult general = RunScenario(s, testing::GeneralPath(false));
  ASSERT_TRUE(fast.single_mode) << what;
  ASSERT_FALSE(general.single_mode) << what;
  const double scale = general.metrics.static_displacement_m;
  const Metrics& f = fast.metrics;
  const Metrics& g = general.metrics;
  for (const MetricInfo& info : MetricTable()) {
    const double a = f.*info.field;
    const double b = g.*info.field;
    if (std::isnan(b)) {
      EXPECT_TRUE(std::isnan(a)) << what << " " << info.name;
      continue;
    }
    if (info.name == "settling_time_s") {
      EXPECT_NEAR(a, b, 1.01 * s.controller.period_s / fast.substeps) << what;
    } else if (info.unit == "m") {
      EXPECT_NEAR(a, b, 2e-10 * scale) << what << " " << info.name;
    } else if (info.unit == "1") {
      EXPECT_NEAR(a, b, 2e-10) << what << " " << info.name;
    } else {
      EXPECT_EQ(a, b) << what << " " << info.name;
    }
  }
  EXPECT_EQ(fast.substeps, general.substeps) << what;
  EXPECT_EQ(fast.residual_modes.size(), general.residual_modes.size()) << what;
}

struct GridPoint {
  double zeta;
  double distance_mm;
};

class SingleModeGrid : public ::testing::TestWithParam<GridPoint> {};

// Tests that every metric is the general exact path's across the sweeps' natural periods
// (15-35 Hz against a 25 Hz design), for the grid's damping and direction: the settling
// tail, the cruise probes and the contour error near the line's ends included.
TEST_P(SingleModeGrid, EveryMetricAsTheGeneralPath) {
  for (double hz = 15.0; hz <= 35.0; hz += 1.3) {
    Scenario s = testing::SdofScenario(hz, GetParam().zeta);
    s.controller.feed_mm_min = 6000;
    s.controller.accel_time_s = 0.05;
    s.move.distance_mm = GetParam().distance_mm;
    ExpectNearGeneral(s, std::to_string(hz) + " Hz");
  }
}

INSTANTIATE_TEST_SUITE_P(DampingAndDirection, SingleModeGrid,
                         ::testing::Values(GridPoint{0.0, 100.0}, GridPoint{0.0, -37.0}, GridPoint{0.02, 100.0},
                                           GridPoint{0.02, -37.0}, GridPoint{0.1, 100.0}, GridPoint{0.3, 213.0}));

// Tests random single-mode moves (mode, damping, feed, acc/dec time, distance, the
// pattern's design frequency, the period; seeded) against the general path.
TEST(SingleModeRun, RandomMovesAsTheGeneralPath) {
  std::mt19937 random(2027);
  for (int trial = 0; trial < 40; ++trial) {
    const Scenario s = testing::RandomSdofMove(&random, trial);
    ExpectNearGeneral(s, "trial " + std::to_string(trial));
  }
}

// Tests that a traced run keeps the closed forms' metrics, and that the runs they do not
// cover go the general way: a servo drive, two modes, CVODE, a stroke limit, a mode too fast for one extremum a period.
TEST(SingleModeRun, OtherRunsTakeTheGeneralPath) {
  const Scenario base = testing::SdofScenario();
  const RunResult untraced = RunScenario(base, RunOptions{false});
  EXPECT_TRUE(untraced.single_mode);
  // A trace is the general path's; the metrics stay the closed forms', bit for bit.
  const RunResult traced = RunScenario(base);
  EXPECT_TRUE(traced.single_mode);
  EXPECT_GT(traced.trace.time_s.size(), 1000u);
  for (const MetricInfo& info : MetricTable()) {
    const double a = traced.metrics.*info.field;
    const double b = untraced.metrics.*info.field;
    EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << info.name;
  }
  Scenario servo = base;
  servo.drive.type = model::DriveType::kServo;
  EXPECT_FALSE(RunScenario(servo, RunOptions{false}).single_mode) << "servo";
  Scenario two = base;
  std::get<model::ModalMachineConfig>(two.machine.axes[1]->form).modes.push_back(model::ModalMode{60.0, 0.02, 0.3});
  EXPECT_FALSE(RunScenario(two, RunOptions{false}).single_mode) << "two modes";
  Scenario cvode = testing::SdofScenario(25.0, 0.0, model::IntegratorMethod::kCvode);
  EXPECT_FALSE(RunScenario(cvode, RunOptions{false}).single_mode) << "cvode";
  Scenario stroke = base;
  stroke.machine.stroke_m[1] = std::array<double, 2>{-1.0, 1.0};
  EXPECT_FALSE(RunScenario(stroke, RunOptions{false}).single_mode) << "stroke";
  Scenario fast = testing::SdofScenario(300.0, 0.0);
  EXPECT_FALSE(RunScenario(fast, RunOptions{false}).single_mode) << "300 Hz at 1 ms";
}

}  // namespace
}  // namespace shapebench::bench
