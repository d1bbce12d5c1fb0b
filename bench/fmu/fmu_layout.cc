#include "bench/fmu/fmu_layout.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <variant>

#include "bench/run/run_scenario.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench::fmu {
namespace {

std::string Axis(int axis) { return model::AxisName(axis); }

int Add(Layout* layout, Variable v) {
  v.value_reference = static_cast<unsigned>(layout->variables.size());
  layout->variables.push_back(std::move(v));
  return static_cast<int>(layout->variables.back().value_reference);
}

Variable Output(std::string name, std::string unit, std::string description) {
  Variable v;
  v.name = std::move(name);
  v.unit = std::move(unit);
  v.description = std::move(description);
  return v;
}

void AddParameter(Layout* layout, const std::string& key, double value, const char* unit,
                  const std::string& description) {
  Variable v;
  v.name = key;
  v.causality = Causality::kParameter;
  v.variability = Variability::kFixed;
  v.initial = Initial::kExact;
  v.unit = unit;
  v.description = description;
  v.has_start = true;
  v.start = value;
  layout->parameters.push_back({static_cast<unsigned>(Add(layout, v)), key});
}

// Each mode's frequency and damping, each element's stiffness and damping, as the scenario
// keys --set takes ("machine.axes.x.modes[0].frequency_hz" or "machine.modes[0]...").
void AddMachineParameters(Layout* layout, const model::MultiAxisMachineConfig& machine) {
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    if (!machine.axes[axis]) continue;
    const std::string prefix = machine.AxisPrefix(axis);
    const std::string base = "machine." + (prefix.empty() ? std::string() : prefix + ".");
    if (const auto* modal = std::get_if<model::ModalMachineConfig>(&machine.axes[axis]->form)) {
      if (!modal->modal_file.empty()) continue;  // modes from a file: no key per mode
      for (std::size_t i = 0; i < modal->modes.size(); ++i) {
        const std::string key = base + "modes[" + std::to_string(i) + "].";
        AddParameter(layout, key + "frequency_hz", modal->modes[i].frequency_hz, "Hz",
                     "natural frequency of mode " + std::to_string(i));
        AddParameter(layout, key + "damping_ratio", modal->modes[i].damping_ratio, "",
                     "damping ratio of mode " + std::to_string(i));
      }
    } else if (const auto* lumped = std::get_if<model::LumpedMachineConfig>(&machine.axes[axis]->form)) {
      for (std::size_t i = 0; i < lumped->elements.size(); ++i) {
        const std::string key = base + "elements[" + std::to_string(i) + "].";
        const std::string& name = lumped->elements[i].name;
        AddParameter(layout, key + "stiffness_n_m", lumped->elements[i].stiffness_n_m, "N/m",
                     "stiffness of element " + name);
        AddParameter(layout, key + "damping_n_s_m", lumped->elements[i].damping_n_s_m, "N.s/m",
                     "damping of element " + name);
      }
    }
  }
}

void AddMachineAxis(Layout* layout, int axis, bool has_input) {
  const std::string a = Axis(axis);
  if (has_input) {
    Variable in = Output("base_accel_" + a, "m/s2",
                         "commanded acceleration of the " + a + " drive, held over the step");
    in.causality = Causality::kInput;
    in.has_start = true;
    layout->input[axis] = Add(layout, in);
  }
  layout->deflection[axis] = Add(layout, Output("deflection_" + a, "m",
      "structural deflection along " + a + " at the step's end"));
  layout->tool_error[axis] = Add(layout, Output("tool_error_" + a, "m",
      "tool position less the commanded position along " + a + " at the step's end"));
  layout->deflection_peak[axis] = Add(layout, Output("deflection_peak_" + a, "m",
      "largest |deflection_" + a + "| over the last step, its inside included"));
  layout->tool_error_peak[axis] = Add(layout, Output("tool_error_peak_" + a, "m",
      "largest |tool_error_" + a + "| over the last step, its inside included"));
  layout->static_deflection[axis] = Add(layout, Output("static_deflection_" + a, "m",
      "deflection along " + a + " the held inputs would give at rest"));
  Variable compliance = Output("static_compliance_" + a, "s2",
                               "static deflection along " + a + " per m/s2 along " + a);
  compliance.causality = Causality::kCalculatedParameter;
  compliance.variability = Variability::kFixed;
  compliance.initial = Initial::kCalculated;
  layout->static_compliance[axis] = Add(layout, compliance);
}

