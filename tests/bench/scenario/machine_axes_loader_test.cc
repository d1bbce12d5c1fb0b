// Reading the multi-axis machine (machine_reader.h: the single forms with `axis:`, the
// `axes:` form) and the drive, with FILE:LINE:COL errors; the shipped moving column.
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/scenario_loader.h"
#include "tests/support/axes.h"
#include "tests/support/bench_test_support.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::RunCli;
using testing::ErrorOf;
using testing::ExpectError;
using testing::ScratchDir;


const std::string kMovingColumn =
    std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/machines/moving_column.yaml";

ConfigError LoadMachineError(const std::string& path, const std::vector<std::string>& sets = {}) {
  return testing::ErrorOf([&] { LoadMachineAxes(path, ParseOverrides(sets)); });
}

ConfigError LoadScenarioError(const std::string& path) {
  return testing::ErrorOf([&] { LoadScenario(path, {}); });
}


double Frequency(const model::MachineConfig& machine, int mode) {
  return std::get<model::ModalMachineConfig>(machine.form).modes[mode].frequency_hz;
}

// Tests that a single form with `axis: x` models X alone and drives it; without `axis` it
// is Y, as the single forms always were.
TEST(MachineAxesLoader, SingleFormWithAxis) {
  ScratchDir dir;
  const model::MultiAxisMachineConfig on_x = LoadMachineAxes(
      dir.Write("x.yaml", "axis: x\nmodes:\n  - {frequency_hz: 30.0, gain: 1.0}\n"), {});
  EXPECT_TRUE(on_x.single_form);
  EXPECT_EQ(on_x.driven_axis, kX);
  ASSERT_TRUE(on_x.axes[kX].has_value());
  EXPECT_FALSE(on_x.axes[kY].has_value());
  EXPECT_FALSE(on_x.axes[kZ].has_value());
  EXPECT_EQ(Frequency(*on_x.axes[kX], 0), 30.0);

  const model::MultiAxisMachineConfig plain =
      LoadMachineAxes(DataPath("machines/two_modes.yaml"), {});
  EXPECT_EQ(plain.driven_axis, kY);
  ASSERT_TRUE(plain.axes[kY].has_value());
  EXPECT_FALSE(plain.axes[kX].has_value());

  const std::string scenario = dir.Write(
      "s.yaml", "machine:\n  axis: z\n  bodies: [{name: head, mass_kg: 500}]\n"
                "  elements: [{name: screw, from: head, to: driven, stiffness_n_m: 2.0e+8}]\n"
                "  output: {body: head}\nmove: {distance_mm: 10}\n");
  const model::MultiAxisMachineConfig on_z = LoadMachineAxes(scenario, {});
  EXPECT_EQ(on_z.driven_axis, kZ);
  ASSERT_TRUE(on_z.axes[kZ].has_value());
  EXPECT_TRUE(std::holds_alternative<model::LumpedMachineConfig>(on_z.axes[kZ]->form));
}

// Tests the multi-axis form: any subset of x, y, z, each a single form, and driven_axis.
TEST(MachineAxesLoader, MultiAxisForm) {
  ScratchDir dir;
  const std::string path = dir.Write("m.yaml", R"(axes:
  x:
    modes: [{frequency_hz: 40.0}]
  z:
    bodies: [{name: head, mass_kg: 500}]
    elements: [{name: screw, from: head, to: driven, stiffness_n_m: 2.0e+8}]
    output: {body: head}
driven_axis: z
)");
  const model::MultiAxisMachineConfig machine = LoadMachineAxes(path, {});
  EXPECT_FALSE(machine.single_form);
  EXPECT_EQ(machine.driven_axis, kZ);
  ASSERT_TRUE(machine.axes[kX].has_value());
  EXPECT_FALSE(machine.axes[kY].has_value());
  ASSERT_TRUE(machine.axes[kZ].has_value());
  EXPECT_EQ(Frequency(*machine.axes[kX], 0), 40.0);
  const std::vector<model::AxisModes> modes = model::AnalyzeMachineModes(machine);
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_EQ(modes[0].axis, kX);
  EXPECT_EQ(modes[1].axis, kZ);
  EXPECT_NEAR(modes[1].analysis.modes[0].frequency_hz,
              std::sqrt(2.0e8 / 500.0) / (2.0 * 3.14159265358979323846), 1e-9);

  // An axis left out is rigid, the driven one too (driven_axis defaults to y), and so is
  // every axis of `axes: {}`; the single-axis view then has nothing to show.
  const std::string no_y = dir.Write("n.yaml", "axes:\n  x:\n    modes: [{frequency_hz: 40.0}]\n");
  const model::MultiAxisMachineConfig x_only = LoadMachineAxes(no_y, {});
  EXPECT_EQ(x_only.driven_axis, kY);
  EXPECT_FALSE(x_only.axes[kY].has_value());
  ExpectError([&] {
    try {
      LoadMachine(no_y, {});
    } catch (const ConfigError& error) {
      return error;
    }
    return ConfigError("", 0, 0, "", "");
  }(), no_y, 0, 0, "machine", "the driven axis y is rigid");
  const model::MultiAxisMachineConfig rigid =
      LoadMachineAxes(dir.Write("r.yaml", "axes: {}\ndriven_axis: x\n"), {});
  EXPECT_EQ(rigid.driven_axis, kX);
  for (const auto& axis : rigid.axes) EXPECT_FALSE(axis.has_value());
}

