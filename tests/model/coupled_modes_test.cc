// Coupled modal machines (model/coupled_modes.h) in the multi-axis plant: the static gain
// against the closed-form compliance computed here from the modes' numbers, the gain
// shorthand against its coupled spelling, the servo drive against the gain form's servo,
// the modal analysis and validation.
#include "common/math_constants.h"
#include "model/coupled_modes.h"

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "model/multi_axis_machine.h"
#include "tests/support/axes.h"

namespace shapebench::model {
namespace {


ModalMode Coupled(double frequency_hz, double damping_ratio, AxisVector participation, AxisVector shape) {
  ModalMode mode;
  mode.frequency_hz = frequency_hz;
  mode.damping_ratio = damping_ratio;
  mode.participation = participation;
  mode.shape = shape;
  return mode;
}

ModalMode Gain(double frequency_hz, double damping_ratio, double gain) {
  ModalMode mode;
  mode.frequency_hz = frequency_hz;
  mode.damping_ratio = damping_ratio;
  mode.gain = gain;
  return mode;
}

MultiAxisMachineConfig Single(std::vector<ModalMode> modes, int axis = kY) {
  ModalMachineConfig modal;
  modal.modes = std::move(modes);
  MultiAxisMachineConfig machine;
  machine.axes = {};
  machine.axes[axis] = MachineConfig{modal};
  machine.driven_axis = axis;
  return machine;
}

// The moving column of configs/machines/moving_column_fe.csv: a 25 Hz sway along Y and a
// 38 Hz rocking mode that X and Y accelerations excite and that deflects X, Y and Z.
MultiAxisMachineConfig TwoModes() {
  return Single({Coupled(25.0, 0.03, {0.0, 49.0, 0.0}, {0.0, 2.4166e-3, 0.0}),
                 Coupled(38.0, 0.04, {3.0, 12.0, 0.0}, {1.5e-3, 0.8e-3, 0.6e-3})});
}

// C_ba = sum_i shape_b,i participation_a,i / w_i^2, written out from TwoModes' numbers.
Eigen::Matrix3d TwoModesCompliance() {
  const double w1 = 2.0 * kPi * 25.0;
  const double w2 = 2.0 * kPi * 38.0;
  const Eigen::Vector3d p1(0.0, 49.0, 0.0), s1(0.0, 2.4166e-3, 0.0);
  const Eigen::Vector3d p2(3.0, 12.0, 0.0), s2(1.5e-3, 0.8e-3, 0.6e-3);
  Eigen::Matrix3d c;
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) c(b, a) = s1(b) * p1(a) / (w1 * w1) + s2(b) * p2(a) / (w2 * w2);
  }
  return c;
}

DriveConfig CoupledServo(double velocity_loop_hz) {
  DriveConfig drive;
  drive.type = DriveType::kServo;
  drive.servo.velocity_loop_hz = velocity_loop_hz;
  drive.servo.velocity_feedforward = 0.4;
  return drive;
}

// Tests that the plant's static gain (held acceleration) is minus the closed-form static
// compliance, cross terms included: MachinePlant::static_gain under the kinematic drive and
// both servos, and under the kinematic drive an independent static solve of the whole
// plant's deflection rows (a servo's static solve at zero velocity is no held
// acceleration: its drive velocity ramps). Tolerance 1e-12 of the largest entry: LU solves
// of 4 states.
TEST(CoupledModes, StaticGainIsTheClosedFormCompliance) {
  const Eigen::Matrix3d c = TwoModesCompliance();
  ASSERT_GT(c(kX, kY), 3e-7);  // a Y acceleration deflects X: the case at hand
  EXPECT_NEAR(ModalCompliance(*TwoModes().CoupledModes(), kY)(kX, kY), c(kX, kY), 1e-12 * c.maxCoeff());
  for (const DriveConfig& drive : {DriveConfig{}, CoupledServo(0.0), CoupledServo(150.0)}) {
    SCOPED_TRACE(drive.type == DriveType::kKinematic ? "kinematic" : "servo");
    const MachinePlant built = BuildMachinePlant(TwoModes(), drive);
    const Eigen::MatrixXd whole = built.plant.StaticGain();
    for (int b = 0; b < kNumAxes; ++b) {
      for (int a = 0; a < kNumAxes; ++a) {
        EXPECT_NEAR(built.static_gain(b, a), -c(b, a), 1e-12 * c.maxCoeff()) << b << ", " << a;
        if (drive.type != DriveType::kKinematic) continue;
        EXPECT_NEAR(whole(kDeflectionRow + b, a), -c(b, a), 1e-12 * c.maxCoeff()) << b << ", " << a;
      }
    }
  }
}