void MakeMachine(const Scenario& scenario, Layout* layout) {
  const model::MachinePlant machine = model::BuildMachinePlant(scenario.machine, scenario.drive);
  const model::LinearPlant& plant = machine.plant;
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    layout->input[axis] = layout->deflection[axis] = layout->tool_error[axis] = kNoVariable;
    layout->deflection_peak[axis] = layout->tool_error_peak[axis] = kNoVariable;
    layout->static_compliance[axis] = layout->static_deflection[axis] = kNoVariable;
    const bool input = plant.num_states() > 0 && axis < plant.num_inputs() &&
                       (plant.B_accel.col(axis).cwiseAbs().maxCoeff() > 0.0 ||
                        plant.B_vel.col(axis).cwiseAbs().maxCoeff() > 0.0);
    if (input || scenario.machine.Models(axis)) AddMachineAxis(layout, axis, input);
  }
  layout->num_states = plant.num_states();
  for (int i = 0; i < plant.num_states(); ++i) {
    const bool position = plant.state_kinds[i] == model::StateKind::kPosition;
    const int vr = Add(layout, Output("state[" + std::to_string(i) + "]", position ? "m" : "m/s",
        std::string("plant state ") + std::to_string(i) + (position ? " (a displacement)" : " (a velocity)")));
    if (i == 0) layout->first_state = vr;
  }
  AddMachineParameters(layout, scenario.machine);
  // A servo inside the FMU moves its driven point off the command's integral: no such outputs.
  if (scenario.drive.type != model::DriveType::kKinematic) return;
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    if (layout->input[axis] == kNoVariable) continue;
    const std::string a = Axis(axis);
    layout->drive_position[axis] = Add(layout, Output("drive_position_" + a, "m",
        "position of the " + a + " drive (the driven point) from rest at 0: the held base_accel_" + a + " integrated twice"));
    layout->drive_velocity[axis] = Add(layout, Output("drive_velocity_" + a, "m/s",
        "velocity of the " + a + " drive: the held base_accel_" + a + " integrated"));
  }
}

void MakeController(Layout* layout) {
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    const std::string a = Axis(axis);
    layout->position[axis] = Add(layout, Output("position_" + a, "m", "commanded position of axis " + a));
    layout->velocity[axis] = Add(layout, Output("velocity_" + a, "m/s", "commanded velocity of axis " + a));
    layout->accel[axis] = Add(layout, Output("accel_" + a, "m/s2",
        "commanded acceleration of axis " + a + ", held over the period that ended"));
  }
}

}  // namespace

const char* PartName(Part part) { return part == Part::kMachine ? "machine" : "controller"; }

const std::vector<UnitDefinition>& UnitDefinitions() {
  static const std::vector<UnitDefinition> units = {
      {"s", 0, 0, 1},   {"m", 0, 1, 0},    {"m/s", 0, 1, -1},   {"m/s2", 0, 1, -2},
      {"s2", 0, 0, 2},  {"Hz", 0, 0, -1},  {"N/m", 1, 0, -2},   {"N.s/m", 1, 0, -1}};
  return units;
}

Layout MakeLayout(const Scenario& scenario, Part part) {
  Layout layout;
  layout.part = part;
  Variable time;
  time.name = "time";
  time.causality = Causality::kIndependent;
  time.unit = "s";
  time.description = "simulation time";
  Add(&layout, time);
  layout.position.fill(kNoVariable);
  layout.velocity.fill(kNoVariable);
  layout.accel.fill(kNoVariable);
  layout.drive_position.fill(kNoVariable);
  layout.drive_velocity.fill(kNoVariable);
  if (part == Part::kMachine) {
    MakeMachine(scenario, &layout);
  } else {
    MakeController(&layout);
  }
  const controller::MultiAxisCommand command = GenerateScenarioCommand(scenario, scenario.RunProgram());
  layout.step_s = command.period_s;
  const long rest_ticks = std::lround(1.0 / command.period_s);
  layout.stop_s = command.period_s * static_cast<double>(static_cast<long>(command.num_ticks()) + rest_ticks);
  return layout;
}

std::string InstantiationToken(const std::string& scenario_text, Part part, int fmi_version) {
  std::uint64_t hash = 1469598103934665603ULL;  // FNV-1a, 64 bits, run twice for 128
  std::uint64_t second = 1099511628211ULL;
  const std::string text = scenario_text + "\n" + PartName(part) + "\n" + std::to_string(fmi_version);
  for (const unsigned char c : text) {
    hash = (hash ^ c) * 1099511628211ULL;
    second = (second ^ c) * 1469598103934665603ULL + 0x9e3779b97f4a7c15ULL;
  }
  char token[64];
  std::snprintf(token, sizeof token, "{%08x-%04x-%04x-%04x-%012llx}",
                static_cast<unsigned>(hash >> 32), static_cast<unsigned>((hash >> 16) & 0xffff),
                static_cast<unsigned>(hash & 0xffff), static_cast<unsigned>(second >> 48),
                static_cast<unsigned long long>(second & 0xffffffffffffULL));
  return token;
}

}  // namespace shapebench::bench::fmu
