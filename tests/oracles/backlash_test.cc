// Backlash with table friction (configs/scenarios/backlash_reversal.yaml): the lost motion
// at a reversal and in a circle's contour, against the closed form. The gap b is centred
// (docs/nonlinear.md): sliding at constant speed, the nut pushes the table from one flank
// against its friction F, so the table lags the command by b/2 + F/k; reversed, it leads by
// as much; a reversal loses b + 2 F/k of table position (the play, and the contact's
// elastic stretch unloaded on one flank and loaded on the other).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

constexpr double kPlayM = 1.0e-5;
constexpr double kFrictionN = 200.0;
constexpr double kContactNM = 1.0e8;

std::string ReversalFile() { return std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/backlash_reversal.yaml"; }

// The table's mean deflection (table less command) over the second half of each cruise:
// block 0 out, block 1 back (the command's speed at the feed).
std::pair<double, double> CruiseDeflections(const Trace& trace) {
  double sums[2] = {0.0, 0.0};
  long counts[2] = {0, 0};
  const double feed = 0.01;  // 600 mm/min
  for (int block = 0; block < 2; ++block) {
    double first = HUGE_VAL;
    double last = -HUGE_VAL;
    for (std::size_t i = 0; i < trace.time_s.size(); ++i) {
      if (trace.block[i] == block && std::abs(std::abs(trace.command_velocity_m_s[i]) - feed) < 1e-12) {
        first = std::min(first, trace.time_s[i]);
        last = std::max(last, trace.time_s[i]);
      }
    }
    for (std::size_t i = 0; i < trace.time_s.size(); ++i) {
      if (trace.block[i] == block && trace.time_s[i] >= 0.5 * (first + last) && trace.time_s[i] <= last) {
        sums[block] += trace.deflection_axes_m[i](0);
        ++counts[block];
      }
    }
  }
  return {sums[0] / counts[0], sums[1] / counts[1]};
}

// Tests that a reversal loses b + 2 F/k of table position within 1e-3 of it (the cruises'
// means: the contact's ringing is damped out by then), each way b/2 + F/k; and without play
// 2 F/k (the contact's stretch alone). Counted from the unloaded contact point instead (the
// nut at the outgoing flank with no force: table less command -b/2, the F/k the outgoing
// contact gives back as it unloads left out), the table's lead on the way back is b + F/k:
// the play plus the stretch of the flank that pushes it back; also within 1e-3.
TEST(Backlash, AReversalLosesThePlayAndTheContactStretch) {
  const RunResult run = RunScenario(LoadScenario(ReversalFile(), {}));
  const auto [out, back] = CruiseDeflections(run.trace);
  const double lost = kPlayM + 2.0 * kFrictionN / kContactNM;  // 14 um
  EXPECT_NEAR(back - out, lost, 1e-3 * lost);
  EXPECT_NEAR(out, -0.5 * lost, 1e-3 * lost);  // lagging on the way out
  EXPECT_NEAR(back, 0.5 * lost, 1e-3 * lost);  // leading on the way back
  const double from_unloaded = kPlayM + kFrictionN / kContactNM;  // 12 um
  EXPECT_NEAR(back - (-0.5 * kPlayM), from_unloaded, 1e-3 * from_unloaded);
  EXPECT_NEAR((back - out) - kFrictionN / kContactNM, from_unloaded, 1e-3 * from_unloaded);
  const RunResult tight = RunScenario(LoadScenario(ReversalFile(), {{"machine.elements[0].backlash_m", "0"}}));
  const auto [tight_out, tight_back] = CruiseDeflections(tight.trace);
  const double stretch = 2.0 * kFrictionN / kContactNM;
  EXPECT_NEAR(tight_back - tight_out, stretch, 1e-3 * stretch);
  EXPECT_GT(run.stats.events, tight.stats.events);  // the gap's edges are events too
}

// Tests that the lost motion shows in a circle's contour error: an XY table, each axis the
// reversal scenario's, on a 10 mm circle (entered at 45 degrees) at 600 mm/min. At each
// axis reversal the stuck table sits b/2 + F/k inside the circle while the other axis runs
// along the tangent: the largest contour error is b/2 + F/k (within 2%: the contact's
// ringing), where without play it is about F/k; the play adds b/2 (within 10%).
TEST(Backlash, TheLostMotionShowsInACirclesContourError) {
  testing::ScratchDir dir;
  const std::string axis =
      "      bodies: [{name: table, mass_kg: 50}]\n"
      "      elements:\n"
      "        - {name: screw, from: driven, to: table, stiffness_n_m: 1.0e+8, backlash_m: 1.0e-5}\n"
      "        - {name: ways, from: table, to: ground, friction: {model: coulomb, coulomb_n: 200}}\n"
      "        - {name: nut_damping, from: driven, to: table, damping_n_s_m: 2000}\n"
      "      output: {body: table}\n";
  const std::string corner = "7.0710678118654755";
  const std::string path = dir.Write(
      "circle.yaml", "machine:\n  axes:\n    x:\n" + axis + "    y:\n" + axis +
                         "controller: {period_s: 0.001, feed_mm_min: 600, accel_time_s: 0.05}\n"
                         "program:\n  - {g: 1, x: " + corner + ", y: " + corner + ", f: 600}\n"
                         "  - {g: 3, x: " + corner + ", y: " + corner + ", i: -" + corner + ", j: -" + corner +
                         ", f: 600}\n");
  const double lag = 0.5 * kPlayM + kFrictionN / kContactNM;  // 7 um
  const RunResult play = RunScenario(LoadScenario(path, {}), {false});
  EXPECT_NEAR(play.metrics.max_contour_error_m, lag, 0.02 * lag);
  const RunResult tight = RunScenario(LoadScenario(path, {{"machine.axes.x.elements[0].backlash_m", "0"},
                                                          {"machine.axes.y.elements[0].backlash_m", "0"}}),
                                      {false});
  EXPECT_NEAR(play.metrics.max_contour_error_m - tight.metrics.max_contour_error_m, 0.5 * kPlayM, 0.1 * 0.5 * kPlayM);
}

// Tests that a backlash element the rigid motion would stretch (from the table to the
// ground) is refused at the element, naming it, and that one needs a contact stiffness.
TEST(Backlash, AnElementOffTheDrivesPathIsRefused) {
  testing::ScratchDir dir;
  const std::string path = dir.Write(
      "s.yaml",
      "machine:\n"
      "  bodies: [{name: table, mass_kg: 50}]\n"
      "  elements:\n"
      "    - {name: screw, from: driven, to: table, stiffness_n_m: 1.0e+8}\n"
      "    - {name: stop, from: table, to: ground, stiffness_n_m: 1.0e+6, backlash_m: 1.0e-3}\n"
      "  output: {body: table}\n"
      "move: {distance_mm: 10}\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadScenario(path, {}); }), path, 5, 7, "machine.elements[1]",
                       "element \"stop\" (table - ground) has backlash and stretches by");
  const std::string soft = dir.Write(
      "t.yaml",
      "machine:\n"
      "  bodies: [{name: table, mass_kg: 50}]\n"
      "  elements:\n"
      "    - {name: screw, from: driven, to: table, stiffness_n_m: 1.0e+8}\n"
      "    - {name: gap, from: driven, to: table, backlash_m: 1.0e-3}\n"
      "  output: {body: table}\n"
      "move: {distance_mm: 10}\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadScenario(soft, {}); }), soft, 5, 7,
                       "machine.elements[1].stiffness_n_m", "must be > 0 in an element with backlash_m");
}

}  // namespace
}  // namespace shapebench::bench
