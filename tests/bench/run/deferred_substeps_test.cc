// Deferred substeps (bench/run/deferred_substeps.h): a single-axis run on the exact path
// without a trace steps a period's inner output substeps only where they can change a
// metric. The metrics must be those of the run that samples every substep (the traced
// run, cosim_fast_path_test.cc: the general samples), bit for bit, over the natural
// periods of the sweeps (15-35 Hz against a 25 Hz design), undamped and damped, both
// directions, and a line that does not start at 0; and the bounds the decision rests on
// must hold against brute force.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/run/deferred_substeps.h"
#include "tests/support/general_path.h"
#include "tests/support/same_metric_bits.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {

using testing::ExpectSameBits;

// The general exact path's deferral is what these tests are about (general_path.h).
RunOptions Deferred() { return testing::GeneralPath(false); }

// Returns how many periods the untraced run deferred.
long ExpectSameAsEverySubstep(const Scenario& scenario, const std::string& what) {
  const RunResult traced = RunScenario(scenario, testing::GeneralPath(true));
  const RunResult deferred = RunScenario(scenario, Deferred());
  EXPECT_EQ(traced.deferred_periods, 0) << what << ": a trace needs every substep";
  EXPECT_GT(deferred.metrics.peak_ratio, 0.5) << what;  // a run that moved
  ExpectSameBits(traced.metrics, deferred.metrics, what);
  return deferred.deferred_periods;
}

// Tests that the deferred run's metrics equal the every-substep run's bit for bit across
// the sweeps' natural periods, undamped and at 2% and 10% damping, in both directions, and
// that most periods were deferred (else the test would not test the deferral).
TEST(DeferredSubsteps, MetricsSameAsEverySubstep) {
  for (double zeta : {0.0, 0.02, 0.1}) {
    for (double hz = 15.0; hz <= 35.0; hz += 1.3) {
      for (double distance_mm : {100.0, -37.0}) {
        Scenario s = testing::SdofScenario(hz, zeta);
        s.controller.feed_mm_min = 6000;
        s.controller.accel_time_s = 0.05;
        s.move.distance_mm = distance_mm;
        const std::string what = std::to_string(hz) + " Hz zeta " + std::to_string(zeta) + " " +
                                 std::to_string(distance_mm) + " mm";
        const long deferred = ExpectSameAsEverySubstep(s, what);
        // At least 80% of the motion's periods (a damped run's settling tail is closed form,
        // not ticked at all).
        const RunResult run = RunScenario(s, Deferred());
        EXPECT_GT(static_cast<double>(deferred), 0.8 * run.metrics.motion_time_s / s.controller.period_s) << what;
      }
    }
  }
}

// Tests random single-axis moves (mode, damping, feed, acc/dec time, distance, the
// pattern's design frequency, the period; seeded): the same metrics bit for bit.
TEST(DeferredSubsteps, RandomMovesSameAsEverySubstep) {
  std::mt19937 random(2026);
  long deferred = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Scenario s = testing::RandomSdofMove(&random, trial);
    deferred += ExpectSameAsEverySubstep(s, "trial " + std::to_string(trial));
  }
  EXPECT_GT(deferred, 0);
}

// Tests a one-block program whose line starts away from 0 (the tool's distance from the
// line is then a rounding residue, not an exact 0, wherever the tool is within it).
TEST(DeferredSubsteps, LineAwayFromZeroSameAsEverySubstep) {
  for (double hz : {17.0, 25.0, 33.3}) {
    Scenario s = testing::SdofScenario(hz, 0.02);
    controller::Program program;
    program.start_m = Eigen::Vector3d(0.0, 0.0375, 0.0);
    controller::ProgramBlock block;
    block.start_m = program.start_m;
    block.end_m = Eigen::Vector3d(0.0, 0.1625, 0.0);
    program.blocks.push_back(block);
    s.program = program;
    EXPECT_GT(ExpectSameAsEverySubstep(s, std::to_string(hz) + " Hz from 37.5 mm"), 0);
  }
}