// Tests that errors inside axes.x keep their full key path and their FILE:LINE:COL: an
// unknown key, an invalid value (validation), a bad axis name, a misplaced key.
TEST(MachineAxesLoader, ErrorLocationsInsideAxes) {
  ScratchDir dir;
  const std::string head = "axes:\n  x:\n    bodies:\n      - {name: a, mass_kg: 1}\n";
  const std::string tail =
      "    elements:\n"
      "      - {name: s, from: a, to: driven, stiffness_n_m: 1.0e+6}\n"
      "      - {name: t, from: b, to: a, stiffness_n_m: 1.0e+6}\n"
      "    output: {body: b}\n"
      "driven_axis: x\n";
  const std::string unknown = dir.Write("u.yaml", head + "      - {name: b, mas_kg: 2}\n" + tail);
  ExpectError(LoadMachineError(unknown), unknown, 5, 19, "machine.axes.x.bodies[1].mas_kg",
              "unknown key 'mas_kg'; allowed: name, mass_kg");
  const std::string invalid =
      dir.Write("i.yaml", head + "      - {name: b, mass_kg: -2}\n" + tail);
  ExpectError(LoadMachineError(invalid), invalid, 5, 28, "machine.axes.x.bodies[1].mass_kg",
              "must be finite and > 0");
  EXPECT_NO_THROW(LoadMachineAxes(
      dir.Write("ok.yaml", head + "      - {name: b, mass_kg: 2}\n" + tail), {}));

  const std::string axis_name = dir.Write("w.yaml", "axes:\n  w: {modes: [{frequency_hz: 9}]}\n");
  ExpectError(LoadMachineError(axis_name), axis_name, 2, 3, "machine.axes.w",
              "unknown key 'w'; allowed: x, y, z");
  const std::string inner_axis =
      dir.Write("a.yaml", "axes:\n  x: {axis: x, modes: [{frequency_hz: 9}]}\n");
  ExpectError(LoadMachineError(inner_axis), inner_axis, 2, 13, "machine.axes.x.axis",
              "'axis' belongs to the single-axis form");
  const std::string mixed =
      dir.Write("m.yaml", "modes: [{frequency_hz: 9}]\naxes:\n  y: {modes: [{frequency_hz: 9}]}\n");
  ExpectError(LoadMachineError(mixed), mixed, 1, 8, "machine.modes",
              "belongs to the single-axis form");
  const std::string driven =
      dir.Write("d.yaml", "modes: [{frequency_hz: 9}]\ndriven_axis: x\n");
  ExpectError(LoadMachineError(driven), driven, 2, 14, "machine.driven_axis",
              "belongs to the multi-axis form");
  const std::string bad_axis = dir.Write("b.yaml", "axis: w\nmodes: [{frequency_hz: 9}]\n");
  ExpectError(LoadMachineError(bad_axis), bad_axis, 1, 7, "machine.axis",
              "expected one of x|y|z, got 'w'");
  const std::string bad_driven = dir.Write(
      "v.yaml", "axes:\n  x: {modes: [{frequency_hz: 9}]}\ndriven_axis: 1\n");
  ExpectError(LoadMachineError(bad_driven), bad_driven, 3, 14, "machine.driven_axis",
              "expected one of x|y|z");
  const std::string neither = dir.Write("n.yaml", "machine: {axis: y}\n");
  ExpectError(LoadMachineError(neither), neither, 1, 10, "machine",
              "expected 'modes' (modal form) or 'bodies' (lumped mass-spring-damper form), or "
              "'axes'");
}

