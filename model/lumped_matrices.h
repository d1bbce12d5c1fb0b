// Assembly of the lumped mass-spring-damper form (docs/scenario-reference.md) into second-order
// matrices, shared by BuildPlant and AnalyzeModes.
#pragma once

#include <Eigen/Dense>

#include "model/machine.h"

namespace shapebench::model {

// Generalized coordinates q: absolute displacements of the bodies along the driven axis.
// The "driven" endpoint sits at x_ref + u (x_ref = 0 for "ground", else q of the body the
// drive is mounted on), "ground" at 0. Each element stretches by Delta = D q + d u, so
//   M q'' + C q' + K q = -K_u u - C_u u'.
// Relative coordinates y = q - g u (g: the rigid motion the held command imposes) give
//   M y'' + C y' + K y = f a - (C g + C_u) v,   f = -M g,  a = u'', v = u'.
// With a `damping:` block (machine.h, LumpedDamping) C comes from M and K instead of the
// dashpots and acts on y alone: C_u = -C g, so C g + C_u = 0.
struct LumpedMatrices {
  Eigen::VectorXd mass_kg;  // M = diag(mass_kg)
  Eigen::MatrixXd K;
  Eigen::MatrixXd C;
  Eigen::VectorXd K_u;
  Eigen::VectorXd C_u;
  Eigen::VectorXd g;                // g = -K^{-1} K_u
  Eigen::VectorXd force_per_accel;  // f = -M g
  Eigen::VectorXd velocity_load;    // C g + C_u
  Eigen::VectorXd output;           // c: deflection = c^T y
  // Per element (config order): its stretch D g + d under the rigid motion per unit of
  // driven motion. All 0 when the structure follows the driven point freely; then also
  // C g + C_u = 0, and the force the elements exert on the driven point is
  // -(K_u^T y + C_u^T y'), independent of the driven point's own position.
  Eigen::VectorXd rigid_stretch;
  // Per element (config order): its stretch as element_D.row(i) q + element_d(i) u.
  Eigen::MatrixXd element_D;
  Eigen::VectorXd element_d;
};

// `config` must have passed validate() (K positive definite).
LumpedMatrices AssembleLumped(const LumpedMachineConfig& config);

}  // namespace shapebench::model
