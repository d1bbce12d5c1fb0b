#include "bench/scenario/fmu_machine_reader.h"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "bench/config/input_path.h"
#include "common/closest_name.h"

namespace shapebench::bench {
namespace {

constexpr const char* kInputRole = "base_acceleration";
const char* const kAxisNames[] = {"x", "y", "z"};

// Each role: where it goes in FmuMachine, the causalities it may have.
struct Role {
  const char* name;
  FmuAxisSignals FmuMachine::*signals;
  std::vector<std::string> causalities;
};

const std::vector<Role>& Roles() {
  static const std::vector<Role> kRoles = {
      {kInputRole, &FmuMachine::base_acceleration, {"input"}},
      {"deflection", &FmuMachine::deflection, {"output"}},
      {"tool_error", &FmuMachine::tool_error, {"output"}},
      {"deflection_peak", &FmuMachine::deflection_peak, {"output"}},
      {"static_compliance", &FmuMachine::static_compliance, {"output", "calculatedParameter", "parameter"}},
      {"residual_amplitude", &FmuMachine::residual_amplitude, {"output"}},
      {"drive_position", &FmuMachine::drive_position, {"output"}},
      {"drive_velocity", &FmuMachine::drive_velocity, {"output"}},
  };
  return kRoles;
}

const Role& RoleNamed(const std::string& name) {
  for (const Role& role : Roles()) {
    if (name == role.name) return role;
  }
  return Roles().front();
}

// The variable `name` of the FMU as a signal of `role`, or the error at `at`.
FmuSignal Signal(const ModelDescription& md, const std::string& name, const Role& role, const NodeReader& at,
                 const std::string& fmu_file) {
  const FmuVariable* variable = md.Find(name);
  const std::string& causality = role.causalities.front();
  if (variable == nullptr) {
    std::vector<std::string> names;
    for (const FmuVariable& v : md.variables) names.push_back(v.name);
    throw at.Error("the FMU " + fmu_file + " has no variable '" + name + "'" + DidYouMean(name, names) +
                   " (its " + causality + "s: " + md.DoubleNames(causality) + ")");
  }
  if (!variable->IsDouble()) {
    throw at.Error("'" + name + "' of the FMU " + fmu_file + " is " + (variable->array ? "an array" : variable->type) +
                   ": the master maps scalar Real (2.0) or Float64 (3.0) variables only");
  }
  bool allowed = false;
  for (const std::string& c : role.causalities) allowed = allowed || variable->causality == c;
  if (!allowed) {
    throw at.Error("'" + name + "' of the FMU " + fmu_file + " has causality " + variable->causality + "; " +
                   role.name + " wants " + JoinNames(role.causalities, " or ") + " (its " + causality +
                   "s: " + md.DoubleNames(causality) + ")");
  }
  return {name, variable->value_reference};
}

// `{x: VAR, y: VAR, z: VAR}` of one role.
void ReadAxes(const NodeReader& node, const Role& role, const ModelDescription& md, const std::string& fmu_file,
              FmuMachine* machine) {
  node.ExpectMap({"x", "y", "z"});
  for (int axis = 0; axis < 3; ++axis) {
    if (auto var = node.Child(kAxisNames[axis])) {
      (machine->*role.signals)[axis] = Signal(md, var->AsString(), role, *var, fmu_file);
    }
  }
}

// Without a mapping: every role's variables by the default names, where the FMU has them.
void FindDefaults(const ModelDescription& md, bool inputs, FmuMachine* machine) {
  for (const Role& role : Roles()) {
    if ((role.name == std::string(kInputRole)) != inputs) continue;
    for (int axis = 0; axis < 3; ++axis) {
      const FmuVariable* v = md.Find(FmuDefaultName(role.name, axis));
      bool fits = v != nullptr && v->IsDouble();
      if (fits) {
        fits = false;
        for (const std::string& c : role.causalities) fits = fits || v->causality == c;
      }
      if (fits) (machine->*role.signals)[axis] = FmuSignal{v->name, v->value_reference};
    }
  }
}

void ReadParameters(const NodeReader& node, const ModelDescription& md, const std::string& fmu_file,
                    FmuMachine* machine) {
  for (const auto& [name, value] : node.Entries()) {
    const FmuVariable* variable = md.Find(name);
    if (variable == nullptr || variable->causality != "parameter") {
      std::vector<std::string> names;
      for (const FmuVariable& v : md.variables) {
        if (v.causality == "parameter") names.push_back(v.name);
      }
      throw value.Error((variable == nullptr ? "the FMU " + fmu_file + " has no variable '" + name + "'"
                                             : "'" + name + "' of the FMU " + fmu_file + " has causality " +
                                                   variable->causality + ", not parameter") +
                        DidYouMean(name, names) + " (its parameters: " + md.DoubleNames("parameter") + ")");
    }
    if (!variable->IsDouble()) {
      throw value.Error("'" + name + "' is " + variable->type + ": fmu_parameters sets Real (2.0) or Float64 (3.0) "
                        "parameters only");
    }
    if (variable->variability == "constant") throw value.Error("'" + name + "' is a constant of the FMU");
    machine->parameters.emplace_back(FmuSignal{name, variable->value_reference}, value.AsNumber());
  }
}

// The machine the run core sees: no model, every axis rigid, the driven axis an input's.
void RigidMachine(const FmuMachine& fmu, const NodeReader& machine, model::MultiAxisMachineConfig* config) {
  *config = model::MultiAxisMachineConfig{};
  config->axes = {};
  config->single_form = false;
  config->rigid = {true, true, true};
  int driven = -1;
  for (int axis : {1, 0, 2}) {
    if (driven < 0 && fmu.base_acceleration[axis]) driven = axis;
  }
  if (driven < 0) {
    throw machine.Error("the FMU " + fmu.fmu->fmu_path() + " has no base acceleration input to drive: map one with "
                        "'inputs: {y: VARIABLE}' (its inputs: " + fmu.fmu->description().DoubleNames("input") + ")");
  }
  bool deflects = false;
  for (const auto& d : fmu.deflection) deflects = deflects || d.has_value();
  if (!deflects) {
    throw machine.Error("the FMU " + fmu.fmu->fmu_path() + " gives no deflection: map one with 'outputs: "
                        "{deflection: {y: VARIABLE}}' (its outputs: " + fmu.fmu->description().DoubleNames("output") +
                        ")");
  }
  config->driven_axis = driven;
}

// shapebench's own machine FMU: the scenario it was made from (resources/scenario.yaml),
// with the fmu_parameters that are its key paths applied as --set would, gives the machine;
// the plant's states are the outputs state[0], state[1], ... Else false (a foreign FMU).
bool ReadPackedModel(const NodeReader& at, const PackedMachineLoader& load_packed, FmuMachine* fmu,
                     model::MultiAxisMachineConfig* config) {
  const std::string packed = fmu->fmu->resources_dir() + "/scenario.yaml";
  const ModelDescription& md = fmu->fmu->description();
  if (!std::filesystem::exists(packed) || md.Find("deflection_peak_" + std::string(kAxisNames[config->driven_axis])) ==
                                               nullptr) {
    return false;
  }
  std::vector<Override> overrides;
  for (const auto& [signal, value] : fmu->parameters) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    if (signal.name.rfind("machine.", 0) == 0) overrides.push_back({signal.name, text});
  }
  try {
    const Scenario scenario = load_packed(packed, overrides);
    *config = scenario.machine;
    fmu->drive = scenario.drive;
  } catch (const std::exception& error) {
    throw at.Error("the scenario packed in the FMU " + fmu->fmu->fmu_path() + " does not load: " + error.what());
  }
  for (int i = 0;; ++i) {
    const FmuVariable* state = md.Find("state[" + std::to_string(i) + "]");
    if (state == nullptr || !state->IsDouble() || state->causality != "output") break;
    fmu->states.push_back(state->value_reference);
  }
  fmu->model_known = true;
  return true;
}

// The child `key` of `drive` when written there, else `drive` itself: where a refusal points.
NodeReader DriveKey(const NodeReader& drive, const char* key) {
  if (auto child = drive.Child(key)) return *child;
  return drive;
}

}  // namespace

