#include "model/linear_plant.h"

#include <algorithm>

namespace shapebench::model {

Eigen::MatrixXd LinearPlant::StaticGain() const {
  // Held acceleration: 0 = A x + B_accel a, so x = -A^{-1} B_accel a. A is non-singular for
  // a restrained, stable plant; a pivoted LU solve avoids forming the inverse.
  const Eigen::MatrixXd x_per_accel = A.fullPivLu().solve(-B_accel);
  return C * x_per_accel;
}

int LinearPlant::NumToleranceGroups() const {
  int groups = 1;
  for (int group : tolerance_group) groups = std::max(groups, group + 1);
  return groups;
}

Eigen::MatrixXd LinearPlant::AugmentedA() const {
  const Eigen::Index n = A.rows();
  const Eigen::Index m = B_accel.cols();
  Eigen::MatrixXd a_z = Eigen::MatrixXd::Zero(n + m, n + m);
  a_z.topLeftCorner(n, n) = A;
  a_z.topRightCorner(n, m) = B_vel;
  return a_z;
}

Eigen::MatrixXd LinearPlant::AugmentedB() const {
  const Eigen::Index n = A.rows();
  const Eigen::Index m = B_accel.cols();
  Eigen::MatrixXd b_z = Eigen::MatrixXd::Zero(n + m, m);
  b_z.topRows(n) = B_accel;
  b_z.bottomRows(m).setIdentity();
  return b_z;
}

}  // namespace shapebench::model
