// Every class of bad input is a ConfigError at the offending node's FILE:LINE:COL (or
// --set:N:1) with the key path, the form the CLI prints after "error: ".
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ErrorOf;
using testing::ExpectError;
using testing::ScratchDir;

ConfigError LoadError(const std::string& path, const std::vector<std::string>& sets = {}) {
  return testing::ErrorOf([&] { LoadScenario(path, ParseOverrides(sets)); });
}


// Tests that what() has the documented "FILE:LINE:COL: key.path: message" form.
TEST(ScenarioLoaderErrors, WhatHasFileLineColumnKeyPath) {
  EXPECT_STREQ(ConfigError("a.yaml", 3, 7, "controller.period_s", "must be > 0").what(),
               "a.yaml:3:7: controller.period_s: must be > 0");
  EXPECT_STREQ(ConfigError("a.yaml", 0, 0, "", "cannot open file").what(),
               "a.yaml: cannot open file");
}

// Tests that malformed YAML is reported at yaml-cpp's mark.
TEST(ScenarioLoaderErrors, MalformedYaml) {
  const std::string path = DataPath("malformed.yaml");
  ExpectError(LoadError(path), path, 3, 1, "", "malformed YAML");
}

// Tests that an unknown key is reported at the key, listing the allowed keys.
TEST(ScenarioLoaderErrors, UnknownKeyListsAllowedKeys) {
  const std::string path = DataPath("unknown_key.yaml");
  ExpectError(LoadError(path), path, 3, 3, "controller.feed_rate",
              "unknown key 'feed_rate'; allowed: period_s, feed_mm_min, accel_time_s, "
              "rapid_feed_mm_min, corner_velocity_change_mm_min, junction_deviation_mm, pattern, "
              "post_interp");
}

// Tests that an unknown top-level key lists the scenario keys.
TEST(ScenarioLoaderErrors, UnknownTopLevelKey) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "move: {distance_mm: 5}\nmachnie: {}\n");
  ExpectError(LoadError(path), path, 2, 1, "machnie",
              "allowed: name, machine, drive, controller, move, program, program_file, program_strict, "
              "program_dialect, program_arc_tolerance, program_max_iterations, output, "
              "integrator, checks");
}

// Tests that a non-number where a number belongs says so at the value's own position.
TEST(ScenarioLoaderErrors, WrongTypeNumber) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "controller:\n  period_s: fast\n");
  ExpectError(LoadError(path), path, 2, 13, "controller.period_s", "expected a number");
  const std::string quoted = dir.Write("q.yaml", "move: {distance_mm: \"10\"}\n");
  ExpectError(LoadError(quoted), quoted, 1, 21, "move.distance_mm", "expected a number");
  const std::string mapping = dir.Write("m.yaml", "move: {distance_mm: {x: 1}}\n");
  ExpectError(LoadError(mapping), mapping, 1, 21, "move.distance_mm", "expected a number");
}

// Tests that an enumerated key lists its choices.
TEST(ScenarioLoaderErrors, WrongTypeChoice) {
  ScratchDir dir;
  const std::string method = dir.Write("m.yaml", "controller:\n  pattern: {method: 5}\n");
  ExpectError(LoadError(method), method, 2, 21, "controller.pattern.method",
              "expected one of none|1|2|3|4");
  const std::string mode = dir.Write("o.yaml", "controller:\n  pattern:\n    mode: always\n");
  ExpectError(LoadError(mode), mode, 3, 11, "controller.pattern.mode",
              "expected one of off|start|end|both");
  const std::string lmm = dir.Write("l.yaml", "integrator: {lmm: rk4}\n");
  ExpectError(LoadError(lmm), lmm, 1, 19, "integrator.lmm", "expected one of adams|bdf");
  const std::string steps = dir.Write("n.yaml", "integrator: {max_num_steps: 1.5}\n");
  ExpectError(LoadError(steps), steps, 1, 29, "integrator.max_num_steps", "expected an integer");
}

// Tests that the drive's type lists its choices and that servo settings need the servo.
TEST(ScenarioLoaderErrors, DriveTypeAndServoKeys) {
  ScratchDir dir;
  const std::string type = dir.Write("t.yaml", "drive: {type: stepper}\n");
  ExpectError(LoadError(type), type, 1, 15, "drive.type", "expected one of kinematic|servo");
  const std::string kinematic =
      dir.Write("k.yaml", "drive: {type: kinematic, velocity_feedforward: 0.5}\n");
  ExpectError(LoadError(kinematic), kinematic, 1, 48, "drive.velocity_feedforward",
              "needs type: servo");
  const std::string untyped = dir.Write("u.yaml", "drive:\n  position_gain: 30\n");
  ExpectError(LoadError(untyped), untyped, 2, 18, "drive.position_gain", "needs type: servo");
  const std::string unknown = dir.Write("x.yaml", "drive: {type: servo, kv: 3}\n");
  ExpectError(LoadError(unknown), unknown, 1, 22, "drive.kv",
              "allowed: type, position_gain, velocity_feedforward, velocity_loop_hz, "
              "motor_mass_kg");
}

