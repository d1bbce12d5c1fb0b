// A linear time-invariant plant in state-space form, the common currency of the machine
// models and the integrators (a constant model, separate from the integrators' state).
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace shapebench::model {

enum class StateKind { kPosition, kVelocity };

// x' = A x + B_accel a(t) + B_vel v(t);   deflection = C x
// a, v: acceleration and velocity of the driven axes (one column per axis); the
// kinematic drive holds a constant over each interpolation period, so v is continuous
// and piecewise linear. States are deflections relative to the rigid-body motion the
// drive imposes, so they stay of the size of the deflection (tolerances make sense).
struct LinearPlant {
  Eigen::MatrixXd A;
  Eigen::MatrixXd B_accel;
  Eigen::MatrixXd B_vel;  // non-zero only where dampers load the structure from the drive
  Eigen::MatrixXd C;
  std::vector<StateKind> state_kinds;
  double max_frequency_rad_s = 0.0;  // the highest natural frequency, for tolerances
  // Tolerance groups (CvodeIntegrator's absolute tolerances): states of very different
  // sizes (a servo's following error, millimetres, beside a structural deflection,
  // micrometres) get their own scale. Within a group the position states share the largest
  // static magnitude of the group's position states, its velocity states that times the
  // group's frequency. Empty: one group of all states, of frequency max_frequency_rad_s.
  std::vector<int> tolerance_group;           // per state: 0 .. number of groups - 1
  std::vector<double> group_frequency_rad_s;  // per group

  int num_states() const { return static_cast<int>(A.rows()); }
  int num_inputs() const { return static_cast<int>(B_accel.cols()); }
  int num_outputs() const { return static_cast<int>(C.rows()); }

  // Deflection per unit acceleration held constant: the static solve A x = -B_accel a.
  Eigen::MatrixXd StaticGain() const;

  // Group of state i and the number of groups, whether or not tolerance_group is set.
  int ToleranceGroup(int i) const { return tolerance_group.empty() ? 0 : tolerance_group[i]; }
  int NumToleranceGroups() const;
  double GroupFrequency(int group) const {
    return group_frequency_rad_s.empty() ? max_frequency_rad_s : group_frequency_rad_s[group];
  }

  // The plant with the drive velocity appended to the state (v' = a), so that the input
  // is the acceleration alone: z = [x; v], z' = AugmentedA() z + AugmentedB() a, with
  // AugmentedA = [[A, B_vel], [0, 0]] and AugmentedB = [B_accel; I].
  Eigen::MatrixXd AugmentedA() const;
  Eigen::MatrixXd AugmentedB() const;
};

}  // namespace shapebench::model
