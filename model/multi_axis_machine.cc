// The multi-axis machine: per-axis plants assembled block-diagonally (axes uncoupled).
#include "model/multi_axis_machine.h"

#include <cmath>

#include "common/format.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

#include "common/validation_error.h"
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

// Appends `block` (one input, two output rows) as axis `axis` of `plant`.
void AppendAxis(const LinearPlant& block, int axis, LinearPlant* plant) {
  const int n0 = plant->num_states();
  const int nb = block.num_states();
  const int n = n0 + nb;
  auto grow = [&](Eigen::MatrixXd* m, int rows, int cols) {
    Eigen::MatrixXd bigger = Eigen::MatrixXd::Zero(rows, cols);
    bigger.topLeftCorner(m->rows(), m->cols()) = *m;
    *m = std::move(bigger);
  };
  grow(&plant->A, n, n);
  grow(&plant->B_accel, n, kNumAxes);
  grow(&plant->B_vel, n, kNumAxes);
  grow(&plant->C, 2 * kNumAxes, n);
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
  for (int axis = 0; axis < kNumAxes; ++axis) {
    const std::optional<MachineConfig>& structure = machine.axes[axis];
    try {
      const NonlinearPlant block = BuildAxisPlant(structure, drive);
      const int n0 = plant.num_states();
      AppendAxis(block.linear, axis, &plant);
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
  for (int axis = 0; axis < kNumAxes; ++axis) {
    if (machine.axes[axis]) result.push_back({axis, AnalyzeModes(*machine.axes[axis])});
  }
  return result;
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
