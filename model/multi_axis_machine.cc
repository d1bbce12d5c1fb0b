// The multi-axis machine: per-axis plants assembled block-diagonally (axes uncoupled).
#include "model/multi_axis_machine.h"

#include <cmath>

#include "common/format.h"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "common/validation_error.h"
#include "model/coupled_modes.h"
#include "model/servo_drive.h"

namespace shapebench::model {
namespace {

// One axis: 1 input column, output rows [deflection; tool relative to the command].
NonlinearPlant BuildAxisPlant(const std::optional<MachineConfig>& structure,
                              const DriveConfig& drive) {
  if (drive.type == DriveType::kServo) {
    return BuildServoAxis(structure ? &*structure : nullptr, drive.servo);
  }
  NonlinearPlant axis;
  LinearPlant& plant = axis.linear;
  if (!structure) {  // rigid under the kinematic drive: it follows the command exactly
    plant.A = Eigen::MatrixXd::Zero(0, 0);
    plant.B_accel = Eigen::MatrixXd::Zero(0, 1);
    plant.B_vel = Eigen::MatrixXd::Zero(0, 1);
    plant.C = Eigen::MatrixXd::Zero(2, 0);
    return axis;
  }
  plant = BuildPlant(*structure);
  const Eigen::MatrixXd c = plant.C;
  plant.C.resize(2, c.cols());
  plant.C << c, c;  // the driven point is the command: no following error
  axis.elements = BuildStructureElements(*structure);
  return axis;
}

// Axis `axis`'s elements (over its block's states n0.., its input 0) into the machine's.
void AppendElements(const std::vector<NonlinearElement>& elements, int axis, int n0, int n,
                    const std::string& prefix, std::vector<NonlinearElement>* out) {
  for (const NonlinearElement& e : elements) {
    NonlinearElement moved = e;
    const auto nb = static_cast<int>(e.row_x.size());
    moved.row_x = Eigen::VectorXd::Zero(n);
    moved.row_x.segment(n0, nb) = e.row_x;
    moved.column_x = Eigen::VectorXd::Zero(n);
    moved.column_x.segment(n0, nb) = e.column_x;
    moved.row_v = Eigen::VectorXd::Zero(kNumAxes);
    moved.row_v(axis) = e.row_v(0);
    // The structure's own fields get the machine's prefix; the drive's name the axis.
    moved.name = e.name.rfind("drive.", 0) == 0
                     ? e.name + " (axis " + AxisName(axis) + ")"
                     : (prefix.empty() ? "machine." : "machine." + prefix + ".") + e.name;
    out->push_back(std::move(moved));
  }
}

// Axis `axis`' following-error states (NonlinearPlant::following_error_axis) appended to
// `out`, which covers the machine's states before the block; `out` stays empty while no
// axis has any.
void AppendFollowingErrors(const NonlinearPlant& block, int axis, int n, std::vector<int>* out) {
  if (block.following_error_axis.empty() && out->empty()) return;
  const int n0 = n - block.linear.num_states();
  out->resize(n0, -1);
  for (int lag : block.following_error_axis) out->push_back(lag < 0 ? -1 : axis);
  out->resize(n, -1);
}

// Grows `plant` to n states (the new rows and columns zero), keeping its inputs (one per
// axis) and output rows (kNumOutputRows).
void GrowPlant(int n, LinearPlant* plant) {
  auto grow = [](Eigen::MatrixXd* m, int rows, int cols) {
    Eigen::MatrixXd bigger = Eigen::MatrixXd::Zero(rows, cols);
    bigger.topLeftCorner(m->rows(), m->cols()) = *m;
    *m = std::move(bigger);
  };
  grow(&plant->A, n, n);
  grow(&plant->B_accel, n, kNumAxes);
  grow(&plant->B_vel, n, kNumAxes);
  grow(&plant->C, kNumOutputRows, n);
}

// Appends `block` (one input, two output rows) as axis `axis` of `plant`.
void AppendAxis(const LinearPlant& block, int axis, LinearPlant* plant) {
  const int n0 = plant->num_states();
  const int nb = block.num_states();
  const int n = n0 + nb;
  GrowPlant(n, plant);
  if (nb > 0) {  // a rigid axis: no blocks (row() of an empty matrix offsets a null pointer)
    plant->A.block(n0, n0, nb, nb) = block.A;
    plant->B_accel.block(n0, axis, nb, 1) = block.B_accel;
    plant->B_vel.block(n0, axis, nb, 1) = block.B_vel;
    plant->C.block(kDeflectionRow + axis, n0, 1, nb) = block.C.row(0);
    plant->C.block(kToolErrorRow + axis, n0, 1, nb) = block.C.row(1);
  }
  plant->state_kinds.insert(plant->state_kinds.end(), block.state_kinds.begin(),
                            block.state_kinds.end());
  plant->max_frequency_rad_s = std::max(plant->max_frequency_rad_s, block.max_frequency_rad_s);
  if (nb == 0) return;
  const int first_group = static_cast<int>(plant->group_frequency_rad_s.size());
  for (int i = 0; i < nb; ++i) {
    plant->tolerance_group.push_back(first_group + block.ToleranceGroup(i));
  }
  for (int g = 0; g < block.NumToleranceGroups(); ++g) {
    plant->group_frequency_rad_s.push_back(block.GroupFrequency(g));
  }
}

// How a driven point's acceleration s'' follows from the plant: s'' = states . x +
// accel a + vel v (the axis' commanded acceleration a and velocity v).
struct DrivenAcceleration {
  Eigen::RowVectorXd states;
  double accel = 1.0;  // the kinematic drive: s'' = a
  double vel = 0.0;
};

// The driven point of a rigid servo axis (`servo`, BuildServoAxisPlant without structure)
// whose states start at `first` of `num_states`: its tool row is the following error
// e = c x (servo_drive.h, row 1), s = u + e, so s'' = a + e'' with
//   e' = c (A x + B_a a + B_v v)                  (c B_a = 0: e' has no a term)
//   e'' = c A A x + (c A B_a + c B_v) a + c A B_v v.
DrivenAcceleration ServoDrivenAcceleration(const LinearPlant& servo, int first, int num_states) {
  const Eigen::RowVectorXd c = servo.C.row(1);
  const Eigen::RowVectorXd ca = c * servo.A;
  DrivenAcceleration driven;
  driven.states = Eigen::RowVectorXd::Zero(num_states);
  driven.states.segment(first, servo.num_states()) = ca * servo.A;
  driven.accel = 1.0 + (ca * servo.B_accel.col(0))(0) + (c * servo.B_vel.col(0))(0);
  driven.vel = (ca * servo.B_vel.col(0))(0);
  return driven;
}

// Appends the coupled structure (BuildCoupledModalPlant), its input a driven by the driven
// point's acceleration of axis a (`driven`, over the states before it), its deflection
// into the deflection and tool-error rows of every axis.
void AppendCoupledStructure(const LinearPlant& structure, const std::array<DrivenAcceleration, kNumAxes>& driven,
                            LinearPlant* plant) {
  const int n0 = plant->num_states();
  const int ns = structure.num_states();
  const int n = n0 + ns;
  GrowPlant(n, plant);
  plant->A.block(n0, n0, ns, ns) = structure.A;
  for (int axis = 0; axis < kNumAxes; ++axis) {
    const Eigen::VectorXd b = structure.B_accel.col(axis);
    const DrivenAcceleration& s = driven[axis];
    // The kinematic drive (s'' = a) adds nothing else: B_accel is then the structure's own.
    plant->B_accel.block(n0, axis, ns, 1) = s.accel == 1.0 ? b : Eigen::VectorXd(b * s.accel);
    if (s.vel != 0.0) plant->B_vel.block(n0, axis, ns, 1) = b * s.vel;
    if (n0 > 0 && !s.states.isZero(0.0)) plant->A.block(n0, 0, ns, n0) += b * s.states;
  }
  plant->C.block(kDeflectionRow, n0, kNumAxes, ns) = structure.C;
  plant->C.block(kToolErrorRow, n0, kNumAxes, ns) = structure.C;
  plant->state_kinds.insert(plant->state_kinds.end(), structure.state_kinds.begin(), structure.state_kinds.end());
  plant->max_frequency_rad_s = std::max(plant->max_frequency_rad_s, structure.max_frequency_rad_s);
  const int group = static_cast<int>(plant->group_frequency_rad_s.size());
  plant->tolerance_group.resize(n, group);
  plant->group_frequency_rad_s.push_back(structure.max_frequency_rad_s);
}

// A coupled machine: each axis' drive first (under the servo its rigid servo states),
// then the structure driven by the three driven points.
void BuildCoupledMachinePlant(const ModalMachineConfig& modes, int own_axis, const DriveConfig& drive,
                              MachinePlant* result) {
  LinearPlant& plant = result->plant;
  std::vector<LinearPlant> servos;
  std::vector<int> first;
  if (drive.type == DriveType::kServo) {
    for (int axis = 0; axis < kNumAxes; ++axis) {
      first.push_back(plant.num_states());
      servos.push_back(BuildServoAxisPlant(nullptr, drive.servo));
      AppendAxis(servos.back(), axis, &plant);
    }
  }
  std::array<DrivenAcceleration, kNumAxes> driven;
  for (int axis = 0; axis < kNumAxes; ++axis) {
    driven[axis].states = Eigen::RowVectorXd::Zero(plant.num_states());
    if (!servos.empty()) driven[axis] = ServoDrivenAcceleration(servos[axis], first[axis], plant.num_states());
  }
  const LinearPlant structure = BuildCoupledModalPlant(modes, own_axis);
  AppendCoupledStructure(structure, driven, &plant);
  // The structure relative to the driven points: the same under either drive.
  result->static_gain = StaticGainByEntry(structure);
}

}  // namespace

const char* AxisName(int axis) {
  static const char* const kNames[kNumAxes] = {"x", "y", "z"};
  if (axis < 0 || axis >= kNumAxes) {
    throw std::out_of_range("AxisName: axis " + std::to_string(axis) + " is not 0, 1 or 2");
  }
  return kNames[axis];
}

std::string MultiAxisMachineConfig::AxisPrefix(int axis) const {
  return single_form ? std::string() : std::string("axes.") + AxisName(axis);
}

const ModalMachineConfig* MultiAxisMachineConfig::CoupledModes() const {
  if (!single_form || driven_axis < 0 || driven_axis >= kNumAxes || !axes[driven_axis]) return nullptr;
  const auto* modal = std::get_if<ModalMachineConfig>(&axes[driven_axis]->form);
  return modal != nullptr && modal->coupled() ? modal : nullptr;
}

bool MultiAxisMachineConfig::Models(int axis) const {
  return axes[axis].has_value() || CoupledModes() != nullptr;
}

namespace {

// Coupled modes only in the single form (one model for all axes), where no axis is rigid.
void ValidateCoupledPlacement(const MultiAxisMachineConfig& machine) {
  for (int axis = 0; axis < kNumAxes; ++axis) {
    const auto* modal = machine.axes[axis] ? std::get_if<ModalMachineConfig>(&machine.axes[axis]->form) : nullptr;
    if (modal == nullptr || !modal->coupled()) continue;
    if (!machine.single_form || axis != machine.driven_axis) {
      for (std::size_t i = 0; i < modal->modes.size(); ++i) {
        if (!modal->modes[i].coupled()) continue;
        const std::string prefix = machine.AxisPrefix(axis);
        throw ValidationError(
            (prefix.empty() ? "" : prefix + ".") + "modes[" + std::to_string(i) + "]" +
                (modal->modes[i].participation ? ".participation" : ".shape"),
            "coupled modes (participation, shape) belong to the single `modes:` form, which "
            "then models all three axes; under `axes:` each axis has its own independent model "
            "(use gain)");
      }
    }
    for (int other = 0; other < kNumAxes; ++other) {
      if (!machine.rigid[other]) continue;
      throw ValidationError("rigid", std::string("axis ") + AxisName(other) +
                                         " has a model in this machine (its coupled modes model every "
                                         "axis); only an axis without one can be rigid");
    }
  }
}

}  // namespace

void MultiAxisMachineConfig::validate() const {
  if (driven_axis < 0 || driven_axis >= kNumAxes) {
    throw ValidationError("driven_axis",
                          "must be x, y or z (0..2), got " + std::to_string(driven_axis));
  }
  for (int axis = 0; axis < kNumAxes; ++axis) {
    if (!stroke_m[axis]) continue;
    const auto& [lo, hi] = *stroke_m[axis];
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi)) {
      throw ValidationError(std::string("stroke.") + AxisName(axis),
                            "must be [min, max] in mm with min < max (got [" +
                                FormatNumber(lo * 1e3) + ", " + FormatNumber(hi * 1e3) + "])");
    }
  }
  for (int axis = 0; axis < kNumAxes; ++axis) {
    if (!axes[axis]) continue;  // rigid
    try {
      axes[axis]->validate();
    } catch (const ValidationError& error) {
      throw error.Prefixed(AxisPrefix(axis));
    }
  }
  ValidateCoupledPlacement(*this);
}