// Tests that --set reaches into axes (with or without "machine." on a machine file, and
// through a scenario that references the file) and that its errors name the --set.
TEST(MachineAxesLoader, OverridesInsideAxes) {
  ScratchDir dir;
  const std::string machine = dir.Write("machines/m.yaml",
                                        "axes:\n  x: {modes: [{frequency_hz: 40.0}]}\n"
                                        "  y: {modes: [{frequency_hz: 25.0}]}\n");
  EXPECT_EQ(Frequency(*LoadMachineAxes(machine, ParseOverrides({"machine.axes.x.modes[0]."
                                                                 "frequency_hz=31"}))
                           .axes[kX],
                      0),
            31.0);
  EXPECT_EQ(Frequency(*LoadMachineAxes(machine, ParseOverrides({"axes.x.modes[0].frequency_hz=32"}))
                           .axes[kX],
                      0),
            32.0);
  const std::string scenario =
      dir.Write("s.yaml", "machine: machines/m.yaml\nmove: {distance_mm: 10}\n");
  EXPECT_EQ(Frequency(*LoadMachineAxes(scenario, ParseOverrides({"machine.axes.x.modes[0]."
                                                                  "frequency_hz=33"}))
                           .axes[kX],
                      0),
            33.0);
  ExpectError(LoadMachineError(machine, {"axes.x.modes[0].frequency_hz=-1"}), "--set", 1, 1,
              "machine.axes.x.modes[0].frequency_hz", "must be finite and > 0");
  // An error in a referenced machine file names that file.
  const std::string bad = dir.Write("machines/bad.yaml",
                                    "axes:\n  y: {modes: [{frequency_hz: 25.0, "
                                    "damping_ratio: 1.5}]}\n");
  const std::string uses_bad =
      dir.Write("b.yaml", "machine: machines/bad.yaml\nmove: {distance_mm: 10}\n");
  ExpectError(LoadMachineError(uses_bad), bad, 2, 51, "machine.axes.y.modes[0].damping_ratio",
              "must be in [0, 1)");
}

