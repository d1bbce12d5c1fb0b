// YAML -> Scenario with exact error reporting: every error is a
// ConfigError located at FILE:LINE:COL (or --set:N:1 for a --set value) with the key
// path, e.g. "scen.yaml:7:19: controller.pattern.k1: must be in [0.5, 1]".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bench/config/config_error.h"
#include "bench/config/node_reader.h"
#include "bench/config/override.h"
#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/scenario.h"
#include "bench/scenario/scenario_guards.h"
#include "common/validation_error.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

struct LoadOptions {
  // Plan the move (controller::GenerateCommand) so that a move too short for its pattern
  // is a load error. `pattern` turns it off: it shows the pattern whatever the move.
  bool plan_move = true;
  // What the pattern's values left to the machine (pattern_defaults.h) are taken from;
  // nullopt: the scenario's own machine and program. A sweep's points take its base
  // scenario's, so the pattern stays fixed while a swept key moves the plant.
  std::optional<DesignModes> design_modes;
};

// Reads, overrides (in order) and validates a scenario. `machine:` may be a mapping or a
// path to a machine file relative to the scenario's directory; --set machine.KEY applies
// to the loaded machine.
Scenario LoadScenario(const std::string& path, const std::vector<Override>& overrides,
                      const LoadOptions& options = {});

// The scenario's YAML tree as a run reads it: the file, its machine file spliced in, the
// overrides applied in order. Throws ConfigError for a file that cannot be read or
// parsed and for an override that does not fit the tree (index out of range, a path
// through a scalar); the keys and values themselves are not validated.
YAML::Node BuildScenarioTree(const std::string& path, const std::vector<Override>& overrides);

// `checks: {METRIC: {min: .., max: ..}, ...}` (MetricTable() names), in order: a sweep's,
// which take no `band:` (a scenario's may; its grid is the sweep's way to span a key).
std::vector<Check> ReadChecks(const NodeReader& checks);

// The `machine:` entry of a scenario (a mapping; a machine file has been spliced in
// already): either form of machine_reader.h. Validation is the caller's.
model::MultiAxisMachineConfig ReadMachineAxesEntry(const NodeReader& machine);

// The machine of a machine file (top level has `modes`, `bodies` or `axes`) or of a
// scenario, validated. Key paths are scenario paths either way ("machine.modes[0].gain",
// "machine.axes.x.bodies[1].mass_kg"); for a machine file a --set path without the
// leading "machine." is accepted too.
model::MultiAxisMachineConfig LoadMachineAxes(const std::string& path,
                                              const std::vector<Override>& overrides);

// The same, reduced to the driven axis' model (the single-axis view); a ConfigError when
// the driven axis is rigid.
model::MachineConfig LoadMachine(const std::string& path, const std::vector<Override>& overrides);

// Locates a ValidationError raised later about a loaded scenario (its field a scenario
// key path, e.g. from RunScenario) in the scenario's sources.
ConfigError LocateValidationError(const std::string& path,
                                  const std::vector<Override>& overrides,
                                  const ValidationError& error);

}  // namespace shapebench::bench