MachinePlant BuildMachinePlant(const MultiAxisMachineConfig& machine, const DriveConfig& drive) {
  machine.validate();
  drive.validate();
  MachinePlant result;
  LinearPlant& plant = result.plant;
  plant.A = Eigen::MatrixXd::Zero(0, 0);
  plant.B_accel = Eigen::MatrixXd::Zero(0, kNumAxes);
  plant.B_vel = Eigen::MatrixXd::Zero(0, kNumAxes);
  plant.C = Eigen::MatrixXd::Zero(2 * kNumAxes, 0);
  if (const ModalMachineConfig* coupled = machine.CoupledModes()) {
    BuildCoupledMachinePlant(*coupled, machine.driven_axis, drive, &result);
    return result;
  }
  for (int axis = 0; axis < kNumAxes; ++axis) {
    const std::optional<MachineConfig>& structure = machine.axes[axis];
    try {
      const NonlinearPlant block = BuildAxisPlant(structure, drive);
      const int n0 = plant.num_states();
      AppendAxis(block.linear, axis, &plant);
      AppendFollowingErrors(block, axis, plant.num_states(), &result.following_error_axis);
      for (NonlinearElement& e : result.nonlinear) {  // earlier axes': the states grew
        e.row_x.conservativeResizeLike(Eigen::VectorXd::Zero(plant.num_states()));
        e.column_x.conservativeResizeLike(Eigen::VectorXd::Zero(plant.num_states()));
      }
      AppendElements(block.elements, axis, n0, plant.num_states(), machine.AxisPrefix(axis),
                     &result.nonlinear);
      if (structure) {
        // The structure relative to the driven point: the same under either drive.
        result.static_gain(axis, axis) = BuildPlant(*structure).StaticGain()(0, 0);
      }
    } catch (const ValidationError& error) {
      // The structure's own fields (the servo's are checked by drive.validate() above).
      throw error.Prefixed(machine.AxisPrefix(axis));
    }
  }
  return result;
}