// Tests that invalid servo settings are located at their values with what is allowed.
TEST(ScenarioLoaderErrors, ServoSettingsInvalid) {
  ScratchDir dir;
  const std::string gain =
      dir.Write("g.yaml", "drive:\n  type: servo\n  position_gain: -30\n");
  ExpectError(LoadError(gain), gain, 3, 18, "drive.position_gain",
              "must be finite and > 0 (1/s; Kp = 1 / T2) (got -30)");
  const std::string feedforward =
      dir.Write("f.yaml", "drive: {type: servo, velocity_feedforward: 1.5}\n");
  ExpectError(LoadError(feedforward), feedforward, 1, 44, "drive.velocity_feedforward",
              "must be in [0, 1] (0 = none, 1 = full) (got 1.5)");
  const std::string loop = dir.Write("l.yaml", "drive: {type: servo, velocity_loop_hz: -1}\n");
  ExpectError(LoadError(loop), loop, 1, 40, "drive.velocity_loop_hz", "must be finite and >= 0");
  const std::string mass = dir.Write("m.yaml", "drive: {type: servo, motor_mass_kg: 0}\n");
  ExpectError(LoadError(mass), mass, 1, 37, "drive.motor_mass_kg", "must be finite and > 0");
  ExpectError(LoadError(DataPath("uses_machine_file.yaml"),
                        {"drive={type: servo}", "drive.velocity_feedforward=2"}),
              "--set", 2, 1, "drive.velocity_feedforward", "must be in [0, 1]");
}

// Tests that a mode frequency <= 0 is located at the value.
TEST(ScenarioLoaderErrors, ModeFrequencyNotPositive) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", R"(machine:
  modes:
    - {frequency_hz: 25.0}
    - {frequency_hz: 0.0}
)");
  ExpectError(LoadError(path), path, 4, 22, "machine.modes[1].frequency_hz", "");
}

// Tests that the pattern's design frequency <= 0 is located at the value.
TEST(ScenarioLoaderErrors, PatternFrequencyNotPositive) {
  ScratchDir dir;
  const std::string path =
      dir.Write("s.yaml", "controller:\n  pattern: {method: 1, frequency_hz: -25}\n");
  ExpectError(LoadError(path), path, 2, 38, "controller.pattern.frequency_hz", "");
}

// Tests that damping ratios outside [0, 1) are located at the value.
TEST(ScenarioLoaderErrors, DampingOutsideRange) {
  ScratchDir dir;
  const std::string one = dir.Write("a.yaml", "machine:\n  modes: [{damping_ratio: 1.0}]\n");
  ExpectError(LoadError(one), one, 2, 27, "machine.modes[0].damping_ratio", "");
  const std::string negative =
      dir.Write("b.yaml", "machine:\n  modes: [{damping_ratio: -0.1}]\n");
  ExpectError(LoadError(negative), negative, 2, 27, "machine.modes[0].damping_ratio", "");
}

// Tests that an interpolation period <= 0 is located at the value.
TEST(ScenarioLoaderErrors, PeriodNotPositive) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "controller:\n  period_s: 0\n");
  ExpectError(LoadError(path), path, 2, 13, "controller.period_s", "");
}

// Tests that a negative acceleration time is located at the value.
TEST(ScenarioLoaderErrors, AccelTimeNegative) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "controller:\n  accel_time_s: -0.01\n");
  ExpectError(LoadError(path), path, 2, 17, "controller.accel_time_s", "");
}

// Tests that method 3's k1 outside [0.5, 1] is located at the value.
TEST(ScenarioLoaderErrors, K1OutsideRange) {
  ScratchDir dir;
  const std::string path =
      dir.Write("s.yaml", "controller:\n  pattern:\n    method: 3\n    k1: 0.4\n");
  ExpectError(LoadError(path), path, 4, 9, "controller.pattern.k1", "");
  const std::string high =
      dir.Write("h.yaml", "controller:\n  pattern:\n    method: 3\n    k1: 1.2\n");
  ExpectError(LoadError(high), high, 4, 9, "controller.pattern.k1", "");
}