// Tests the shipped moving column (configs/machines/moving_column.yaml): three axes, Y
// driven; the lowest X and Y modes at the patent's 25.00 Hz (within 0.01 Hz), Y's static
// tool-tip deflection 4.799 um per m/s^2 (8.00 um at 0.17 G; within 0.1%), Z stiff (its
// lowest mode above 60 Hz). The single-axis view is the Y chain.
TEST(MachineAxesLoader, MovingColumnHasThreeAxes) {
  const model::MultiAxisMachineConfig machine = LoadMachineAxes(kMovingColumn, {});
  EXPECT_FALSE(machine.single_form);
  EXPECT_EQ(machine.driven_axis, kY);
  const std::vector<model::AxisModes> modes = model::AnalyzeMachineModes(machine);
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_EQ(modes[kX].axis, kX);
  EXPECT_NEAR(modes[kX].analysis.modes.front().frequency_hz, 25.0, 0.01);
  EXPECT_NEAR(modes[kY].analysis.modes.front().frequency_hz, 25.0, 0.01);
  EXPECT_GT(modes[kZ].analysis.modes.front().frequency_hz, 60.0);
  EXPECT_NEAR(modes[kY].analysis.static_deflection_per_accel_s2, 4.799e-6, 4.799e-9);
  EXPECT_NEAR(1.667 * modes[kY].analysis.static_deflection_per_accel_s2, 8.00e-6, 0.01e-6);

  const model::MachineConfig y = LoadMachine(kMovingColumn, {});
  const auto& lumped = std::get<model::LumpedMachineConfig>(y.form);
  EXPECT_EQ(lumped.elements[1].name, "y_guides");
  EXPECT_EQ(lumped.elements[1].stiffness_n_m, 7.6176e7);

  // The demo scenario references it.
  const model::MultiAxisMachineConfig from_demo =
      LoadMachineAxes(std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/demo.yaml", {});
  EXPECT_TRUE(from_demo.axes[kX].has_value() && from_demo.axes[kZ].has_value());
}

// Tests `modes --json` on the moving column: every mode names its axis (x, then y, then
// z), static_deflection_per_accel_s2 is the driven axis' (Y) and the per-axis map has the
// three axes; a --set inside axes reaches the report.
TEST(MachineAxesLoader, ModesReportsEveryAxis) {
  const testing::CliResult r = RunCli({"modes", kMovingColumn, "--json"}, SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json.size(), 3u);
  ASSERT_EQ(json["modes"].size(), 4u + 4u + 3u);
  std::vector<std::string> axes;
  for (const auto& mode : json["modes"]) axes.push_back(mode["axis"].get<std::string>());
  EXPECT_EQ(axes, (std::vector<std::string>{"x", "x", "x", "x", "y", "y", "y", "y", "z", "z",
                                            "z"}));
  EXPECT_NEAR(json["modes"][0]["frequency_hz"].get<double>(), 25.0, 0.01);
  EXPECT_NEAR(json["modes"][4]["frequency_hz"].get<double>(), 25.0, 0.01);
  const nlohmann::json& by_axis = json["static_deflection_per_accel_s2_by_axis"];
  ASSERT_EQ(by_axis.size(), 3u);
  EXPECT_EQ(json["static_deflection_per_accel_s2"], by_axis["y"]);
  EXPECT_NEAR(by_axis["y"].get<double>(), 4.799e-6, 4.799e-9);

  const testing::CliResult table =
      RunCli({"modes", kMovingColumn, "--set", "axes.z.elements[2].stiffness_n_m=1.0e+9"},
             SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_EQ(table.out.rfind("axis  mode  frequency_hz", 0), 0u) << table.out;
  EXPECT_NE(table.out.find("static_deflection_per_accel_s2  y  4.79913e-06 m per m/s^2  "
                           "(driven axis)"),
            std::string::npos)
      << table.out;
  // The stiffer screw: the head's 0.6 um per m/s^2 plus the mounts' share.
  EXPECT_EQ(table.out.find("static_deflection_per_accel_s2  z  2.5e-06"), std::string::npos)
      << table.out;

  const testing::CliResult bad =
      RunCli({"modes", kMovingColumn, "--set", "axes.x.bodies[1].mass_kg=-1"},
             SHAPEBENCH_SOURCE_DIR);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "error: --set:1:1: machine.axes.x.bodies[1].mass_kg: must be finite and > 0 "
                     "(got -1)\n");
}

// Tests that the servo drive's settings are read (the kinematic drive stays the default).
TEST(MachineAxesLoader, ReadsServoDrive) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "s.yaml", "drive: {type: servo, position_gain: 25, velocity_feedforward: 0.5,\n"
                "        velocity_loop_hz: 0, motor_mass_kg: 30}\nmove: {distance_mm: 10}\n");
  const Scenario s = LoadScenario(path, {});
  EXPECT_EQ(s.drive.type, model::DriveType::kServo);
  EXPECT_EQ(s.drive.servo.position_gain_1_s, 25.0);
  EXPECT_EQ(s.drive.servo.velocity_feedforward, 0.5);
  EXPECT_EQ(s.drive.servo.velocity_loop_hz, 0.0);
  EXPECT_EQ(s.drive.servo.motor_mass_kg, 30.0);
  const Scenario defaults =
      LoadScenario(dir.Write("d.yaml", "drive: {type: servo}\nmove: {distance_mm: 10}\n"), {});
  EXPECT_EQ(defaults.drive.servo.position_gain_1_s, model::ServoConfig{}.position_gain_1_s);
  EXPECT_EQ(LoadScenario(dir.Write("k.yaml", "move: {distance_mm: 10}\n"), {}).drive.type,
            model::DriveType::kKinematic);
  ExpectError(LoadScenarioError(dir.Write("f.yaml", "drive: {type: servo, velocity_feedforward: "
                                                    "1.5}\nmove: {distance_mm: 10}\n")),
              dir.File("f.yaml"), 1, 44, "drive.velocity_feedforward", "must be in [0, 1]");
}

}  // namespace
}  // namespace shapebench::bench
