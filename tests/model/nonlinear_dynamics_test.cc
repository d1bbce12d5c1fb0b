// NonlinearDynamics (model/nonlinear_dynamics.h): the Jacobian CVODE's Newton iteration is
// given is the right-hand side's derivative, and a stuck element's holding force keeps its
// relative velocity still.
#include "model/nonlinear_dynamics.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "model/multi_axis_machine.h"

namespace shapebench::model {
namespace {

// A servo axis (velocity loop, drive friction and force limit) moving a table over a screw
// with backlash, the table's column on LuGre guides, the table on Stribeck ways.
NonlinearPlant EveryKind(FrictionModel drive_friction) {
  LumpedMachineConfig lumped;
  lumped.bodies = {{"table", 200.0}, {"column", 800.0}};
  LumpedElement screw{"screw", "driven", "table", 2.0e8, 0.0};
  screw.backlash_m = 1e-5;
  LumpedElement column{"column_mount", "column", "table", 5.0e8, 2.0e4};
  LumpedElement guides{"guides", "column", "table"};
  guides.friction = {FrictionModel::kLuGre, 100.0, 150.0, 1e-3, 20.0, 1e7, 1e3};
  LumpedElement ways{"ways", "table", "ground"};
  ways.friction = {FrictionModel::kStribeck, 80.0, 120.0, 2e-3, 10.0, 0.0, 0.0};
  lumped.elements = {screw, column, guides, ways};
  lumped.output_body = "table";
  MultiAxisMachineConfig machine;
  machine.axes[1] = MachineConfig{lumped};
  DriveConfig drive;
  drive.type = DriveType::kServo;
  drive.servo.friction = {drive_friction, 40.0, 60.0, drive_friction == FrictionModel::kCoulomb ? 0.0 : 1e-3,
                          5.0, 0.0, 0.0};
  drive.servo.force_limit_n = 2000.0;
  const MachinePlant built = BuildMachinePlant(machine, drive);
  return {built.plant, built.nonlinear, built.following_error_axis};
}

// Central differences of the right-hand side, column by column.
Eigen::MatrixXd NumericJacobian(NonlinearDynamics* dynamics, const Eigen::VectorXd& y) {
  const int n = dynamics->size();
  Eigen::MatrixXd jac(n, n);
  Eigen::VectorXd plus(n), minus(n);
  for (int j = 0; j < n; ++j) {
    // 1e-3 of the state (of the largest, for one near 0): rounding (1e-16 of the forces
    // over h) and truncation (the third derivative times h^2) stay below the comparison's
    // 1e-5, and no step reaches across a kink (LuGre's |w| at w = 0).
    const double h = 1e-3 * std::max(std::abs(y(j)), 1e-2 * y.cwiseAbs().maxCoeff());
    Eigen::VectorXd yp = y, ym = y;
    yp(j) += h;
    ym(j) -= h;
    dynamics->Rhs(yp.data(), plus.data());
    dynamics->Rhs(ym.data(), minus.data());
    jac.col(j) = (plus - minus) / (2.0 * h);
  }
  return jac;
}

// Tests that the Jacobian equals central differences of the right-hand side (to 1e-5 of
// each row's largest entry, or of its linear part's: the differences' own error) in several modes: sliding and LuGre
// elements, the screw in contact and in its gap, the force limit reached, and with the
// drive's Coulomb friction stuck (its holding force differentiated through the others).
TEST(NonlinearDynamics, JacobianIsTheDerivativeOfTheRightHandSide) {
  std::vector<std::vector<bool>> seen;  // per element, modes -1, 0, +1 met
  for (FrictionModel drive_friction : {FrictionModel::kStribeck, FrictionModel::kCoulomb}) {
    const NonlinearPlant plant = EveryKind(drive_friction);
    NonlinearDynamics dynamics(plant);
    const int n = dynamics.size();
    const int nz = dynamics.num_augmented();
    ASSERT_EQ(n, nz + 1);  // one LuGre bristle
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 6; ++trial) {
      Eigen::VectorXd y(n);
      for (int i = 0; i < n; ++i) y(i) = 1e-5 * unit(rng);  // positions, velocities alike
      y(n - 1) = 5e-6 * unit(rng);                         // the bristle
      if (trial % 2 == 1) {
        // Y's motor at rest (its friction's w = v + e' = 0) and small deflections: stuck.
        y *= 1e-4;
        const NonlinearElement& drive_y = plant.elements[5];
        for (int i = 0; i < drive_y.row_x.size(); ++i) {
          if (drive_y.row_x(i) != 0.0) y(i) = 0.0;
        }
        y.segment(plant.linear.num_states(), 3).setZero();
      }
      Eigen::VectorXd forcing = Eigen::VectorXd::Zero(nz);
      forcing.tail(3) = Eigen::Vector3d(0.0, 0.5 * unit(rng), 0.0);
      dynamics.SetForcing(forcing);
      dynamics.InitModes(y.data());
      seen.resize(dynamics.num_elements(), std::vector<bool>(3, false));
      for (int e = 0; e < dynamics.num_elements(); ++e) seen[e][dynamics.mode(e) + 1] = true;
      Eigen::MatrixXd analytic(n, n);
      dynamics.Jacobian(y.data(), analytic.data());
      const Eigen::MatrixXd numeric = NumericJacobian(&dynamics, y);
      const Eigen::MatrixXd linear = plant.linear.AugmentedA();
      for (int r = 0; r < n; ++r) {
        // The row's scale: its entries, or the linear part's that a holding force cancels
        // (a stuck motor's row is 0 from terms of 1e4 /s: their differences' rounding).
        double scale = std::max(1.0, numeric.row(r).cwiseAbs().maxCoeff());
        if (r < nz) scale = std::max(scale, linear.row(r).cwiseAbs().maxCoeff());
        for (int c = 0; c < n; ++c) {
          EXPECT_NEAR(analytic(r, c), numeric(r, c), 1e-5 * scale) << "trial " << trial << " row " << r << " col " << c;
        }
      }
    }
  }
  // The plant's elements in axis order: X's drive friction and force limit (every servo axis
  // has them), Y's screw (backlash), guides (LuGre), ways (Stribeck), drive friction, force
  // limit, then Z's two. Each mode the test claims was met on Y.
  ASSERT_EQ(seen.size(), 9u);
  EXPECT_TRUE(seen[2][1] && (seen[2][0] || seen[2][2])) << "the screw in its gap and in contact";
  EXPECT_TRUE(seen[4][0] || seen[4][2]) << "the ways sliding";
  EXPECT_TRUE(seen[5][1]) << "the drive's friction stuck";
  EXPECT_TRUE(seen[6][0] || seen[6][2]) << "the force limit reached";
}

// Tests that a stuck element's holding force keeps its relative velocity still: with the
// drive friction stuck (the motor at rest, its w exactly 0), the right-hand side leaves w'
// at 0 whatever the other states, and HandleRoots' impulse zeroes a small w.
TEST(NonlinearDynamics, AStuckElementHoldsItsVelocity) {
  const NonlinearPlant plant = EveryKind(FrictionModel::kCoulomb);
  NonlinearDynamics dynamics(plant);
  const int n = dynamics.size();
  const NonlinearElement* drive = nullptr;
  for (const NonlinearElement& e : plant.elements) {
    if (e.name.rfind("drive.friction", 0) == 0) drive = &e;
  }
  ASSERT_NE(drive, nullptr);
  Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
  row.head(drive->row_x.size()) = drive->row_x;
  row.segment(drive->row_x.size(), 3) = drive->row_v;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);  // at rest: w = 0, the holding force 0
  dynamics.SetForcing(Eigen::VectorXd::Zero(dynamics.num_augmented()));
  dynamics.InitModes(y.data());
  Eigen::VectorXd ydot(n);
  dynamics.Rhs(y.data(), ydot.data());
  EXPECT_EQ(row.dot(ydot), 0.0);
  // A state with small deflections (w still 0): the holding force balances them, within F_s.
  y(0) = 1e-9;
  y(1) = -2e-9;
  dynamics.Rhs(y.data(), ydot.data());
  EXPECT_NEAR(row.dot(ydot), 0.0, 1e-12 * ydot.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace shapebench::model
