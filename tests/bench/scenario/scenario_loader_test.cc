// Reading valid scenarios: values, defaults, forms of the machine, --set overrides.
#include "bench/scenario/scenario_loader.h"

#include <variant>

#include <gtest/gtest.h>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;

// Tests that every key of a full scenario lands in its struct field.
TEST(ScenarioLoader, ReadsAllKeys) {
  ScratchDir dir;
  const std::string path = dir.Write("full.yaml", R"(
name: full scenario
machine:
  modes:
    - {frequency_hz: 30.0, damping_ratio: 0.01, gain: 0.5}
    - {frequency_hz: 90.0, damping_ratio: 0.02, gain: 0.1}
drive: {type: kinematic}
controller:
  period_s: 0.002
  feed_mm_min: 3000
  accel_time_s: 0.08
  pattern: {method: 4, mode: end, frequency_hz: 30.0, k1: 0.6, t1_s: 0.003, step_resolution_s: 0.0001}
  post_interp: {type: exponential, time_constant_s: 0.02}
move: {distance_mm: -40}
integrator: {method: cvode, rtol: 1.0e-9, atol_scale: 0.5, lmm: adams, max_num_steps: 5000, output_substeps: 8}
checks:
  peak_ratio: {max: 1.5}
  residual_ratio: {min: 0, max: 0.2}
)");
  const Scenario s = LoadScenario(path, {});
  EXPECT_EQ(s.name, "full scenario");
  EXPECT_EQ(s.source_file, path);
  const auto& modal = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 2u);
  EXPECT_DOUBLE_EQ(modal.modes[1].frequency_hz, 90.0);
  EXPECT_DOUBLE_EQ(modal.modes[1].damping_ratio, 0.02);
  EXPECT_DOUBLE_EQ(modal.modes[0].gain, 0.5);
  EXPECT_DOUBLE_EQ(s.controller.period_s, 0.002);
  EXPECT_DOUBLE_EQ(s.controller.feed_mm_min, 3000.0);
  EXPECT_DOUBLE_EQ(s.controller.accel_time_s, 0.08);
  EXPECT_EQ(s.controller.pattern.method, "4");
  EXPECT_EQ(s.controller.pattern.mode, controller::PatternMode::kEnd);
  EXPECT_DOUBLE_EQ(s.controller.pattern.frequency_hz, 30.0);
  EXPECT_DOUBLE_EQ(s.controller.pattern.k1, 0.6);
  EXPECT_DOUBLE_EQ(s.controller.pattern.t1_s, 0.003);
  EXPECT_DOUBLE_EQ(s.controller.pattern.step_resolution_s, 0.0001);
  EXPECT_EQ(s.controller.post_interp.type, controller::PostInterpType::kExponential);
  EXPECT_DOUBLE_EQ(s.controller.post_interp.time_constant_s, 0.02);
  EXPECT_DOUBLE_EQ(s.move.distance_mm, -40.0);
  EXPECT_EQ(s.integrator.method, model::IntegratorMethod::kCvode);
  EXPECT_DOUBLE_EQ(s.integrator.rtol, 1e-9);
  EXPECT_DOUBLE_EQ(s.integrator.atol_scale, 0.5);
  EXPECT_EQ(s.integrator.lmm, model::CvodeLmm::kAdams);
  EXPECT_EQ(s.integrator.max_num_steps, 5000);
  EXPECT_EQ(s.integrator.output_substeps, 8);
  ASSERT_EQ(s.checks.size(), 2u);
  EXPECT_EQ(s.checks[0].metric, "peak_ratio");
  EXPECT_FALSE(s.checks[0].min.has_value());
  EXPECT_DOUBLE_EQ(*s.checks[0].max, 1.5);
  EXPECT_EQ(s.checks[1].metric, "residual_ratio");
  EXPECT_DOUBLE_EQ(*s.checks[1].min, 0.0);
}

// Tests that absent keys keep the structs' defaults and the name defaults to the file stem.
TEST(ScenarioLoader, DefaultsComeFromTheStructs) {
  ScratchDir dir;
  const Scenario s = LoadScenario(dir.Write("minimal_move.yaml", "move: {distance_mm: 20}\n"), {});
  EXPECT_EQ(s.name, "minimal_move");
  const controller::ControllerConfig defaults;
  EXPECT_DOUBLE_EQ(s.controller.period_s, defaults.period_s);
  EXPECT_DOUBLE_EQ(s.controller.feed_mm_min, defaults.feed_mm_min);
  EXPECT_EQ(s.controller.pattern.method, defaults.pattern.method);
  EXPECT_EQ(s.integrator.method, model::IntegratorConfig{}.method);
  const auto& modal = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 1u);
  EXPECT_DOUBLE_EQ(modal.modes[0].frequency_hz, 25.0);
  EXPECT_TRUE(s.checks.empty());
}

// Tests that pattern.method reads the same whether written as an int or a string.
TEST(ScenarioLoader, MethodAsIntOrString) {
  ScratchDir dir;
  const Scenario as_int = LoadScenario(
      dir.Write("a.yaml", "controller: {pattern: {method: 3}}\n"), {});
  const Scenario as_string = LoadScenario(
      dir.Write("b.yaml", "controller: {pattern: {method: \"3\"}}\n"), {});
  const Scenario as_none = LoadScenario(
      dir.Write("c.yaml", "controller: {pattern: {method: none}}\n"), {});
  EXPECT_EQ(as_int.controller.pattern.method, "3");
  EXPECT_EQ(as_string.controller.pattern.method, "3");
  EXPECT_EQ(as_none.controller.pattern.method, "none");
}