void ExpectSamePlant(const MachinePlant& x, const MachinePlant& y) {
  EXPECT_TRUE(x.plant.A == y.plant.A);
  EXPECT_TRUE(x.plant.B_accel == y.plant.B_accel);
  EXPECT_TRUE(x.plant.B_vel == y.plant.B_vel);
  EXPECT_TRUE(x.plant.C == y.plant.C);
  EXPECT_TRUE(x.plant.state_kinds == y.plant.state_kinds);
  EXPECT_TRUE(x.plant.tolerance_group == y.plant.tolerance_group);
  EXPECT_TRUE(x.plant.group_frequency_rad_s == y.plant.group_frequency_rad_s);
  EXPECT_EQ(x.plant.max_frequency_rad_s, y.plant.max_frequency_rad_s);
  EXPECT_TRUE(x.static_gain == y.static_gain);
}

// Tests that `gain: g` and its coupled spelling (participation p e_y, shape (g / p) e_y with
// p a power of 2) give the same plant entry for entry under the kinematic drive, and the
// same modal analysis along Y bit for bit; the coupled one models X and Z too, with no
// share there.
TEST(CoupledModes, GainShorthandIsTheCoupledFormEntryForEntry) {
  const MultiAxisMachineConfig gain = Single({Gain(25.0, 0.03, 0.5), Gain(70.0, 0.05, -0.2)});
  const MultiAxisMachineConfig coupled = Single({Coupled(25.0, 0.03, {0.0, 2.0, 0.0}, {0.0, 0.25, 0.0}),
                                                 Coupled(70.0, 0.05, {0.0, 1.0, 0.0}, {0.0, -0.2, 0.0})});
  ASSERT_NE(coupled.CoupledModes(), nullptr);
  ASSERT_EQ(gain.CoupledModes(), nullptr);
  ExpectSamePlant(BuildMachinePlant(gain, DriveConfig{}), BuildMachinePlant(coupled, DriveConfig{}));
  const std::vector<AxisModes> of_gain = AnalyzeMachineModes(gain);
  const std::vector<AxisModes> of_coupled = AnalyzeMachineModes(coupled);
  ASSERT_EQ(of_gain.size(), 1u);
  ASSERT_EQ(of_coupled.size(), 3u);
  const ModalAnalysis& y = of_coupled[kY].analysis;
  EXPECT_EQ(y.static_deflection_per_accel_s2, of_gain[0].analysis.static_deflection_per_accel_s2);
  ASSERT_EQ(y.modes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(y.modes[i].frequency_hz, of_gain[0].analysis.modes[i].frequency_hz);
    EXPECT_EQ(y.modes[i].damping_ratio, of_gain[0].analysis.modes[i].damping_ratio);
    EXPECT_EQ(y.modes[i].participation, of_gain[0].analysis.modes[i].participation);
    EXPECT_EQ(of_coupled[kX].analysis.modes[i].participation, 0.0);
    EXPECT_EQ(of_coupled[kZ].analysis.modes[i].participation, 0.0);
  }
  EXPECT_EQ(of_coupled[kX].analysis.static_deflection_per_accel_s2, 0.0);
}

// H(s) = C (sI - A)^-1 B at s = j w for one input column and output row.
std::complex<double> Response(const LinearPlant& plant, const Eigen::MatrixXd& b, int column, int row, double w) {
  const int n = plant.num_states();
  const Eigen::MatrixXcd m = std::complex<double>(0.0, w) * Eigen::MatrixXcd::Identity(n, n) -
                             plant.A.cast<std::complex<double>>();
  const Eigen::VectorXcd x = m.fullPivLu().solve(b.col(column).cast<std::complex<double>>());
  return (plant.C.row(row).cast<std::complex<double>>() * x)(0);
}

// Tests the coupled servo assembly (each axis' rigid servo, the structure driven by the
// motors' accelerations derived from the servo plant) against BuildServoAxisPlant's own
// structure-on-motor formulas: a coupled machine whose modes lie along Y responds, from Y's
// acceleration and velocity to Y's deflection and tool error, as the gain form under the
// same servo, at frequencies from 1 to 200 Hz (relative 1e-9: complex solves of at most 13
// states); X and Z answer 0 deflection.
TEST(CoupledModes, ServoDriveMatchesTheGainFormsServo) {
  const MultiAxisMachineConfig gain = Single({Gain(25.0, 0.03, 0.5), Gain(70.0, 0.05, -0.2)});
  const MultiAxisMachineConfig coupled = Single({Coupled(25.0, 0.03, {0.0, 2.0, 0.0}, {0.0, 0.25, 0.0}),
                                                 Coupled(70.0, 0.05, {0.0, 1.0, 0.0}, {0.0, -0.2, 0.0})});
  for (const double loop_hz : {0.0, 150.0}) {
    SCOPED_TRACE(loop_hz);
    const LinearPlant g = BuildMachinePlant(gain, CoupledServo(loop_hz)).plant;
    const LinearPlant c = BuildMachinePlant(coupled, CoupledServo(loop_hz)).plant;
    for (const double hz : {1.0, 10.0, 25.0, 40.0, 70.0, 200.0}) {
      const double w = 2.0 * kPi * hz;
      for (const int row : {kDeflectionRow + kY, kToolErrorRow + kY}) {
        for (const bool velocity : {false, true}) {
          const std::complex<double> expected = Response(g, velocity ? g.B_vel : g.B_accel, kY, row, w);
          const std::complex<double> got = Response(c, velocity ? c.B_vel : c.B_accel, kY, row, w);
          EXPECT_LE(std::abs(got - expected), 1e-9 * std::abs(expected)) << hz << " Hz, row " << row;
        }
      }
      EXPECT_EQ(std::abs(Response(c, c.B_accel, kY, kDeflectionRow + kX, w)), 0.0);
    }
  }
}

