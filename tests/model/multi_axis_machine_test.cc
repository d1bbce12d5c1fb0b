// The multi-axis machine: block-diagonal assembly of uncoupled axes, validation paths,
// per-axis modes, and integration of a plant whose unmodelled axes have no states.
#include "model/multi_axis_machine.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "model/integrator.h"
#include "tests/support/axes.h"

namespace shapebench::model {
namespace {


MachineConfig AxisModal(std::vector<ModalMode> modes) {
  return MachineConfig{ModalMachineConfig{std::move(modes)}};
}

// A column on a damped screw on a bed on damped mounts (the lumped form, driven from the
// bed, following the driven point freely so a servo with a velocity loop accepts it).
MachineConfig LumpedColumn() {
  LumpedMachineConfig c;
  c.bodies = {{"bed", 5000.0}, {"column", 2000.0}};
  c.elements = {{"mounts", "bed", "ground", 1.2e9, 2e5}, {"screw", "column", "driven", 5e7, 2e4}};
  c.driven_relative_to = "bed";
  c.output_body = "column";
  c.output_relative_to = "bed";
  return MachineConfig{c};
}

MultiAxisMachineConfig ThreeAxes() {
  MultiAxisMachineConfig machine;
  machine.single_form = false;
  machine.axes[kX] = LumpedColumn();
  machine.axes[kY] = AxisModal({{25.0, 0.03, 1.0}, {70.0, 0.05, -0.2}});
  machine.axes[kZ] = AxisModal({{90.0, 0.02, 1.0}});
  return machine;
}

DriveConfig ServoDrive(double velocity_loop_hz) {
  DriveConfig drive;
  drive.type = DriveType::kServo;
  drive.servo.velocity_loop_hz = velocity_loop_hz;
  drive.servo.velocity_feedforward = 0.4;
  return drive;
}

// Tests the block structure under both drives: an input on one axis reaches only that axis'
// states and output rows (checked on the static responses to acceleration and velocity and
// on the matrix pattern), static_gain is diagonal with each axis' signed static deflection
// (AnalyzeModes' magnitude), the same under the servo; under the kinematic drive rows 3..5
// equal rows 0..2.
TEST(MultiAxisMachine, BlockDiagonalAssembly) {
  const MultiAxisMachineConfig machine = ThreeAxes();
  for (const DriveConfig& drive : {DriveConfig{}, ServoDrive(0.0), ServoDrive(150.0)}) {
    SCOPED_TRACE(drive.type == DriveType::kKinematic
                     ? "kinematic"
                     : "servo " + std::to_string(drive.servo.velocity_loop_hz));
    const MachinePlant built = BuildMachinePlant(machine, drive);
    const LinearPlant& plant = built.plant;
    ASSERT_EQ(plant.num_inputs(), kNumAxes);
    ASSERT_EQ(plant.num_outputs(), 2 * kNumAxes);
    ASSERT_EQ(static_cast<int>(plant.state_kinds.size()), plant.num_states());
    ASSERT_EQ(static_cast<int>(plant.tolerance_group.size()), plant.num_states());
    // The states each input reaches (B column non-zero) form the axis' block: no A entry
    // links two blocks, no output row of one axis reads another's states.
    std::vector<int> owner(plant.num_states(), -1);
    for (int axis = 0; axis < kNumAxes; ++axis) {
      for (int i = 0; i < plant.num_states(); ++i) {
        if (plant.B_accel(i, axis) != 0.0 || plant.B_vel(i, axis) != 0.0) {
          ASSERT_TRUE(owner[i] == -1 || owner[i] == axis);
          owner[i] = axis;
        }
      }
    }
    // States reached from no input directly (e.g. modal positions) belong to the block
    // whose states feed them.
    for (int pass = 0; pass < plant.num_states(); ++pass) {
      for (int i = 0; i < plant.num_states(); ++i) {
        for (int j = 0; j < plant.num_states(); ++j) {
          if (plant.A(i, j) != 0.0 && owner[j] != -1 && owner[i] == -1) owner[i] = owner[j];
        }
      }
    }
    for (int i = 0; i < plant.num_states(); ++i) {
      ASSERT_NE(owner[i], -1) << "state " << i;
      for (int j = 0; j < plant.num_states(); ++j) {
        if (plant.A(i, j) != 0.0) {
          EXPECT_EQ(owner[i], owner[j]) << i << ", " << j;
        }
      }
      for (int row = 0; row < plant.num_outputs(); ++row) {
        if (plant.C(row, i) != 0.0) {
          EXPECT_EQ(row % kNumAxes, owner[i]) << row << ", " << i;
        }
      }
    }
    const Eigen::MatrixXd per_accel = plant.StaticGain();
    const Eigen::MatrixXd per_velocity = plant.C * plant.A.fullPivLu().solve(-plant.B_vel);
    for (int row = 0; row < plant.num_outputs(); ++row) {
      for (int axis = 0; axis < kNumAxes; ++axis) {
        if (row % kNumAxes == axis) continue;
        EXPECT_EQ(per_accel(row, axis), 0.0) << row << ", " << axis;
        EXPECT_EQ(per_velocity(row, axis), 0.0) << row << ", " << axis;
      }
    }
    const std::vector<AxisModes> modes = AnalyzeMachineModes(machine);
    ASSERT_EQ(modes.size(), 3u);
    for (int axis = 0; axis < kNumAxes; ++axis) {
      EXPECT_EQ(modes[axis].axis, axis);
      const double expected = modes[axis].analysis.static_deflection_per_accel_s2;
      EXPECT_NEAR(std::abs(built.static_gain(axis, axis)), expected, 1e-12 * expected);
      EXPECT_LT(built.static_gain(axis, axis), 0.0);  // the structure lags the acceleration
      for (int other = 0; other < kNumAxes; ++other) {
        if (other != axis) {
          EXPECT_EQ(built.static_gain(axis, other), 0.0);
        }
      }
    }
    if (drive.type == DriveType::kKinematic) {
      EXPECT_EQ(plant.C.middleRows(kToolErrorRow, kNumAxes),
                plant.C.middleRows(kDeflectionRow, kNumAxes));
      // The blocks are the single-axis plants.
      EXPECT_EQ(plant.num_states(), BuildPlant(*machine.axes[kX]).num_states() +
                                        BuildPlant(*machine.axes[kY]).num_states() +
                                        BuildPlant(*machine.axes[kZ]).num_states());
    }
  }
}

// Tests that an axis without a structural model is rigid: no states under the kinematic
// drive (its output rows are 0), only the servo's states under a servo; a machine may be
// rigid altogether.
TEST(MultiAxisMachine, RigidAxes) {
  MultiAxisMachineConfig machine;
  machine.axes[kY] = AxisModal({{25.0, 0.0, 1.0}});
  const MachinePlant kinematic = BuildMachinePlant(machine, DriveConfig{});
  EXPECT_EQ(kinematic.plant.num_states(), 2);
  EXPECT_TRUE(kinematic.plant.B_accel.col(kX).isZero());
  EXPECT_TRUE(kinematic.plant.C.row(kDeflectionRow + kX).isZero());
  EXPECT_TRUE(kinematic.plant.C.row(kToolErrorRow + kZ).isZero());
  EXPECT_EQ(kinematic.static_gain(kX, kX), 0.0);
  EXPECT_EQ(BuildMachinePlant(machine, ServoDrive(0.0)).plant.num_states(), 2 + 3 * 1);
  EXPECT_EQ(BuildMachinePlant(machine, ServoDrive(200.0)).plant.num_states(), 2 + 3 * 3);

  MultiAxisMachineConfig rigid;
  rigid.axes = {};
  rigid.single_form = false;
  EXPECT_NO_THROW(rigid.validate());
  EXPECT_TRUE(AnalyzeMachineModes(rigid).empty());
  const MachinePlant none = BuildMachinePlant(rigid, DriveConfig{});
  EXPECT_EQ(none.plant.num_states(), 0);
  EXPECT_EQ(none.plant.num_inputs(), kNumAxes);
  EXPECT_EQ(none.plant.num_outputs(), 2 * kNumAxes);
  EXPECT_TRUE(none.static_gain.isZero());
  EXPECT_EQ(BuildMachinePlant(rigid, ServoDrive(0.0)).plant.num_states(), 3);
}

// Tests that a three-input plant with one modelled axis integrates exactly like that axis'
// single-input plant (BuildPlant), bit for bit under CVODE: the stateless axes' inputs
// are left out of the integration.
TEST(MultiAxisMachine, StatelessAxesLeaveIntegrationUnchanged) {
  MultiAxisMachineConfig machine;
  machine.axes[kY] = AxisModal({{25.0, 0.02, 1.0}, {70.0, 0.05, -0.4}});
  const MachinePlant built = BuildMachinePlant(machine, DriveConfig{});
  const LinearPlant single = BuildPlant(*machine.axes[kY]);
  for (const IntegratorMethod method : {IntegratorMethod::kCvode, IntegratorMethod::kExact}) {
    IntegratorConfig config;
    config.method = method;
    auto multi = MakeIntegrator(built.plant, config, 1e-3, 4, 1.667);
    auto one = MakeIntegrator(single, config, 1e-3, 4, 1.667);
    multi->Reset(Eigen::VectorXd::Zero(kNumAxes));
    one->Reset(Eigen::VectorXd::Zero(1));
    for (int tick = 0; tick < 120; ++tick) {
      const double a = tick < 30 ? 1.667 : tick < 60 ? 0.0 : tick < 90 ? -1.667 : 0.0;
      Eigen::VectorXd input = Eigen::VectorXd::Zero(kNumAxes);
      input(kY) = a;
      multi->SetInput(input);
      one->SetInput(Eigen::VectorXd::Constant(1, a));
      for (int j = 0; j < 4; ++j) {
        multi->Step();
        one->Step();
        ASSERT_EQ(multi->Output()(kDeflectionRow + kY), one->Output()(0));
        ASSERT_EQ(multi->Output()(kToolErrorRow + kY), one->Output()(0));
      }
    }
    EXPECT_EQ(multi->Stats().steps, one->Stats().steps);
  }
}

// Tests validation paths: the multi-axis form prefixes the axis ("axes.x.modes[0]..."),
// the single form keeps the form's own names, the driven axis must be modelled, and a
// lumped error found only when building the servo plant is prefixed alike.
TEST(MultiAxisMachine, ValidationNamesTheAxis) {
  MultiAxisMachineConfig machine = ThreeAxes();
  std::get<ModalMachineConfig>(machine.axes[kY]->form).modes[1].frequency_hz = -1.0;
  try {
    machine.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "axes.y.modes[1].frequency_hz");
  }
  machine.single_form = true;
  try {
    BuildMachinePlant(machine, DriveConfig{});
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "modes[1].frequency_hz");
  }