// Tests that method 4's t1 outside [0, T/6] is located at the value, or at the pattern
// mapping when the offending value is the default that was not written.
TEST(ScenarioLoaderErrors, T1OutsideRange) {
  ScratchDir dir;
  const std::string path =
      dir.Write("s.yaml", "controller:\n  pattern:\n    method: 4\n    t1_s: 0.01\n");
  ExpectError(LoadError(path), path, 4, 11, "controller.pattern.t1_s", "");
  const std::string negative =
      dir.Write("n.yaml", "controller:\n  pattern:\n    method: 4\n    t1_s: -0.001\n");
  ExpectError(LoadError(negative), negative, 4, 11, "controller.pattern.t1_s", "");
  // Default t1_s = 0.004 s exceeds T/6 = 0.00167 s at 100 Hz: nearest parent is the pattern.
  const std::string defaulted =
      dir.Write("d.yaml", "controller:\n  pattern:\n    method: 4\n    frequency_hz: 100\n");
  ExpectError(LoadError(defaulted), defaulted, 3, 5, "controller.pattern.t1_s", "");
}

// Tests that a move too short for its pattern is a load error at move.distance_mm.
TEST(ScenarioLoaderErrors, MoveTooShortForPattern) {
  ScratchDir dir;
  const std::string path =
      dir.Write("s.yaml", "controller: {pattern: {method: 2}}\nmove: {distance_mm: 0.01}\n");
  ExpectError(LoadError(path), path, 2, 21, "move.distance_mm", "too short");
}

// Tests that errors inside a referenced machine file name that file and its position.
TEST(ScenarioLoaderErrors, ErrorInReferencedMachineFile) {
  ExpectError(LoadError(DataPath("uses_bad_machine_file.yaml")),
              DataPath("machines/bad_damping.yaml"), 3, 41, "machine.modes[1].damping_ratio", "");
}

// Tests that malformed YAML in a referenced machine file names that file.
TEST(ScenarioLoaderErrors, MalformedReferencedMachineFile) {
  ScratchDir dir;
  const std::string machine = dir.Write("m/broken.yaml", "modes: [{frequency_hz: 25}\n");
  const std::string path = dir.Write("s.yaml", "machine: m/broken.yaml\n");
  const ConfigError error = LoadError(path);
  EXPECT_EQ(error.file(), machine) << error.what();
  EXPECT_GT(error.line(), 0);
}

// Tests that a missing machine file is reported at the scenario's `machine:` value.
TEST(ScenarioLoaderErrors, MissingMachineFile) {
  const std::string path = DataPath("uses_missing_machine_file.yaml");
  ExpectError(LoadError(path), path, 2, 10, "machine", "machines/does_not_exist.yaml");
}

// Tests that a missing scenario file is named, without a position.
TEST(ScenarioLoaderErrors, MissingScenarioFile) {
  ExpectError(LoadError("/nonexistent/scenario.yaml"), "/nonexistent/scenario.yaml", 0, 0, "",
              "cannot open file");
}

// Tests that an empty file and a non-mapping top level are refused.
TEST(ScenarioLoaderErrors, TopLevelNotAMapping) {
  ScratchDir dir;
  const std::string empty = dir.Write("e.yaml", "# nothing\n");
  ExpectError(LoadError(empty), empty, 1, 1, "", "expected a mapping");
  const std::string list = dir.Write("l.yaml", "- 1\n- 2\n");
  ExpectError(LoadError(list), list, 1, 1, "", "expected a mapping");
}

// Tests that modal and lumped keys cannot be mixed, and a machine needs one form.
TEST(ScenarioLoaderErrors, MachineFormsDoNotMix) {
  ScratchDir dir;
  const std::string mixed = dir.Write(
      "m.yaml", "machine:\n  modes: [{frequency_hz: 25}]\n  bodies: [{name: a, mass_kg: 1}]\n");
  ExpectError(LoadError(mixed), mixed, 3, 11, "machine.bodies", "lumped form");
  const std::string neither = dir.Write("n.yaml", "machine: {}\n");
  ExpectError(LoadError(neither), neither, 1, 10, "machine", "expected 'modes'");
}

// Tests that a key given twice is refused at its second occurrence.
TEST(ScenarioLoaderErrors, DuplicateKey) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "move: {distance_mm: 5, distance_mm: 6}\n");
  ExpectError(LoadError(path), path, 1, 24, "move.distance_mm", "duplicate key");
}

// Tests that checks name known metrics and carry sensible bounds.
TEST(ScenarioLoaderErrors, BadChecks) {
  ScratchDir dir;
  const std::string metric = dir.Write("a.yaml", "checks:\n  peak: {max: 1}\n");
  ExpectError(LoadError(metric), metric, 2, 3, "checks.peak", "allowed: static_displacement_m");
  const std::string empty = dir.Write("b.yaml", "checks:\n  peak_ratio: {}\n");
  ExpectError(LoadError(empty), empty, 2, 15, "checks.peak_ratio", "expected min and/or max");
  const std::string inverted = dir.Write("c.yaml", "checks:\n  peak_ratio: {min: 2, max: 1}\n");
  ExpectError(LoadError(inverted), inverted, 2, 15, "checks.peak_ratio", "above max");
  const std::string bound = dir.Write("d.yaml", "checks:\n  peak_ratio: {maximum: 1}\n");
  ExpectError(LoadError(bound), bound, 2, 16, "checks.peak_ratio.maximum", "allowed: min, max");
}

