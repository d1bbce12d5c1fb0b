// The closed-form sampler's stretches (bench/run/single_mode_kernel.h: Jump, and the free
// residual window of closed_form_sampler.cc) against an oracle written here in extended
// precision (long double), tick by tick and sample by sample on the run's own grid: every
// length metric of 60 random single moves, damped and undamped, shaped and not, within
// 1e-12 of the static displacement (the contour error: plus the rounding of the positions
// it is the difference of). The kernel's rounding over a few thousand periods is
// about 1e-14 of it; the oracle's own, in long double, 1e-17.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <variant>

#include <gtest/gtest.h>

#include "bench/run/command_samples.h"
#include "bench/run/run_scenario.h"
#include "controller/controller.h"
#include "tests/support/long_double_mode.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench::single_mode_oracle_test {
namespace {

using testing::LongDoubleMode;
using Real = LongDoubleMode::Real;

struct OracleMetrics {
  double peak_m = 0.0;
  double residual_m = 0.0;       // the free vibration's amplitude at motion end
  double residual_peak_m = 0.0;  // the largest |deflection| after the motion's last tick end
  double cruise_m = NAN;         // the largest amplitude at the cruise probes
  double contour_m = 0.0;        // the largest distance of the tool off the line, sampled
};

// The run's ticks 1..last_tick (the run's own end: its settling tail's length is the
// run's decision, checked against the general path elsewhere) on the sample grid of
// `substeps` a tick, the line from 0 along the move's axis.
OracleMetrics Oracle(const Scenario& s, std::size_t last_tick, int substeps) {
  const controller::MultiAxisCommand command = GenerateScenarioCommand(s, s.RunProgram());
  const CommandSamples samples = SampleCommand(command);
  const int ax = s.move_axis();
  const model::ModalMode& mode = std::get<model::ModalMachineConfig>(s.machine.axes[ax]->form).modes.front();
  const LongDoubleMode m(mode);
  const Real h = static_cast<Real>(command.period_s);
  const Real length = std::abs(static_cast<Real>(s.move.distance_mm)) / 1000;
  const Real dir = s.move.distance_mm < 0 ? -1 : 1;
  // The cruise probes (run_window.h's definition): one lowest-mode period into each steady
  // run at least that long.
  const std::size_t period_ticks = static_cast<std::size_t>(std::ceil(1.0 / mode.frequency_hz / command.period_s));
  std::vector<std::size_t> probes;
  for (const auto& [first, end] : samples.steady_runs) {
    if (end - first >= period_ticks) probes.push_back(first - 1 + period_ticks);
  }
  // The residual window: three lowest-mode periods (run_window.h).
  const std::size_t window_ticks = static_cast<std::size_t>(std::ceil(3.0 / mode.frequency_hz / command.period_s));
  // Samples can leave the line only within this of its ends: |q| <= sum |a| dt / w_d.
  Real l1 = 0;
  for (std::size_t k = 1; k <= samples.n; ++k) l1 += std::abs(static_cast<Real>(samples.accel[k](ax))) * h;
  const Real near = l1 / m.wd() + static_cast<Real>(samples.max_speed_m_s) * h +
                    static_cast<Real>(samples.max_accel_m_s2) * h * h + 1e-9L;
  OracleMetrics out;
  Real q = 0;
  Real v = 0;
  Real peak = 0;
  Real residual = 0;
  Real contour = 0;
  for (std::size_t k = 1; k <= last_tick; ++k) {
    const bool commanded = k <= samples.n;
    const Real a = static_cast<Real>(samples.AccelAt(k)(ax));
    const Real p0 = static_cast<Real>((commanded ? samples.positions[k - 1] : samples.positions.back())(ax));
    const Real v0 = commanded ? static_cast<Real>(samples.velocity[k - 1](ax)) : 0;
    const Real along0 = p0 * dir;
    if (along0 < near || along0 > length - near) {
      for (int j = 1; j <= substeps; ++j) {
        const Real tau = h * j / substeps;
        Real qj = 0;
        Real vj = 0;
        m.Step(q, v, a, tau, &qj, &vj);
        const Real u = (p0 + v0 * tau + a * tau * tau / 2 + qj) * dir;
        contour = std::max(contour, std::max(-u, u - length));
      }
    }
    const Real inside = m.Inside(q, v, a, h);
    Real q1 = 0;
    Real v1 = 0;
    m.Step(q, v, a, h, &q1, &v1);
    peak = std::max(peak, std::max(std::abs(q1), inside));
    if (k == samples.motion_ticks) residual = std::abs(q1);
    if (k > samples.motion_ticks && k <= samples.motion_ticks + window_ticks) {
      residual = std::max(residual, std::max(std::abs(q1), inside));
    }
    q = q1;
    v = v1;
    if (k == samples.motion_ticks) out.residual_m = static_cast<double>(m.Amplitude(q, v));
    if (std::find(probes.begin(), probes.end(), k) != probes.end()) {
      const double amplitude = static_cast<double>(m.Amplitude(q, v));
      out.cruise_m = std::isnan(out.cruise_m) ? amplitude : std::max(out.cruise_m, amplitude);
    }
  }
  out.peak_m = static_cast<double>(peak);
  out.residual_peak_m = static_cast<double>(residual);
  out.contour_m = static_cast<double>(contour);
  return out;
}

// Tests that the closed form's length metrics (peak, residual amplitude and peak, cruise
// residual, contour error) of 60 random single moves, damped and undamped, unshaped and
// shaped by the patent's methods and a registry shaper, with short and long cruises, are
// the extended-precision oracle's within 1e-12 of the static displacement.
TEST(SingleModeOracle, RandomMovesLengthMetrics) {
  std::mt19937 random(4141);
  const char* methods[] = {"none", "1", "2", "3", "zvd"};
  int jumped = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Scenario s = testing::RandomSdofMove(&random, trial);
    s.controller.pattern.method = methods[trial % 5];
    const RunResult run = RunScenario(s, RunOptions{false});
    const std::string what = "trial " + std::to_string(trial) + " (" + s.controller.pattern.method + ")";
    ASSERT_EQ(run.sampler, SamplerKind::kClosedForm) << what;
    const std::size_t last_tick = static_cast<std::size_t>(run.stats.steps / run.substeps);
    const OracleMetrics oracle = Oracle(s, last_tick, run.substeps);
    const Metrics& got = run.metrics;
    const double tolerance = 1e-12 * got.static_displacement_m;
    EXPECT_NEAR(got.peak_deflection_m, oracle.peak_m, tolerance) << what;
    EXPECT_NEAR(got.residual_amplitude_m, oracle.residual_m, tolerance) << what;
    EXPECT_NEAR(got.residual_peak_m, oracle.residual_peak_m, tolerance) << what;
    // The contour error is a difference of positions of the line's size (the tool's and
    // the line's end): their rounding, a few ulps of the length, comes on top.
    const double positions = 8.0 * std::numeric_limits<double>::epsilon() * std::abs(s.move.distance_mm) / 1000.0;
    EXPECT_NEAR(got.max_contour_error_m, oracle.contour_m, tolerance + positions) << what;
    if (std::isnan(oracle.cruise_m)) {
      EXPECT_TRUE(std::isnan(got.cruise_residual_ratio)) << what;
    } else {
      EXPECT_NEAR(got.cruise_residual_ratio * got.static_displacement_m, oracle.cruise_m, tolerance) << what;
    }
    jumped += run.deferred_periods > 0;
  }
  // The stretches were taken, not only the tick loop: most runs defer periods.
  EXPECT_GT(jumped, 50);
}

}  // namespace
}  // namespace shapebench::bench::single_mode_oracle_test