std::vector<AxisModes> AnalyzeMachineModes(const MultiAxisMachineConfig& machine) {
  machine.validate();
  std::vector<AxisModes> result;
  const ModalMachineConfig* coupled = machine.CoupledModes();
  for (int axis = 0; axis < kNumAxes; ++axis) {
    if (coupled != nullptr) {
      result.push_back({axis, AnalyzeCoupledAxis(*coupled, machine.driven_axis, axis)});
    } else if (machine.axes[axis]) {
      result.push_back({axis, AnalyzeModes(*machine.axes[axis])});
    }
  }
  return result;
}

namespace {
// LowestModeHz where every modelled axis is an uncoupled modal form, else NaN.
double LowestModalFormHz(const MultiAxisMachineConfig& machine) {
  if (machine.CoupledModes() != nullptr) return NAN;
  double lowest_hz = std::numeric_limits<double>::infinity();
  for (const auto& axis : machine.axes) {
    if (!axis.has_value()) continue;
    const auto* modal = std::get_if<ModalMachineConfig>(&axis->form);
    if (modal == nullptr || modal->coupled()) return NAN;
    for (const ModalMode& mode : modal->modes) lowest_hz = std::min(lowest_hz, mode.frequency_hz);
  }
  return lowest_hz;
}
}  // namespace

