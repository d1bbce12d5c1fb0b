// A pattern left to the machine (bench/scenario/pattern_defaults.h): frequency_hz not given
// is the lowest participating mode of the moved axes; `design_damping_ratio: machine`
// and `frequencies_hz: machine` take the modes' own damping; a sweep keeps the base
// scenario's design; the run reports pattern_frequency_hz and pattern_damping_ratio.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ErrorOf;
using testing::ScratchDir;

std::string Configs(const std::string& name) { return std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/" + name; }

// A modal machine of (frequency, damping, gain) modes.
std::string Modes(const std::vector<std::array<double, 3>>& modes) {
  std::string text = "machine:\n  modes:\n";
  for (const auto& m : modes) {
    text += "    - {frequency_hz: " + std::to_string(m[0]) + ", damping_ratio: " + std::to_string(m[1]) +
            ", gain: " + std::to_string(m[2]) + "}\n";
  }
  return text;
}

const std::string kZvdMove =
    "controller: {period_s: 0.001, feed_mm_min: 12000, accel_time_s: 0.1, pattern: {method: zvd}}\n"
    "move: {distance_mm: 100}\nintegrator: {method: exact}\n";

// Tests that a mode carrying less than 1% of the static deflection does not count: the
// 5 Hz mode of gain 0.0001 contributes 0.0001/5^2 against 1/20^2 of the 20 Hz one (0.16%),
// so the pattern is designed for 20 Hz; with gain 0.001 (1.6%) for 5 Hz.
TEST(PatternDefaults, LowestModeBelowOnePercentDoesNotParticipate) {
  ScratchDir dir;
  const Scenario low = LoadScenario(
      dir.Write("low.yaml", Modes({{5.0, 0.0, 0.0001}, {20.0, 0.0, 1.0}}) + kZvdMove), {});
  EXPECT_EQ(low.controller.pattern.frequency_hz, 20.0);
  EXPECT_TRUE(low.controller.pattern.frequency_from_machine);
  const Scenario participating = LoadScenario(
      dir.Write("part.yaml", Modes({{5.0, 0.0, 0.001}, {20.0, 0.0, 1.0}}) + kZvdMove), {});
  EXPECT_EQ(participating.controller.pattern.frequency_hz, 5.0);
}

// Tests that only the moved axes count, the lowest over several of them, on the lumped
// moving column (its modal analysis): a Z move is designed for Z's 93 Hz head mode, an
// X+Z move for the 25 Hz of X.
TEST(PatternDefaults, MovedAxesOfALumpedMachine) {
  const std::string machine = Configs("machines/moving_column.yaml");
  ScratchDir dir;
  const std::string head = "machine: " + machine +
                           "\ncontroller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.1, "
                           "pattern: {method: zv}}\n";
  const Scenario z = LoadScenario(dir.Write("z.yaml", head + "program:\n  - {g: 1, z: -50}\n"), {});
  EXPECT_NEAR(z.controller.pattern.frequency_hz, 93.1, 0.1);
  const Scenario xz = LoadScenario(dir.Write("xz.yaml", head + "program:\n  - {g: 1, x: 50, z: -50}\n"), {});
  EXPECT_NEAR(xz.controller.pattern.frequency_hz, 25.0, 0.01);
  const DesignModes modes = FindDesignModes(xz.machine, xz.RunProgram());
  EXPECT_EQ(modes.axes, "x, z");
  for (std::size_t i = 1; i < modes.modes.size(); ++i) {
    EXPECT_GT(modes.modes[i].frequency_hz, modes.modes[i - 1].frequency_hz);
  }
}

// Tests that `design_damping_ratio: machine` takes the chosen mode's damping, and that
// `frequencies_hz: machine` with it takes every participating mode with its own.
TEST(PatternDefaults, DampingAndFrequenciesFromTheMachine) {
  const std::string gantry = Configs("scenarios/gantry_zvd.yaml");
  const Scenario one = LoadScenario(gantry, {{"controller.pattern.design_damping_ratio", "machine"}});
  EXPECT_EQ(one.controller.pattern.frequency_hz, 18.0);
  EXPECT_NEAR(one.controller.pattern.design_damping_ratio, 0.02, 1e-12);
  const Scenario both = LoadScenario(gantry, {{"controller.pattern.frequencies_hz", "machine"},
                                              {"controller.pattern.design_damping_ratio", "machine"}});
  EXPECT_EQ(both.controller.pattern.frequencies_hz, (std::vector<double>{18.0, 55.0}));
  ASSERT_EQ(both.controller.pattern.damping_ratios.size(), 2u);
  EXPECT_NEAR(both.controller.pattern.damping_ratios[0], 0.02, 1e-12);
  EXPECT_NEAR(both.controller.pattern.damping_ratios[1], 0.04, 1e-12);
  // Given frequencies take the damping of the nearest participating mode.
  const Scenario given = LoadScenario(gantry, {{"controller.pattern.frequencies_hz", "[50, 20]"},
                                               {"controller.pattern.design_damping_ratio", "machine"}});
  EXPECT_EQ(given.controller.pattern.damping_ratios, (std::vector<double>{0.04, 0.02}));
}

// Tests the shipped gantry scenario: designed at 18.00 Hz (reported), residual below 1%;
// one ZVD per mode at its own damping leaves below 0.1%.
TEST(PatternDefaults, GantryScenario) {
  const std::string gantry = Configs("scenarios/gantry_zvd.yaml");
  const Metrics lowest = RunScenario(LoadScenario(gantry, {})).metrics;
  EXPECT_NEAR(lowest.pattern_frequency_hz, 18.0, 0.005);
  EXPECT_EQ(lowest.pattern_damping_ratio, 0.0);
  EXPECT_LT(lowest.residual_ratio, 0.01);
  const Metrics every = RunScenario(LoadScenario(gantry, {{"controller.pattern.frequencies_hz", "machine"},
                                                          {"controller.pattern.design_damping_ratio", "machine"}}))
                            .metrics;
  EXPECT_NEAR(every.pattern_frequency_hz, 18.0, 0.005);
  EXPECT_NEAR(every.pattern_damping_ratio, 0.02, 1e-12);
  EXPECT_LT(every.residual_ratio, 1e-3);
  const Metrics unshaped = RunScenario(LoadScenario(gantry, {{"controller.pattern.method", "none"}})).metrics;
  EXPECT_TRUE(std::isnan(unshaped.pattern_frequency_hz));
  EXPECT_TRUE(std::isnan(unshaped.pattern_damping_ratio));
}

// Tests that a machine rigid along the moved axes leaves a shaping pattern without a
// frequency as an error at controller.pattern, and keeps an unshaped one loadable.
TEST(PatternDefaults, RigidMachine) {
  ScratchDir dir;
  const std::string rigid = "machine: {axes: {}}\n";
  const ConfigError error = ErrorOf([&] { LoadScenario(dir.Write("r.yaml", rigid + kZvdMove), {}); });
  EXPECT_EQ(error.key_path(), "controller.pattern.frequency_hz") << error.what();
  EXPECT_NE(error.message().find("rigid"), std::string::npos) << error.what();
  EXPECT_NO_THROW(LoadScenario(dir.Write("r.yaml", rigid + kZvdMove), {{"controller.pattern.method", "none"}}));
  EXPECT_NO_THROW(LoadScenario(dir.Write("r.yaml", rigid + kZvdMove), {{"controller.pattern.frequency_hz", "30"}}));
}

// Tests that damping_ratios must match frequencies_hz in length, and go with it.
TEST(PatternDefaults, DampingRatiosLengthsAreChecked) {
  const std::string gantry = Configs("scenarios/gantry_zvd.yaml");
  const ConfigError length = ErrorOf([&] {
    LoadScenario(gantry, {{"controller.pattern.frequencies_hz", "[18, 55]"},
                          {"controller.pattern.damping_ratios", "[0.02]"}});
  });
  EXPECT_EQ(length.key_path(), "controller.pattern.damping_ratios") << length.what();
  const ConfigError alone =
      ErrorOf([&] { LoadScenario(gantry, {{"controller.pattern.damping_ratios", "[0.02]"}}); });
  EXPECT_NE(alone.message().find("frequencies_hz"), std::string::npos) << alone.what();
  const Scenario ok = LoadScenario(gantry, {{"controller.pattern.frequencies_hz", "[18, 55]"},
                                            {"controller.pattern.damping_ratios", "[0.02, 0.04]"}});
  EXPECT_EQ(ok.controller.pattern.damping_ratios, (std::vector<double>{0.02, 0.04}));
}

// Tests that a sweep of the plant keeps the base scenario's design: every point reports
// the base's 18 Hz whatever its own lowest mode, and the sweep carries a note saying so;
// with frequency_hz given there is no note.
TEST(PatternDefaults, SweepKeepsTheBaseDesign) {
  ScratchDir dir;
  const std::string sweep_text = "base: " + Configs("scenarios/gantry_zvd.yaml") +
                                 "\ngrid:\n  machine.modes[0].frequency_hz: [15, 18, 21]\n";
  const std::string path = dir.Write("sweep.yaml", sweep_text);
  const Sweep sweep = LoadSweep(path, {});
  EXPECT_NE(sweep.note.find("machine.modes[0].frequency_hz"), std::string::npos) << sweep.note;
  for (std::uint64_t p = 0; p < sweep.points; ++p) {
    const PointOutcome outcome = RunPoint(sweep, {}, p);
    ASSERT_TRUE(outcome.ok()) << outcome.error;
    EXPECT_NEAR(outcome.metrics.pattern_frequency_hz, 18.0, 1e-9) << p;
  }
  // The 15 Hz point, alone, would be designed for 15 Hz: the sweep's row is not.
  const Metrics alone =
      RunScenario(LoadScenario(sweep.base, MakePoint(sweep, 0, {}).overrides)).metrics;
  EXPECT_NEAR(alone.pattern_frequency_hz, 15.0, 1e-9);
  const std::vector<Override> fixed = {{"controller.pattern.frequency_hz", "18"}};
  EXPECT_TRUE(LoadSweep(path, fixed).note.empty());
}

// Tests that `sweep` says once on stderr that the points keep the base's design, and that
// results.csv's pattern_frequency_hz column holds it for every point.
TEST(PatternDefaults, SweepCommandNotesOnce) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "sweep.yaml", "base: " + Configs("scenarios/gantry_zvd.yaml") +
                        "\ngrid:\n  machine.modes[0].frequency_hz: [15, 21]\n"
                        "metrics: [residual_ratio, pattern_frequency_hz]\n");
  const testing::CliResult r =
      testing::RunCli({"sweep", path, "--jobs", "2", "--out", dir.File("out")}, dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The sweep is named by its canonical path: relative to the working directory, here `dir`.
  const std::string note = "note: sweep.yaml: the pattern's design is left to the machine";
  const std::size_t at = r.err.find(note);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(note, at + 1), std::string::npos) << r.err;
  const std::string csv = testing::ReadText(dir.File("out/results.csv"));
  EXPECT_NE(csv.find("\n0,15,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",18,ok,\n1,21,"), std::string::npos) << csv;
}

}  // namespace
}  // namespace shapebench::bench