  MultiAxisMachineConfig no_y;
  no_y.axes = {};
  no_y.single_form = false;
  no_y.axes[kX] = LumpedColumn();
  no_y.driven_axis = 3;
  try {
    no_y.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "driven_axis");
  }
  no_y.driven_axis = kY;  // rigid: allowed
  EXPECT_NO_THROW(no_y.validate());

  LumpedMachineConfig stretched = std::get<LumpedMachineConfig>(LumpedColumn().form);
  stretched.elements.push_back({"wiper", "column", "ground", 0.0, 500.0});
  no_y.axes[kX] = MachineConfig{stretched};
  try {
    BuildMachinePlant(no_y, ServoDrive(200.0));
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "axes.x.elements[2]");
  }
  EXPECT_NO_THROW(BuildMachinePlant(no_y, DriveConfig{}));

  DriveConfig bad = ServoDrive(200.0);
  bad.servo.position_gain_1_s = 0.0;
  try {
    BuildMachinePlant(ThreeAxes(), bad);
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "position_gain");
  }
}

// Tests that the default machine is the documented default: the modal form's default on Y.
TEST(MultiAxisMachine, DefaultIsSpecDefault) {
  const MultiAxisMachineConfig machine;
  EXPECT_NO_THROW(machine.validate());
  EXPECT_EQ(machine.driven_axis, kY);
  EXPECT_TRUE(machine.single_form);
  EXPECT_FALSE(machine.axes[kX].has_value());
  EXPECT_FALSE(machine.axes[kZ].has_value());
  ASSERT_TRUE(machine.axes[kY].has_value());
  const auto& modal = std::get<ModalMachineConfig>(machine.axes[kY]->form);
  ASSERT_EQ(modal.modes.size(), 1u);
  EXPECT_EQ(modal.modes[0].frequency_hz, 25.0);
}

// Tests the axis names.
TEST(MultiAxisMachine, AxisNames) {
  EXPECT_STREQ(AxisName(0), "x");
  EXPECT_STREQ(AxisName(1), "y");
  EXPECT_STREQ(AxisName(2), "z");
  EXPECT_THROW(AxisName(3), std::out_of_range);
}

}  // namespace
}  // namespace shapebench::model
