// `machine: {fmu: FILE.fmu, inputs: {AXIS: VAR}, outputs: {ROLE: {AXIS: VAR}},
// fmu_parameters: {NAME: VALUE}}`: a plant FMU as the machine (docs/fmi.md#importing-a-plant-fmu).
// The FMU is unpacked and its modelDescription read here, at load time, so that a missing
// file, a bad FMU or a variable it does not have is located at its key (exit 2).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "bench/config/override.h"
#include "bench/fmi/fmu_machine.h"
#include "bench/scenario/scenario.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

// The keys of the FMU form, and the roles under `outputs:`.
const std::vector<std::string>& FmuMachineKeys();
const std::vector<std::string>& FmuOutputRoles();

// Whether `machine` (a mapping) is the FMU form.
bool IsFmuMachine(const NodeReader& machine);

// Reads it. *config becomes what the run core sees of such a machine: no structural model,
// every axis rigid (the FMU is the structure), driven along the first axis with an input
// (y when it has one). Without `inputs:` (`outputs:`) the variables are found by the names
// shapebench's own machine FMUs use (FmuDefaultName).
// shapebench's own machine FMU (resources/scenario.yaml) gets that scenario's machine (and
// records its drive) instead, from `load_packed` (the scenario loader's; passed in so that
// the loader and this reader do not include each other).
using PackedMachineLoader = std::function<Scenario(const std::string& path, const std::vector<Override>& overrides)>;
std::shared_ptr<const FmuMachine> ReadFmuMachine(const NodeReader& machine, model::MultiAxisMachineConfig* config,
                                                 const PackedMachineLoader& load_packed);

// `drive: {type: servo}` (`servo`, read at `drive`) beside the FMU: the FMU with the servo's
// loops run on the master (FmuMachine::master_servo). Exit 2 at `drive` for an FMU that
// carries a servo inside, a servo without a velocity loop or with friction or a force limit,
// and an FMU without the drive_position and drive_velocity outputs of each driven axis.
std::shared_ptr<const FmuMachine> WithMasterServo(const FmuMachine& fmu, const model::ServoConfig& servo,
                                                  const NodeReader& drive);

// The variable name shapebench's machine FMU gives `role` ("base_acceleration" or one of
// FmuOutputRoles()) of axis 0, 1, 2: e.g. base_accel_y, deflection_y.
std::string FmuDefaultName(const std::string& role, int axis);

}  // namespace shapebench::bench
