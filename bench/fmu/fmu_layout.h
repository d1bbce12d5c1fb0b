// The variables of an FMU that shapebench exports (docs/fmi.md): one table per part, made
// from the scenario alone, so that `shapebench fmu` (which writes modelDescription.xml) and
// the FMU's own library (which reads the packed scenario at instantiation) agree on every
// value reference without reading the XML.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "bench/scenario/scenario.h"

namespace shapebench::bench::fmu {

enum class Part { kMachine, kController };
const char* PartName(Part part);  // "machine", "controller"

enum class Causality { kIndependent, kParameter, kCalculatedParameter, kInput, kOutput };
enum class Variability { kFixed, kContinuous };
// kDefault: the attribute is left out (the standard's default for the combination).
enum class Initial { kDefault, kExact, kCalculated };

struct Variable {
  std::string name;
  unsigned value_reference = 0;
  Causality causality = Causality::kOutput;
  Variability variability = Variability::kContinuous;
  Initial initial = Initial::kDefault;
  std::string unit;  // a name of UnitDefinitions(); empty: dimensionless, no unit
  std::string description;
  bool has_start = false;
  double start = 0.0;
};

// One unit: its name and SI base-unit exponents (kg, m, s).
struct UnitDefinition {
  std::string name;
  int kg = 0;
  int m = 0;
  int s = 0;
};
const std::vector<UnitDefinition>& UnitDefinitions();

// A parameter of the machine part: the scenario key path it overrides (as --set takes it).
struct ParameterRef {
  unsigned value_reference = 0;
  std::string key_path;  // "machine.modes[0].frequency_hz"
};

constexpr int kNoVariable = -1;

// The variables of a part, by value reference (value_reference == index), time first.
struct Layout {
  Part part = Part::kMachine;
  std::vector<Variable> variables;
  double step_s = 0.001;  // DefaultExperiment: the interpolation period
  double stop_s = 1.0;    // DefaultExperiment: the command's ticks and one second more
  // Machine: per axis the value reference of each role (kNoVariable: none).
  std::array<int, 3> input{kNoVariable, kNoVariable, kNoVariable};
  std::array<int, 3> deflection{}, tool_error{}, deflection_peak{}, tool_error_peak{};
  std::array<int, 3> static_compliance{}, static_deflection{};
  // The kinematic drive's own motion (the held input's integrals from rest), for a master
  // that closes a servo loop across the FMU boundary (docs/fmi.md#the-servo-drive): after
  // the parameters, so the other value references are those of FMUs without them.
  std::array<int, 3> drive_position{}, drive_velocity{};
  int first_state = kNoVariable;  // the plant's states, consecutive
  int num_states = 0;
  std::vector<ParameterRef> parameters;
  // Controller: per axis.
  std::array<int, 3> position{}, velocity{}, accel{};
};

// Throws ValidationError (the scenario's machine or drive) as a run would.
Layout MakeLayout(const Scenario& scenario, Part part);

// The FMU's instantiation token (FMI 2.0 guid): a hash of the packed scenario's text, the
// part and the FMI version, in the GUID form.
std::string InstantiationToken(const std::string& scenario_text, Part part, int fmi_version);

}  // namespace shapebench::bench::fmu
