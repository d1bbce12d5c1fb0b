// The machine as the co-simulation sees it: a structural model per axis (X, Y, Z; an
// axis without one is rigid), uncoupled (the lumped forms have no rotation), each with
// its drive. The single forms (`modes:` or `bodies:`) model one axis, except a modal form
// with coupled modes (participation and shape; model/coupled_modes.h): it models all three
// axes and their cross terms, each axis with its drive.
#pragma once

#include <array>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "model/drive.h"
#include "model/linear_plant.h"
#include "model/machine.h"
#include "model/nonlinear_plant.h"

namespace shapebench::model {

constexpr int kNumAxes = 3;  // x, y, z
const char* AxisName(int axis);  // "x", "y", "z"

struct MultiAxisMachineConfig {
  // Default: the default machine (what a scenario without `machine:` runs), the modal
  // form's default (one 25 Hz mode) on Y, as a single form. Clear `axes` to build another.
  std::array<std::optional<MachineConfig>, kNumAxes> axes{std::nullopt, MachineConfig{},
                                                          std::nullopt};
  // The axis `move:` runs along and the modes report refers to; Y by default (the
  // moving column's axis in the patent).
  int driven_axis = 1;
  // The stroke per axis, [min, max] in metres (machine.stroke in mm); nullopt: unlimited.
  std::array<std::optional<std::array<double, 2>>, kNumAxes> stroke_m;
  // The axes the machine says are rigid (machine.rigid): a program may move them although
  // they have no model. An axis neither modelled nor listed here may not be moved by a
  // machine that models any axis (bench/scenario/scenario_loader.cc).
  std::array<bool, kNumAxes> rigid{};
  // Read from the single form (`modes:` or `bodies:` with an optional `axis:`): the one
  // axis' fields are then named as in that form ("modes[0].gain", not "axes.y.modes[0].gain").
  bool single_form = true;
  // Throws ValidationError naming e.g. "axes.y.modes[0].frequency_hz" (or, for a
  // single-form machine, the form's own field). Any axis may be rigid, all of them too (a
  // rigid machine: only the drive's own dynamics remain); the driven axis' static
  // deflection is then 0.
  void validate() const;
  // The key path prefix of axis `axis`'s fields: "axes.x", or "" for a single form.
  std::string AxisPrefix(int axis) const;
  // The single modal form with coupled modes (held at axes[driven_axis]); nullptr for any
  // other machine. Such a machine models every axis.
  const ModalMachineConfig* CoupledModes() const;
  // Whether axis `axis` has a structural model (its own, or the coupled modes').
  bool Models(int axis) const;
};

// The output layout of MachinePlant::plant.C: kNumOutputRows rows, per axis a deflection
// row (kDeflectionRow + axis) and a tool-error row (kToolErrorRow + axis).
constexpr int kNumOutputRows = 6;
constexpr int kDeflectionRow = 0;  // rows 0..2: structural deflection x, y, z (tool
                                   // relative to the workpiece, less the motion of the
                                   // driven point)
constexpr int kToolErrorRow = 3;   // rows 3..5: tool relative to the workpiece, less the
                                   // command position (servo lag + deflection)

struct MachinePlant {
  // Inputs: column i of B_accel / B_vel is axis i's commanded acceleration / velocity.
  LinearPlant plant;
  // The nonlinear elements of every axis (friction, backlash, the servo's force limit:
  // docs/nonlinear.md) over plant's augmented state; empty for a linear machine.
  std::vector<NonlinearElement> nonlinear;
  // NonlinearPlant::following_error_axis over plant's states (empty: no servo axis).
  std::vector<int> following_error_axis;
  // Structural deflection per held commanded acceleration, entry (b, a): deflection along
  // b per m/s^2 along a. Diagonal for uncoupled axes; a coupled machine's cross terms off it.
  Eigen::Matrix3d static_gain = Eigen::Matrix3d::Zero();
};

// Validates both (ValidationError: the machine's fields as validate() names them, the
// drive's as DriveConfig::validate() does). Every axis gets the same drive. Per axis:
// kinematic, BuildPlant of its structure (C row duplicated into rows 0 and 3), nothing for a
// rigid axis; servo, BuildServoAxisPlant (servo_drive.h). Inputs of a stateless axis reach
// no state; a rigid machine under the kinematic drive has no states at all (nothing to
// integrate: every output is 0). Tolerance groups: one per axis' structure, one per axis'
// servo. A coupled machine: each axis' drive (nothing, or its rigid servo), then the coupled
// structure driven by the three driven points' accelerations (deflection in rows 0..2 and
// 3..5); one tolerance group for the structure.
MachinePlant BuildMachinePlant(const MultiAxisMachineConfig& machine, const DriveConfig& drive);

struct AxisModes {
  int axis = 0;
  ModalAnalysis analysis;
};
// The modes of every modelled axis, in axis order (a coupled machine: all three axes, each
// mode's share from model/coupled_modes.h AnalyzeCoupledAxis).
std::vector<AxisModes> AnalyzeMachineModes(const MultiAxisMachineConfig& machine);
// The lowest frequency of AnalyzeMachineModes' modes (infinity without any), read from the
// modes themselves where every modelled axis is an uncoupled modal form (the analysis
// copies their frequencies; a sweep point asks this at every point, and the analysis
// builds vectors); the analysis (and its validation) elsewhere.
double LowestModeHz(const MultiAxisMachineConfig& machine);

// True when no modelled axis has any damping: under the kinematic drive such a structure
// keeps the vibration the motion leaves in it for ever (each mode's energy is conserved).
bool ConservesEnergy(const MultiAxisMachineConfig& machine);

// What the co-simulation and the reports ask of a machine, answered by the machine:
// its modes per axis and the frequencies that bound the run's window and sampling.
struct MachineDynamics {
  std::vector<AxisModes> axes;  // every modelled axis, in axis order
  bool conserves_energy = true;

  // The lowest natural frequency of any mode of any axis; +infinity for a rigid machine.
  double LowestHz() const;
  // The lowest frequency among `axis`' modes that carry at least `min_share` of its
  // static deflection (ModeInfo::participation); NaN when none (a rigid axis).
  double LowestParticipatingHz(int axis, double min_share = kParticipatingShare) const;
  // The highest such frequency over every axis; 0 when none.
  double FastestParticipatingHz(double min_share = kParticipatingShare) const;

  // A mode participates when it carries at least 1% of its axis' static deflection.
  static constexpr double kParticipatingShare = 0.01;
};
MachineDynamics AnalyzeMachine(const MultiAxisMachineConfig& machine);

}  // namespace shapebench::model