// Tests QuadraticRange against a dense evaluation of the quadratic (the vertex inside,
// outside and at an end of the interval).
TEST(DeferredSubsteps, QuadraticRangeHoldsEverySample) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double p0 = u(random);
    const double v0 = u(random);
    const double half_a = trial % 5 == 0 ? 0.0 : 50.0 * u(random);
    const double h = 0.001 + 0.01 * std::abs(u(random));
    double lo = 0.0;
    double hi = 0.0;
    QuadraticRange(p0, v0, half_a, h, &lo, &hi);
    double seen_lo = HUGE_VAL;
    double seen_hi = -HUGE_VAL;
    for (int i = 0; i <= 1000; ++i) {
      const double t = h * i / 1000.0;
      const double p = p0 + v0 * t + half_a * t * t;
      seen_lo = std::min(seen_lo, p);
      seen_hi = std::max(seen_hi, p);
    }
    // The range is the exact one (to rounding): it holds every sample and is no wider
    // than the samples' range by more than the grid's resolution of the vertex.
    EXPECT_LE(lo, seen_lo + 1e-15) << trial;
    EXPECT_GE(hi, seen_hi - 1e-15) << trial;
    const double resolution = std::abs(half_a) * std::pow(h / 1000.0, 2) + 1e-15;
    EXPECT_GE(lo, seen_lo - resolution) << trial;
    EXPECT_LE(hi, seen_hi + resolution) << trial;
  }
}

// Tests OffLineBound against the single-axis samples' own arithmetic (single_axis_sampler.cc: the tool
// clamped onto the line), for tool positions all over [lo, hi]: every distance within the
// bound, and exactly 0 where the bound says 0.
TEST(DeferredSubsteps, OffLineBoundHoldsTheSamplesArithmetic) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int exact_zero = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double start = trial % 2 == 0 ? 0.0 : 0.3 * (u(random) - 0.5);
    const double direction = trial % 4 < 2 ? 1.0 : -1.0;
    const double length = 0.2 * u(random) + 1e-3;
    // Intervals inside the line, across its ends, and beyond them.
    const double centre = start + direction * length * (1.4 * u(random) - 0.2);
    const double half = length * 0.1 * u(random) * u(random);
    const double lo = centre - half;
    const double hi = centre + half;
    const double bound = OffLineBound(start, direction, length, lo, hi);
    if (bound == 0.0) ++exact_zero;
    for (int i = 0; i <= 200; ++i) {
      const double actual = lo + (hi - lo) * i / 200.0;
      const double along = std::clamp((actual - start) * direction, 0.0, length);
      const double off = actual - (start + along * direction);
      if (bound == 0.0) {
        EXPECT_EQ(off, 0.0) << trial << " " << actual;
      } else {
        EXPECT_LE(std::abs(off), bound) << trial << " " << actual;
      }
    }
  }
  EXPECT_GT(exact_zero, 200);  // the exact-zero case was exercised
}

// Tests InnerSampleBound: at least the largest |value| of the ends and the inside
// extremum, and within the stated margin of it.
TEST(DeferredSubsteps, InnerSampleBoundIsTheLargestWithItsMargin) {
  EXPECT_GE(InnerSampleBound(-3e-5, 1e-5, 2e-5, 1e-4), 3e-5);
  EXPECT_GE(InnerSampleBound(1e-6, -1e-6, 4e-5, 1e-4), 4e-5);
  EXPECT_LE(InnerSampleBound(1e-6, -1e-6, 4e-5, 1e-4), 4e-5 + 2e-9 * 1.4e-4);
  EXPECT_TRUE(std::isnan(InnerSampleBound(NAN, 0.0, 0.0, 1.0)));
  EXPECT_TRUE(std::isnan(InnerSampleBound(0.0, NAN, 0.0, 1.0)));
  EXPECT_TRUE(std::isnan(InnerSampleBound(0.0, 0.0, NAN, 1.0)));
}

}  // namespace
}  // namespace shapebench::bench