// Tests that the lumped machine form is read with its nested output mapping.
TEST(ScenarioLoader, ReadsLumpedMachine) {
  ScratchDir dir;
  const Scenario s = LoadScenario(dir.Write("lumped.yaml", R"(
machine:
  bodies:
    - {name: bed, mass_kg: 5000}
    - {name: column, mass_kg: 1000}
  elements:
    - {name: anchor, from: ground, to: bed, stiffness_n_m: 1.0e9, damping_n_s_m: 1000}
    - {name: screw, from: driven, to: column, stiffness_n_m: 2.5e7}
  driven_relative_to: bed
  output: {body: column, relative_to: bed}
)"),
                                  {});
  const auto& lumped = std::get<model::LumpedMachineConfig>(s.machine.axes[1]->form);
  ASSERT_EQ(lumped.bodies.size(), 2u);
  EXPECT_EQ(lumped.bodies[1].name, "column");
  EXPECT_DOUBLE_EQ(lumped.bodies[0].mass_kg, 5000.0);
  ASSERT_EQ(lumped.elements.size(), 2u);
  EXPECT_EQ(lumped.elements[1].from, "driven");
  EXPECT_EQ(lumped.elements[1].to, "column");
  EXPECT_DOUBLE_EQ(lumped.elements[0].damping_n_s_m, 1000.0);
  EXPECT_DOUBLE_EQ(lumped.elements[1].damping_n_s_m, 0.0);
  EXPECT_EQ(lumped.driven_relative_to, "bed");
  EXPECT_EQ(lumped.output_body, "column");
  EXPECT_EQ(lumped.output_relative_to, "bed");
}

// Tests that a machine file referenced by path (relative to the scenario) is loaded.
TEST(ScenarioLoader, LoadsReferencedMachineFile) {
  const Scenario s = LoadScenario(DataPath("uses_machine_file.yaml"), {});
  const auto& modal = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 2u);
  EXPECT_DOUBLE_EQ(modal.modes[1].frequency_hz, 80.0);
  EXPECT_EQ(s.controller.pattern.method, "2");
  EXPECT_EQ(s.controller.pattern.mode, controller::PatternMode::kStart);
}

// Tests that --set overrides scalars, creates missing keys, and reaches into a
// referenced machine file; later options win.
TEST(ScenarioLoader, OverridesApplyInOrder) {
  const Scenario s = LoadScenario(DataPath("uses_machine_file.yaml"),
                                  ParseOverrides({"machine.modes[1].gain=0.3",
                                                  "controller.feed_mm_min=3000",
                                                  "controller.post_interp.type=exponential",
                                                  "controller.feed_mm_min=4000",
                                                  "name=renamed"}));
  const auto& modal = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form);
  EXPECT_DOUBLE_EQ(modal.modes[1].gain, 0.3);
  EXPECT_DOUBLE_EQ(modal.modes[0].gain, 1.0);
  EXPECT_DOUBLE_EQ(s.controller.feed_mm_min, 4000.0);
  EXPECT_EQ(s.controller.post_interp.type, controller::PostInterpType::kExponential);
  EXPECT_EQ(s.name, "renamed");
}

// Tests that --set can replace whole subtrees with YAML values, including the machine.
TEST(ScenarioLoader, OverrideWithStructuredValue) {
  const Scenario s = LoadScenario(
      DataPath("uses_machine_file.yaml"),
      ParseOverrides({"machine={modes: [{frequency_hz: 40}]}", "machine.modes[0].gain=2"}));
  const auto& modal = std::get<model::ModalMachineConfig>(s.machine.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 1u);
  EXPECT_DOUBLE_EQ(modal.modes[0].frequency_hz, 40.0);
  EXPECT_DOUBLE_EQ(modal.modes[0].gain, 2.0);
}

// Tests that LoadMachine reads a machine file, a scenario, and accepts --set paths
// with or without the "machine." prefix on a machine file.
TEST(ScenarioLoader, LoadMachineFromEitherFile) {
  const model::MachineConfig from_file = LoadMachine(DataPath("machines/two_modes.yaml"), {});
  EXPECT_EQ(std::get<model::ModalMachineConfig>(from_file.form).modes.size(), 2u);
  const model::MachineConfig from_scenario = LoadMachine(DataPath("uses_machine_file.yaml"), {});
  EXPECT_EQ(std::get<model::ModalMachineConfig>(from_scenario.form).modes.size(), 2u);
  const model::MachineConfig bare = LoadMachine(DataPath("machines/two_modes.yaml"),
                                                ParseOverrides({"modes[0].frequency_hz=30"}));
  EXPECT_DOUBLE_EQ(std::get<model::ModalMachineConfig>(bare.form).modes[0].frequency_hz, 30.0);
  const model::MachineConfig prefixed = LoadMachine(
      DataPath("machines/two_modes.yaml"), ParseOverrides({"machine.modes[0].frequency_hz=31"}));
  EXPECT_DOUBLE_EQ(std::get<model::ModalMachineConfig>(prefixed.form).modes[0].frequency_hz,
                   31.0);
  const model::MachineConfig lumped = LoadMachine(DataPath("machines/lumped_column.yaml"), {});
  EXPECT_TRUE(std::holds_alternative<model::LumpedMachineConfig>(lumped.form));
}

// Tests that the pattern command's load skips move planning, so a move too short for
// its pattern still loads.
TEST(ScenarioLoader, PlanMoveCanBeSkipped) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "short.yaml", "controller: {pattern: {method: 2}}\nmove: {distance_mm: 0.01}\n");
  LoadOptions options;
  options.plan_move = false;
  EXPECT_NO_THROW(LoadScenario(path, {}, options));
  EXPECT_THROW(LoadScenario(path, {}), ConfigError);
}

}  // namespace
}  // namespace shapebench::bench
