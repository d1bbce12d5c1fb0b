// Coupled modal structures: modes that the accelerations of several axes excite and that
// deflect the tool along several axes (a moving column's rocking modes turn a Y move into
// X and Z deflection at the tool), given in the single `modes:` form by each mode's
// participation and shape (machine.h, ModalMode). Per mode i:
//   q_i'' + 2 zeta_i w_i q_i' + w_i^2 q_i = -sum_a participation_a,i acc_a
//   deflection_b = sum_i shape_b,i q_i
// Held accelerations give the static compliance C_ba = sum_i shape_b,i participation_a,i / w_i^2
// (m per m/s^2), in general not diagonal.
#pragma once

#include <Eigen/Dense>

#include "model/linear_plant.h"
#include "model/machine.h"

namespace shapebench::model {

// A mode's participation and shape as vectors over x, y, z. A gain mode (the one-axis
// shorthand) is participation e_axis and shape gain e_axis, axis the machine's own
// (`own_axis`, the single form's axis).
Eigen::Vector3d ModeParticipation(const ModalMode& mode, int own_axis);
Eigen::Vector3d ModeShape(const ModalMode& mode, int own_axis);

// The closed form C_ba = sum_i shape_b,i participation_a,i / w_i^2.
Eigen::Matrix3d ModalCompliance(const ModalMachineConfig& config, int own_axis);

// The part of a modal plant both forms share: per mode the states [q_i, q_i'] (A's 2 x 2
// block, the state kinds, the fastest w), in the config's order; B_accel, B_vel (n x
// num_inputs) and C (num_outputs x n) zero, for the form to fill.
LinearPlant ModalOscillatorPlant(const ModalMachineConfig& config, int num_inputs, int num_outputs);

// The structure relative to the driven points: inputs the three axes' accelerations,
// outputs the deflection along x, y, z (3 rows). States [q_i, q_i'] per mode in the
// config's order, q_i per unit of the mode's largest |participation_a| (its shape scaled
// up alike), with the very values BuildPlant gives a gain form: a coupled form whose modes
// all lie along one axis, each with shape x participation = gain and a participation
// whose ratio to 1 is a power of 2, is that axis' gain form, matrix entry for matrix entry.
LinearPlant BuildCoupledModalPlant(const ModalMachineConfig& config, int own_axis);

// The plant's static gain (held acceleration), entry (b, a) computed as LinearPlant::
// StaticGain computes the one-input, one-output plant of input a and output b: an axis'
// entry is then bit for bit the gain form's (multi_axis_machine.cc).
Eigen::Matrix3d StaticGainByEntry(const LinearPlant& plant);

// The modes as seen from a held acceleration along `axis`: each mode contributes
// v_i = shape_i participation_axis,i / w_i^2 to the static deflection vector s = sum v_i;
// its share is its projection on s, v_i . s / |s|^2 (the shares sum to 1), and
// static_deflection_per_accel_s2 is |s|. For a machine whose modes all lie along `axis`
// this is AnalyzeModes of the gain form, bit for bit.
ModalAnalysis AnalyzeCoupledAxis(const ModalMachineConfig& config, int own_axis, int axis);

}  // namespace shapebench::model
