// A plant FMU as the machine of a scenario (`machine: {fmu: FILE.fmu, inputs, outputs,
// fmu_parameters}`, docs/fmi.md#importing-a-plant-fmu): the unpacked FMU and which of its
// variables take and give what, per axis (0 x, 1 y, 2 z). Read by
// bench/scenario/fmu_machine_reader.cc, stepped by FmuPlant (fmu_plant.h).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/fmi/fmu_archive.h"
#include "model/drive.h"

namespace shapebench::bench {

// One double variable of the FMU.
struct FmuSignal {
  std::string name;
  unsigned value_reference = 0;
};

using FmuAxisSignals = std::array<std::optional<FmuSignal>, 3>;

struct FmuMachine {
  std::shared_ptr<const UnpackedFmu> fmu;
  // Inputs: the base acceleration of the axis' driven point in m/s^2, held over each
  // communication step (the kinematic drive's command acceleration).
  FmuAxisSignals base_acceleration;
  // Outputs after each step: the structural deflection (m, the modal form's sign: tool
  // relative to the driven point) and the tool error (m; absent: the deflection, as under
  // the kinematic drive).
  FmuAxisSignals deflection;
  FmuAxisSignals tool_error;
  // Documented outputs the metrics use when present (absent: those metrics are n/a, or
  // taken from the communication points only):
  FmuAxisSignals deflection_peak;           // max |deflection| over the last step (m): in-step peaks
  FmuAxisSignals static_compliance;   // deflection per held m/s^2 (s^2): static_displacement_m
  FmuAxisSignals residual_amplitude;  // the free vibration's amplitude about rest (m)
  // The driven point's position (m, from rest at 0) and velocity (m/s): what a servo on the
  // master's side feeds back (master_servo).
  FmuAxisSignals drive_position;
  FmuAxisSignals drive_velocity;
  std::vector<std::pair<FmuSignal, double>> parameters;  // fmu_parameters, in the file's order
  // shapebench's own machine FMU (bench/fmu: resources/scenario.yaml, outputs state[i]): the
  // scenario got the FMU's own machine model, so the run's window, substeps and static
  // reference are the native run's, and the residual vibration is read from these states
  // as the native run reads its plant's (PlantState()).
  bool model_known = false;
  std::vector<unsigned> states;
  // Its drive (a servo's loops run inside the FMU, on the commanded acceleration): the run
  // takes it in place of the scenario's kinematic one.
  std::optional<model::DriveConfig> drive;
  // `drive: {type: servo}` beside an FMU whose input is the drive's acceleration: the servo's
  // loops run on the master, closed across the FMU boundary once per communication step on
  // the drive_position / drive_velocity outputs of the last communication point (FmuPlant;
  // docs/fmi.md#the-servo-drive).
  std::optional<model::ServoConfig> master_servo;
};

}  // namespace shapebench::bench
