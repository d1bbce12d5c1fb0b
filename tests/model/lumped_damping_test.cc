// The lumped form's `damping:` block (machine.h, LumpedDamping): modal damping ratios and
// Rayleigh damping in place of dashpots, checked against an independent eigen-decomposition
// of the plant's A.
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "common/math_constants.h"
#include "common/validation_error.h"
#include "model/lumped_matrices.h"
#include "model/machine.h"
#include "model/servo_drive.h"

namespace shapebench::model {
namespace {


// A bed on its mounts carrying a column on the drive and a head on the column (the moving
// column's chain, lighter and softer so the eigenvalues are well conditioned), no dashpots.
LumpedMachineConfig UndampedChain() {
  LumpedMachineConfig config;
  config.bodies = {{"bed", 400.0}, {"column", 150.0}, {"head", 40.0}};
  config.elements = {{"mounts", "bed", "ground", 8e7, 0.0},
                     {"guides", "column", "driven", 6e6, 0.0},
                     {"z_guides", "head", "column", 2e7, 0.0}};
  config.driven_relative_to = "bed";
  config.output_body = "head";
  config.output_relative_to = "bed";
  return config;
}

MachineConfig Machine(const LumpedMachineConfig& config) { return MachineConfig{config}; }

// Undamped natural frequencies (rad/s, ascending) from K phi = w^2 M phi, independently of
// the code under test.
std::vector<double> UndampedOmegas(const LumpedMachineConfig& config) {
  const LumpedMatrices m = AssembleLumped(config);
  const Eigen::MatrixXd M = m.mass_kg.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(m.K, M, Eigen::EigenvaluesOnly);
  std::vector<double> w;
  for (int i = 0; i < solver.eigenvalues().size(); ++i) w.push_back(std::sqrt(solver.eigenvalues()(i)));
  return w;
}

struct PlantMode {
  double omega = 0.0;  // |lambda|
  double zeta = 0.0;   // -Re(lambda) / |lambda|
};

// The modes of the state matrix A: one per conjugate pair, ascending |lambda|.
std::vector<PlantMode> PlantModes(const LinearPlant& plant) {
  Eigen::EigenSolver<Eigen::MatrixXd> solver(plant.A, false);
  std::vector<PlantMode> modes;
  for (int i = 0; i < solver.eigenvalues().size(); ++i) {
    const std::complex<double> lambda = solver.eigenvalues()(i);
    if (lambda.imag() <= 0.0) continue;
    modes.push_back({std::abs(lambda), -lambda.real() / std::abs(lambda)});
  }
  std::sort(modes.begin(), modes.end(),
            [](const PlantMode& a, const PlantMode& b) { return a.omega < b.omega; });
  return modes;
}

// Tests that modal damping gives each mode exactly its requested zeta at its undamped
// frequency: in the eigenvalues of the plant's A and in AnalyzeModes.
TEST(LumpedDamping, ModalGivesEachModeItsZeta) {
  LumpedMachineConfig config = UndampedChain();
  const std::vector<double> w = UndampedOmegas(config);
  config.damping.kind = LumpedDampingKind::kModal;
  config.damping.modal = {0.02, 0.045, 0.011};
  const MachineConfig machine = Machine(config);

  const std::vector<PlantMode> modes = PlantModes(BuildPlant(machine));
  ASSERT_EQ(modes.size(), 3u);
  const ModalAnalysis analysis = AnalyzeModes(machine);
  ASSERT_EQ(analysis.modes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(modes[i].zeta, config.damping.modal[i], 1e-9) << "mode " << i;
    EXPECT_NEAR(modes[i].omega, w[i], 1e-9 * w[i]) << "mode " << i;
    EXPECT_NEAR(analysis.modes[i].damping_ratio, config.damping.modal[i], 1e-9) << "mode " << i;
    EXPECT_NEAR(analysis.modes[i].frequency_hz, w[i] / kTwoPi, 1e-9 * w[i]) << "mode " << i;
  }
}

// Tests that a modal list shorter than the modes repeats its last entry for the higher
// modes, and that a longer one is refused naming damping.modal.
TEST(LumpedDamping, ShortModalListRepeatsItsLastEntry) {
  LumpedMachineConfig config = UndampedChain();
  config.damping.kind = LumpedDampingKind::kModal;
  config.damping.modal = {0.05, 0.02};
  const std::vector<PlantMode> modes = PlantModes(BuildPlant(Machine(config)));
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_NEAR(modes[0].zeta, 0.05, 1e-9);
  EXPECT_NEAR(modes[1].zeta, 0.02, 1e-9);
  EXPECT_NEAR(modes[2].zeta, 0.02, 1e-9);

  config.damping.modal = {0.01, 0.02, 0.03, 0.04};
  try {
    Machine(config).validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "damping.modal");
    EXPECT_NE(e.message().find("3 modes"), std::string::npos) << e.message();
  }
}

// Tests that Rayleigh damping gives zeta_i = alpha / (2 w_i) + beta w_i / 2 at each
// undamped mode, in the plant's eigenvalues and in AnalyzeModes.
TEST(LumpedDamping, RayleighZetaPerMode) {
  LumpedMachineConfig config = UndampedChain();
  const std::vector<double> w = UndampedOmegas(config);
  config.damping.kind = LumpedDampingKind::kRayleigh;
  config.damping.rayleigh = {12.0, 4e-5};
  const MachineConfig machine = Machine(config);
  const std::vector<PlantMode> modes = PlantModes(BuildPlant(machine));
  const ModalAnalysis analysis = AnalyzeModes(machine);
  ASSERT_EQ(modes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const double zeta = 12.0 / (2.0 * w[i]) + 4e-5 * w[i] / 2.0;
    EXPECT_NEAR(modes[i].zeta, zeta, 1e-9) << "mode " << i;
    EXPECT_NEAR(analysis.modes[i].damping_ratio, zeta, 1e-9) << "mode " << i;
  }
}

// Tests that the block damps the deflection only: a held command velocity loads nothing
// (B_vel = 0), so a carriage moving at constant speed is not braked, and the static
// deflection is the undamped chain's.
TEST(LumpedDamping, RigidMotionIsNotDamped) {
  const LumpedMachineConfig undamped = UndampedChain();
  for (const LumpedDampingKind kind : {LumpedDampingKind::kModal, LumpedDampingKind::kRayleigh}) {
    LumpedMachineConfig config = undamped;
    config.damping.kind = kind;
    config.damping.modal = {0.03};
    config.damping.rayleigh = {5.0, 1e-4};
    const LinearPlant plant = BuildPlant(Machine(config));
    EXPECT_TRUE(plant.B_vel.isZero(0.0)) << plant.B_vel.transpose();
    const LumpedMatrices m = AssembleLumped(config);
    EXPECT_LT((m.C * m.g + m.C_u).norm(), 1e-9 * m.C.norm());
    EXPECT_NEAR(AnalyzeModes(Machine(config)).static_deflection_per_accel_s2,
                AnalyzeModes(Machine(undamped)).static_deflection_per_accel_s2, 1e-18);
  }
}

// Tests that a dashpot beside a damping block is refused naming the element's
// damping_n_s_m and the block, and that the block's numbers are checked.
TEST(LumpedDamping, DashpotBesideBlockAndBadNumbersAreRefused) {
  auto field_of = [](const LumpedMachineConfig& config) {
    try {
      Machine(config).validate();
    } catch (const ValidationError& e) {
      return e.field() + ": " + e.message();
    }
    return std::string("valid");
  };
  LumpedMachineConfig config = UndampedChain();
  config.damping.kind = LumpedDampingKind::kRayleigh;
  config.elements[1].damping_n_s_m = 300.0;
  const std::string both = field_of(config);
  EXPECT_EQ(both.rfind("elements[1].damping_n_s_m: ", 0), 0u) << both;
  EXPECT_NE(both.find("damping.rayleigh"), std::string::npos) << both;
  config.elements[1].damping_n_s_m = 0.0;
  EXPECT_EQ(field_of(config), "valid");
  config.damping.rayleigh.beta = -1e-5;
  EXPECT_EQ(field_of(config).rfind("damping.rayleigh.beta: ", 0), 0u) << field_of(config);
  config.damping.kind = LumpedDampingKind::kModal;
  config.damping.modal = {0.02, 1.0};
  EXPECT_EQ(field_of(config).rfind("damping.modal[1]: ", 0), 0u) << field_of(config);
  config.damping.modal = {};
  EXPECT_EQ(field_of(config).rfind("damping.modal: ", 0), 0u) << field_of(config);
}

// Tests that stiffness-proportional Rayleigh damping (alpha 0) is the same structure as a
// dashpot c = beta k on every element: the same kinematic plant and, through the drive's
// reaction, the same servo plant, to rounding.
TEST(LumpedDamping, BetaOnlyRayleighEqualsDashpotsAlongTheSprings) {
  const double beta = 3e-5;
  LumpedMachineConfig dashpots = UndampedChain();
  for (LumpedElement& e : dashpots.elements) e.damping_n_s_m = beta * e.stiffness_n_m;
  LumpedMachineConfig block = UndampedChain();
  block.damping.kind = LumpedDampingKind::kRayleigh;
  block.damping.rayleigh = {0.0, beta};
  const MachineConfig a = Machine(dashpots);
  const MachineConfig b = Machine(block);
  const LinearPlant x = BuildPlant(a);
  const LinearPlant y = BuildPlant(b);
  EXPECT_LT((x.A - y.A).norm(), 1e-12 * x.A.norm());
  EXPECT_LT((x.B_accel - y.B_accel).norm(), 1e-12 * x.B_accel.norm());
  EXPECT_LT((x.B_vel - y.B_vel).norm(), 1e-9);  // both 0 up to rounding: free following
  const ServoConfig servo;  // a finite velocity loop: the reaction C_u enters the motor
  const LinearPlant xs = BuildServoAxisPlant(&a, servo);
  const LinearPlant ys = BuildServoAxisPlant(&b, servo);
  ASSERT_EQ(xs.A.rows(), ys.A.rows());
  EXPECT_LT((xs.A - ys.A).norm(), 1e-12 * xs.A.norm());
}

// Tests that a block of zeros conserves energy and any nonzero ratio does not.
TEST(LumpedDamping, ConservesEnergyOnlyWhenAllZero) {
  LumpedMachineConfig config = UndampedChain();
  EXPECT_TRUE(ConservesEnergy(Machine(config)));
  config.damping.kind = LumpedDampingKind::kModal;
  config.damping.modal = {0.0, 0.0};
  EXPECT_TRUE(ConservesEnergy(Machine(config)));
  config.damping.modal = {0.0, 0.01};
  EXPECT_FALSE(ConservesEnergy(Machine(config)));
  config.damping.kind = LumpedDampingKind::kRayleigh;
  EXPECT_TRUE(ConservesEnergy(Machine(config)));
  config.damping.rayleigh.beta = 1e-6;
  EXPECT_FALSE(ConservesEnergy(Machine(config)));
}

}  // namespace
}  // namespace shapebench::model