// Tests the modal analysis of a coupled machine: along Y each mode's share is its static
// deflection vector v_i = shape_i p_y,i / w_i^2 projected on their sum s (v_i . s / |s|^2,
// computed here), the shares sum to 1 and the static deflection is |s| = |C e_y|; along X
// the rocking mode carries it all (it participates there, so a pattern for an X move is
// designed for it); Z has none.
TEST(CoupledModes, AnalysisProjectsEachModeOnTheStaticDeflection) {
  const MultiAxisMachineConfig machine = TwoModes();
  const Eigen::Matrix3d c = TwoModesCompliance();
  const double w1 = 2.0 * kPi * 25.0;
  const double w2 = 2.0 * kPi * 38.0;
  const Eigen::Vector3d v1 = Eigen::Vector3d(0.0, 2.4166e-3, 0.0) * 49.0 / (w1 * w1);
  const Eigen::Vector3d v2 = Eigen::Vector3d(1.5e-3, 0.8e-3, 0.6e-3) * 12.0 / (w2 * w2);
  const Eigen::Vector3d s = v1 + v2;
  const std::vector<AxisModes> modes = AnalyzeMachineModes(machine);
  ASSERT_EQ(modes.size(), 3u);
  const ModalAnalysis& y = modes[kY].analysis;
  EXPECT_NEAR(y.static_deflection_per_accel_s2, c.col(kY).norm(), 1e-12 * c.col(kY).norm());
  EXPECT_NEAR(y.modes[0].participation, v1.dot(s) / s.squaredNorm(), 1e-12);
  EXPECT_NEAR(y.modes[1].participation, v2.dot(s) / s.squaredNorm(), 1e-12);
  EXPECT_NEAR(y.modes[0].participation + y.modes[1].participation, 1.0, 1e-12);
  EXPECT_NEAR(modes[kX].analysis.modes[1].participation, 1.0, 1e-12);
  EXPECT_EQ(modes[kX].analysis.modes[0].participation, 0.0);
  EXPECT_EQ(modes[kZ].analysis.static_deflection_per_accel_s2, 0.0);
  const MachineDynamics dynamics = AnalyzeMachine(machine);
  EXPECT_EQ(dynamics.LowestParticipatingHz(kX), 38.0);
  EXPECT_EQ(dynamics.LowestParticipatingHz(kY), 25.0);
  for (int axis = 0; axis < kNumAxes; ++axis) EXPECT_TRUE(machine.Models(axis));
}

std::string FieldOf(const MultiAxisMachineConfig& machine) {
  try {
    machine.validate();
  } catch (const ValidationError& error) {
    return error.field();
  }
  return "(valid)";
}

// Tests that validation names the field of a coupled mode that is incomplete, has a gain
// beside, or a non-finite component; coupled modes under `axes:` and a rigid axis beside
// coupled modes are refused; the one-axis BuildPlant refuses a coupled form.
TEST(CoupledModes, ValidationNamesTheField) {
  MultiAxisMachineConfig machine = TwoModes();
  EXPECT_EQ(FieldOf(machine), "(valid)");
  auto modal = [&]() -> ModalMachineConfig& { return std::get<ModalMachineConfig>(machine.axes[kY]->form); };
  modal().modes[1].participation.reset();
  EXPECT_EQ(FieldOf(machine), "modes[1].participation");
  machine = TwoModes();
  modal().modes[1].shape.reset();
  EXPECT_EQ(FieldOf(machine), "modes[1].shape");
  machine = TwoModes();
  modal().modes[0].gain = 2.0;
  EXPECT_EQ(FieldOf(machine), "modes[0].gain");
  machine = TwoModes();
  modal().modes[1].shape->x = NAN;
  EXPECT_EQ(FieldOf(machine), "modes[1].shape.x");
  machine = TwoModes();
  machine.rigid[kX] = true;
  EXPECT_EQ(FieldOf(machine), "rigid");
  machine = TwoModes();
  machine.single_form = false;
  EXPECT_EQ(FieldOf(machine), "axes.y.modes[0].participation");
  EXPECT_THROW(BuildPlant(*TwoModes().axes[kY]), std::logic_error);
}

}  // namespace
}  // namespace shapebench::model
