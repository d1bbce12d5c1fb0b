#include "model/linear_plant.h"

namespace shapebench::model {

Eigen::MatrixXd LinearPlant::StaticGain() const {
  // Held acceleration: 0 = A x + B_accel a, so x = -A^{-1} B_accel a. A is non-singular for
  // a restrained, stable plant; a pivoted LU solve avoids forming the inverse.
  const Eigen::MatrixXd x_per_accel = A.fullPivLu().solve(-B_accel);
  return C * x_per_accel;
}

}  // namespace shapebench::model