std::shared_ptr<const FmuMachine> WithMasterServo(const FmuMachine& fmu, const model::ServoConfig& servo,
                                                  const NodeReader& drive) {
  const std::string file = fmu.fmu->fmu_path();
  if (fmu.drive && fmu.drive->type == model::DriveType::kServo) {
    throw drive.Error("the FMU " + file + " carries its servo inside already (it was exported from a servo "
                      "scenario): leave drive: out, or export the machine under drive: {type: kinematic} to run "
                      "the servo on the master");
  }
  if (servo.velocity_loop_hz == 0.0) {
    throw DriveKey(drive, "velocity_loop_hz").Error(
        "a servo closed across the FMU boundary needs a velocity loop (velocity_loop_hz > 0): the FMU takes the "
        "drive's acceleration, and under ideal inner loops (0) the motor is a velocity source");
  }
  if (servo.nonlinear()) {
    throw DriveKey(drive, servo.friction.present() ? "friction" : "force_limit_n").Error(
        "the drive's friction and force limit act inside a step on the motor's force balance, which a servo "
        "closed across the FMU boundary does not see: put the servo inside the FMU (export the machine from "
        "the servo scenario)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!fmu.base_acceleration[axis]) continue;
    for (const char* role : {"drive_position", "drive_velocity"}) {
      if ((fmu.*RoleNamed(role).signals)[axis]) continue;
      throw drive.Error("a servo closed across the FMU boundary feeds back the drive's position and velocity, "
                        "and the FMU " + file + " maps no " + role + " output for axis " + kAxisNames[axis] +
                        ": map one with 'outputs: {" + role + ": {" + kAxisNames[axis] + ": VARIABLE}}' (its "
                        "outputs: " + fmu.fmu->description().DoubleNames("output") + ")");
    }
  }
  auto copy = std::make_shared<FmuMachine>(fmu);
  copy->master_servo = servo;
  return copy;
}

const std::vector<std::string>& FmuMachineKeys() {
  static const std::vector<std::string> kKeys = {"fmu", "inputs", "outputs", "fmu_parameters"};
  return kKeys;
}

const std::vector<std::string>& FmuOutputRoles() {
  static const std::vector<std::string> kRoles = {"deflection",         "tool_error",     "deflection_peak",
                                                  "static_compliance",  "residual_amplitude",
                                                  "drive_position",     "drive_velocity"};
  return kRoles;
}

bool IsFmuMachine(const NodeReader& machine) { return machine.IsMap() && machine.Has("fmu"); }

std::string FmuDefaultName(const std::string& role, int axis) {
  // As shapebench's machine FMUs name them (bench/fmu/fmu_layout.cc).
  return (role == kInputRole ? std::string("base_accel") : role) + "_" + kAxisNames[axis];
}

std::shared_ptr<const FmuMachine> ReadFmuMachine(const NodeReader& machine, model::MultiAxisMachineConfig* config,
                                                 const PackedMachineLoader& load_packed) {
  machine.ExpectMap(FmuMachineKeys());
  const NodeReader file_node = *machine.Child("fmu");
  const std::string file = ResolvedInputPath(file_node);
  auto fmu = std::make_shared<FmuMachine>();
  try {
    fmu->fmu = std::make_shared<const UnpackedFmu>(file);
  } catch (const FmuError& error) {
    throw file_node.Error(error.what());
  }
  const ModelDescription& md = fmu->fmu->description();
  if (auto inputs = machine.Child("inputs")) {
    ReadAxes(*inputs, RoleNamed(kInputRole), md, file, fmu.get());
  } else {
    FindDefaults(md, true, fmu.get());
  }
  if (auto outputs = machine.Child("outputs")) {
    outputs->ExpectMap(FmuOutputRoles());
    for (const auto& [role, axes] : outputs->Entries()) ReadAxes(axes, RoleNamed(role), md, file, fmu.get());
  } else {
    FindDefaults(md, false, fmu.get());
  }
  if (auto parameters = machine.Child("fmu_parameters")) ReadParameters(*parameters, md, file, fmu.get());
  RigidMachine(*fmu, machine, config);
  if (!machine.Has("inputs") && !machine.Has("outputs")) ReadPackedModel(file_node, load_packed, fmu.get(), config);
  return fmu;
}

}  // namespace shapebench::bench
