// The coupled modal structure (coupled_modes.h).
#include "model/coupled_modes.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace shapebench::model {
namespace {

Eigen::Vector3d FromAxes(const AxisVector& v) { return Eigen::Vector3d(v.x, v.y, v.z); }

Eigen::Vector3d Along(int axis, double value) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v(axis) = value;
  return v;
}

// +0 for any zero: -0.0 entries would make outputs -0.0 where a gain form's are +0.0.
double Entry(double value) { return value == 0.0 ? 0.0 : value; }

}  // namespace

Eigen::Vector3d ModeParticipation(const ModalMode& mode, int own_axis) {
  return mode.participation ? FromAxes(*mode.participation) : Along(own_axis, 1.0);
}

Eigen::Vector3d ModeShape(const ModalMode& mode, int own_axis) {
  return mode.shape ? FromAxes(*mode.shape) : Along(own_axis, mode.gain);
}

Eigen::Matrix3d ModalCompliance(const ModalMachineConfig& config, int own_axis) {
  Eigen::Matrix3d compliance = Eigen::Matrix3d::Zero();
  for (const ModalMode& mode : config.modes) {
    const double w = kTwoPi * mode.frequency_hz;
    compliance += ModeShape(mode, own_axis) * ModeParticipation(mode, own_axis).transpose() / (w * w);
  }
  return compliance;
}

LinearPlant ModalOscillatorPlant(const ModalMachineConfig& config, int num_inputs, int num_outputs) {
  const int num_modes = static_cast<int>(config.modes.size());
  const int n = 2 * num_modes;
  LinearPlant plant;
  plant.A = Eigen::MatrixXd::Zero(n, n);
  plant.B_accel = Eigen::MatrixXd::Zero(n, num_inputs);
  plant.B_vel = Eigen::MatrixXd::Zero(n, num_inputs);
  plant.C = Eigen::MatrixXd::Zero(num_outputs, n);
  for (int i = 0; i < num_modes; ++i) {
    const ModalMode& mode = config.modes[i];
    const double w = kTwoPi * mode.frequency_hz;
    const int q = 2 * i;  // states [q_i, q_i']
    plant.A(q, q + 1) = 1.0;
    plant.A(q + 1, q) = -w * w;
    plant.A(q + 1, q + 1) = -2.0 * mode.damping_ratio * w;
    plant.state_kinds.push_back(StateKind::kPosition);
    plant.state_kinds.push_back(StateKind::kVelocity);
    plant.max_frequency_rad_s = std::max(plant.max_frequency_rad_s, w);
  }
  return plant;
}

// Not the gain form's B and C with participation e_axis, shape gain e_axis: those would
// be the same but for the sign of a zero gain (Entry writes +0, the gain form keeps -0.0).
LinearPlant BuildCoupledModalPlant(const ModalMachineConfig& config, int own_axis) {
  config.validate();
  LinearPlant plant = ModalOscillatorPlant(config, 3, 3);
  for (std::size_t i = 0; i < config.modes.size(); ++i) {
    const ModalMode& mode = config.modes[i];
    Eigen::Vector3d participation = ModeParticipation(mode, own_axis);
    Eigen::Vector3d shape = ModeShape(mode, own_axis);
    // q's scale is free: q_i is taken per unit of the largest participation, so that the
    // states are deflections (an FE export's sqrt(kg) scale would make them 50 times the
    // tool's), and participation {y: 2}, shape {y: 0.25} is gain 0.5 exactly.
    const double scale = participation.cwiseAbs().maxCoeff();
    if (scale > 0.0 && scale != 1.0) {
      participation /= scale;
      shape *= scale;
    }
    const int q = 2 * static_cast<int>(i);
    for (int axis = 0; axis < 3; ++axis) {
      plant.B_accel(q + 1, axis) = Entry(-participation(axis));
      plant.C(axis, q) = Entry(shape(axis));
    }
  }
  return plant;
}

Eigen::Matrix3d StaticGainByEntry(const LinearPlant& plant) {
  // LinearPlant::StaticGain's operations on one column and one row: the same LU, the same
  // solve of an n x 1 right-hand side, the same 1 x n by n x 1 product.
  const auto lu = plant.A.fullPivLu();
  Eigen::Matrix3d gain = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) {
    const Eigen::MatrixXd b = plant.B_accel.col(a);
    const Eigen::MatrixXd x_per_accel = lu.solve(-b);
    for (int row = 0; row < 3; ++row) {
      const Eigen::MatrixXd c = plant.C.row(row);
      gain(row, a) = (c * x_per_accel)(0, 0);
    }
  }
  return gain;
}

ModalAnalysis AnalyzeCoupledAxis(const ModalMachineConfig& config, int own_axis, int axis) {
  config.validate();
  // The same operations as AnalyzeModes' gain form (machine.cc) where the modes lie along
  // `axis`: (shape participation) / (w w), summed in the config's order.
  std::vector<Eigen::Vector3d> contributions;
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (const ModalMode& mode : config.modes) {
    const double w = kTwoPi * mode.frequency_hz;
    const double participation = ModeParticipation(mode, own_axis)(axis);
    const Eigen::Vector3d shape = ModeShape(mode, own_axis);
    Eigen::Vector3d v;
    for (int b = 0; b < 3; ++b) v(b) = shape(b) * participation / (w * w);
    contributions.push_back(v);
    for (int b = 0; b < 3; ++b) total(b) += v(b);
  }
  const double norm = std::sqrt(total(0) * total(0) + total(1) * total(1) + total(2) * total(2));
  ModalAnalysis analysis;
  for (std::size_t i = 0; i < config.modes.size(); ++i) {
    const ModalMode& mode = config.modes[i];
    const Eigen::Vector3d& v = contributions[i];
    double share = 0.0;
    if (norm != 0.0) {
      // Along one axis the direction is +-1 there and 0 elsewhere: +-v / |s| = v / s exactly.
      const Eigen::Vector3d direction = total / norm;
      share = (v(0) * direction(0) + v(1) * direction(1) + v(2) * direction(2)) / norm;
    }
    analysis.modes.push_back({mode.frequency_hz, mode.damping_ratio, share});
  }
  std::stable_sort(
      analysis.modes.begin(), analysis.modes.end(),
      [](const ModeInfo& a, const ModeInfo& b) { return a.frequency_hz < b.frequency_hz; });
  analysis.static_deflection_per_accel_s2 = norm;
  return analysis;
}

}  // namespace shapebench::model