// Tests that a --set value failing validation is reported as --set:N:1 with its key path.
TEST(ScenarioLoaderErrors, SetValueInvalid) {
  const std::string path = DataPath("uses_machine_file.yaml");
  ExpectError(LoadError(path, {"controller.feed_mm_min=3000", "machine.modes[0].frequency_hz=-5"}),
              "--set", 2, 1, "machine.modes[0].frequency_hz", "");
  ExpectError(LoadError(path, {"controller.period_s=zero"}), "--set", 1, 1, "controller.period_s",
              "expected a number");
}

// Tests that a --set path to an unknown key is reported against the --set.
TEST(ScenarioLoaderErrors, SetUnknownKey) {
  ExpectError(LoadError(DataPath("uses_machine_file.yaml"), {"controller.pattern.methd=1"}),
              "--set", 1, 1, "controller.pattern.methd", "unknown key 'methd'");
}

// Tests that --set refuses out-of-range indices, paths through scalars, malformed
// values and options without '='.
TEST(ScenarioLoaderErrors, SetMalformed) {
  const std::string path = DataPath("uses_machine_file.yaml");
  ExpectError(LoadError(path, {"move.distance_mm=10", "machine.modes[2].gain=1"}), "--set", 2, 1,
              "machine.modes[2].gain", "out of range");
  ExpectError(LoadError(path, {"move.distance_mm.x=1"}), "--set", 1, 1, "move.distance_mm.x",
              "not a mapping");
  // An index into a key the section does not allow: that key is unknown.
  ExpectError(LoadError(path, {"controller.extra[0]=1"}), "--set", 1, 1, "controller.extra",
              "unknown key 'extra'");
  // One it allows but the input lacks: the whole sequence must be set.
  ExpectError(LoadError(path, {"controller.pattern.frequencies_hz[0]=1"}), "--set", 1, 1,
              "controller.pattern.frequencies_hz[0]", "does not exist; set the whole sequence");
  ExpectError(LoadError(path, {"move=[1"}), "--set", 1, 1, "move", "malformed YAML value");
  ExpectError(LoadError(path, {"move.distance_mm"}), "--set", 1, 1, "", "expected KEY=VALUE");
  ExpectError(LoadError(path, {"move..x=1"}), "--set", 1, 1, "move..x", "not a key path");
}

// Tests that a later --set of a parent takes over the location of an earlier child's.
TEST(ScenarioLoaderErrors, LaterSetOfParentOwnsTheSubtree) {
  const std::string path = DataPath("uses_machine_file.yaml");
  ExpectError(LoadError(path, {"machine.modes[0].gain=2", "machine={modes: [{frequency_hz: 0}]}"}),
              "--set", 2, 1, "machine.modes[0].frequency_hz", "");
  // A --set below the machine file leaves the file's other values located in the file.
  ExpectError(LoadError(path, {"machine.modes[0].gain=2", "machine.modes[1].damping_ratio=1"}),
              "--set", 2, 1, "machine.modes[1].damping_ratio", "");
}

// Tests that LocateValidationError maps a scenario-root field to its position.
TEST(ScenarioLoaderErrors, LocatesLaterValidationErrors) {
  const std::string path = DataPath("uses_machine_file.yaml");
  ExpectError(LocateValidationError(path, {}, ValidationError("move.distance_mm", "bad")), path, 5,
              21, "move.distance_mm", "bad");
  ExpectError(LocateValidationError(path, {}, ValidationError("machine.modes[1].gain", "bad")),
              DataPath("machines/two_modes.yaml"), 4, 53, "machine.modes[1].gain", "bad");
}

// Tests that LoadMachine locates errors in a machine file given directly.
TEST(ScenarioLoaderErrors, LoadMachineErrors) {
  const std::string path = DataPath("machines/bad_damping.yaml");
  try {
    LoadMachine(path, {});
    ADD_FAILURE() << "loaded";
  } catch (const ConfigError& error) {
    ExpectError(error, path, 3, 41, "machine.modes[1].damping_ratio", "");
  }
  try {
    LoadMachine(DataPath("machines/two_modes.yaml"), ParseOverrides({"modes[0].typo=1"}));
    ADD_FAILURE() << "loaded";
  } catch (const ConfigError& error) {
    ExpectError(error, "--set", 1, 1, "machine.modes[0].typo", "unknown key 'typo'");
  }
}

}  // namespace
}  // namespace shapebench::bench