double LowestModeHz(const MultiAxisMachineConfig& machine) {
  const double lowest_hz = LowestModalFormHz(machine);
  if (!std::isnan(lowest_hz)) return lowest_hz;
  MachineDynamics dynamics;
  dynamics.axes = AnalyzeMachineModes(machine);
  return dynamics.LowestHz();
}

bool ConservesEnergy(const MultiAxisMachineConfig& machine) {
  for (const auto& axis : machine.axes) {
    if (axis && !ConservesEnergy(*axis)) return false;
  }
  return true;
}

MachineDynamics AnalyzeMachine(const MultiAxisMachineConfig& machine) {
  MachineDynamics dynamics;
  dynamics.axes = AnalyzeMachineModes(machine);
  dynamics.conserves_energy = ConservesEnergy(machine);
  return dynamics;
}

double MachineDynamics::LowestHz() const {
  double lowest_hz = std::numeric_limits<double>::infinity();
  for (const AxisModes& axis : axes) {
    for (const ModeInfo& mode : axis.analysis.modes) lowest_hz = std::min(lowest_hz, mode.frequency_hz);
  }
  return lowest_hz;
}

double MachineDynamics::LowestParticipatingHz(int axis, double min_share) const {
  for (const AxisModes& modes : axes) {
    if (modes.axis != axis) continue;
    for (const ModeInfo& mode : modes.analysis.modes) {  // ascending frequency
      if (std::abs(mode.participation) >= min_share) return mode.frequency_hz;
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double MachineDynamics::FastestParticipatingHz(double min_share) const {
  double fastest_hz = 0.0;
  for (const AxisModes& axis : axes) {
    for (const ModeInfo& mode : axis.analysis.modes) {
      if (std::abs(mode.participation) >= min_share) fastest_hz = std::max(fastest_hz, mode.frequency_hz);
    }
  }
  return fastest_hz;
}

}  // namespace shapebench::model
