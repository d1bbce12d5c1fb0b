// The servo drive (model/servo_drive.h) against closed forms: the first-order lag of the
// ideal inner loops, the v / Kp following error at constant speed, the static force
// balance of the velocity loop, and the rigid limit of a stiff structure.
#include "common/math_constants.h"
#include "model/servo_drive.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "model/integrator.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"
#include "tests/support/axes.h"

namespace shapebench::model {
namespace {


// The Y chain of configs/machines/moving_column.yaml (25.00 Hz, 4.799 um per m/s^2).
MachineConfig MovingColumnY() {
  LumpedMachineConfig c;
  c.bodies = {{"bed", 6000.0}, {"column", 2400.0}, {"spindle_head", 600.0}, {"tool_tip", 1.0}};
  c.elements = {{"floor_mounts", "bed", "ground", 1.5e9, 2.7e5},
                {"y_guides", "column", "driven", 7.6176e7, 3.2e4},
                {"z_guides", "spindle_head", "column", 3.4e8, 1.8e4},
                {"tip_to_guides", "tool_tip", "driven", 2.1985e7, 175.0},
                {"tip_to_head", "tool_tip", "spindle_head", 3.0145e6, 25.0}};
  c.driven_relative_to = "bed";
  c.output_body = "tool_tip";
  c.output_relative_to = "bed";
  return MachineConfig{c};
}

MachineConfig Modal25Hz() { return MachineConfig{ModalMachineConfig{{{25.0, 0.03, 1.0}}}}; }

DriveConfig Servo(double feedforward, double velocity_loop_hz) {
  DriveConfig drive;
  drive.type = DriveType::kServo;
  drive.servo.position_gain_1_s = 30.0;
  drive.servo.velocity_feedforward = feedforward;
  drive.servo.velocity_loop_hz = velocity_loop_hz;
  return drive;
}

// Closed form of the ideal-inner-loop servo: x' = Kp (u - x) + FF v from rest, so
// x = u - (1 - FF) (u - w) with w the first-order lag of u (u convolved with Kp e^{-Kp t}).
// The command is the two-period velocity triangle of a position step of D:
//   v = (D/dt^2) [r(t) - 2 r(t - dt) + r(t - 2 dt)],  r(s) = s for s > 0,
// so u is the same combination of Q(s) = s^2/2, and u - w of the lag's error on Q,
//   Q(s) - lag(Q)(s) = s/Kp - (1 - e^{-Kp s})/Kp^2  (s > 0).
struct StepOracle {
  double step_m, period_s, kp, feedforward;

  static double Q(double s) { return s > 0.0 ? 0.5 * s * s : 0.0; }
  double LagError(double s) const {
    return s > 0.0 ? s / kp + std::expm1(-kp * s) / (kp * kp) : 0.0;
  }
  double Command(double t) const {
    const double dt = period_s;
    return step_m / (dt * dt) * (Q(t) - 2.0 * Q(t - dt) + Q(t - 2.0 * dt));
  }
  double Motor(double t) const {
    const double dt = period_s;
    const double lag_error =
        step_m / (dt * dt) * (LagError(t) - 2.0 * LagError(t - dt) + LagError(t - 2.0 * dt));
    return Command(t) - (1.0 - feedforward) * lag_error;
  }
};

struct LagCase {
  std::string name;
  double feedforward;
  IntegratorMethod method;
};

void PrintTo(const LagCase& c, std::ostream* os) { *os << c.name; }

class ServoStepResponse : public testing::TestWithParam<LagCase> {};

// Tests the issue's requirement: "The servo's response to a position step matches its
// closed form (first-order lag when the inner loops are ideal) within 1e-6 of the step."
// A servo on a rigid X axis (no structure; Y carries a structure so the machine is valid)
// with ideal inner loops gets a 1 mm step as the tick interface allows it: the commanded
// velocity a triangle over two periods (acceleration +D/dt^2, then -D/dt^2). The motor
// position u + (X's tool-error row) is compared with StepOracle at every output substep for
// 0.3 s (9 time constants), through MakeIntegrator with both methods. Bound 1e-6 D: the
// exact integrator is at rounding level. CVODE's absolute tolerance on the following error
// is rtol times its static scale, the steady lag at the peak speed, v/Kp = 33 D here (the
// 2 ms step never gets near it): at rtol 1e-8 that leaves ~1e-5 D, so this test asks for
// rtol 1e-10 (~1e-7 D).
TEST_P(ServoStepResponse, MatchesFirstOrderLag) {
  const LagCase& c = GetParam();
  const double step_m = 1e-3, dt = 1e-3;
  const int substeps = 10;
  MultiAxisMachineConfig machine;
  machine.axes[kY] = Modal25Hz();
  const DriveConfig drive = Servo(c.feedforward, 0.0);
  const MachinePlant built = BuildMachinePlant(machine, drive);
  const StepOracle oracle{step_m, dt, drive.servo.position_gain_1_s, c.feedforward};

  IntegratorConfig config;
  config.method = c.method;
  config.rtol = 1e-10;
  const double peak_accel = step_m / (dt * dt);
  const double peak_speed = step_m / dt;
  auto integrator = MakeIntegrator(built.plant, config, dt, substeps, peak_accel, peak_speed);
  Eigen::VectorXd input = Eigen::VectorXd::Zero(kNumAxes);
  integrator->Reset(input);
  double max_error_m = 0.0;
  double max_lag_m = 0.0;
  for (int tick = 0; tick < 300; ++tick) {
    input(kX) = tick == 0 ? peak_accel : tick == 1 ? -peak_accel : 0.0;
    integrator->SetInput(input);
    for (int j = 0; j < substeps; ++j) {
      integrator->Step();
      const double t = integrator->Time();
      const Eigen::VectorXd out = integrator->Output();
      const double motor = oracle.Command(t) + out(kToolErrorRow + kX);
      max_error_m = std::max(max_error_m, std::abs(motor - oracle.Motor(t)));
      max_lag_m = std::max(max_lag_m, std::abs(oracle.Command(t) - oracle.Motor(t)));
      ASSERT_EQ(out(kDeflectionRow + kX), 0.0);  // a rigid axis does not deflect
      ASSERT_EQ(out(kDeflectionRow + kY), 0.0);  // and Y is not commanded
    }
  }
  EXPECT_LE(max_error_m, 1e-6 * step_m) << "error/step " << max_error_m / step_m;
  // The oracle's lag is really there (FF = 1 follows exactly: no lag at all).
  if (c.feedforward < 1.0) {
    EXPECT_GT(max_lag_m, 0.1 * step_m);
  }
  if (c.feedforward == 1.0) {
    EXPECT_EQ(max_lag_m, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Feedforward, ServoStepResponse,
    testing::Values(LagCase{"Ff0Exact", 0.0, IntegratorMethod::kExact},
                    LagCase{"Ff0Cvode", 0.0, IntegratorMethod::kCvode},
                    LagCase{"Ff05Exact", 0.5, IntegratorMethod::kExact},
                    LagCase{"Ff05Cvode", 0.5, IntegratorMethod::kCvode},
                    LagCase{"Ff1Exact", 1.0, IntegratorMethod::kExact},
                    LagCase{"Ff1Cvode", 1.0, IntegratorMethod::kCvode}),
    [](const testing::TestParamInfo<LagCase>& info) { return info.param.name; });

// A trapezoidal Y move: `accel_ticks` at +a, `cruise_ticks` at 0, `accel_ticks` at -a,
// then `tail_ticks` at rest. Records the outputs at the end of each tick.
struct MoveRecord {
  std::vector<Eigen::VectorXd> outputs;  // after tick k (k = 0 .. total - 1)
};

MoveRecord RunMove(PlantIntegrator& integrator, double accel, int accel_ticks, int cruise_ticks,
                   int tail_ticks, int substeps) {
  MoveRecord record;
  Eigen::VectorXd input = Eigen::VectorXd::Zero(kNumAxes);
  integrator.Reset(input);
  const int total = 2 * accel_ticks + cruise_ticks + tail_ticks;
  for (int k = 0; k < total; ++k) {
    input(kY) = k < accel_ticks                                ? accel
                : k < accel_ticks + cruise_ticks               ? 0.0
                : k < 2 * accel_ticks + cruise_ticks           ? -accel
                                                               : 0.0;
    integrator.SetInput(input);
    for (int j = 0; j < substeps; ++j) integrator.Step();
    record.outputs.push_back(integrator.Output());
  }
  return record;
}

// Tests the servo with a 200 Hz velocity loop on the moving column's Y chain, 30 m/min at
// 1.667 m/s^2 (the patent's 0.17 G): with FF = 0 the following error at constant speed is
// v / Kp (the position loop's type-1 lag; the PI velocity loop leaves no velocity error),
// checked within 1% after 0.5 s of cruise (15 time constants, the loops have settled);
// with FF = 1 it is below 1% of that. After the move the following error settles to
// zero and so does the deflection: 2 s after the move the following error is below 1e-6
// of v / Kp (what remains is the 25 Hz mode's residual, 3% damped, reaching the motor
// through the screw; the loops themselves decay at 30 1/s and faster) and the deflection
// below 1e-3 of static. The axis is stable for every FF.
TEST(ServoDrive, FiniteVelocityLoopOnMovingColumn) {
  const double accel = 1.667, speed = 0.5, dt = 1e-3;
  const int accel_ticks = 300, cruise_ticks = 500, tail_ticks = 2000, substeps = 1;
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MovingColumnY();
  for (const double ff : {0.0, 0.5, 1.0}) {
    SCOPED_TRACE("FF = " + std::to_string(ff));
    const DriveConfig drive = Servo(ff, 200.0);
    const MachinePlant built = BuildMachinePlant(machine, drive);
    const Eigen::VectorXcd poles = built.plant.A.eigenvalues();
    for (int i = 0; i < poles.size(); ++i) EXPECT_LT(poles(i).real(), 0.0) << poles(i);

    IntegratorConfig config;
    config.method = IntegratorMethod::kExact;
    auto exact = MakeIntegrator(built.plant, config, dt, substeps, accel, speed);
    const MoveRecord move = RunMove(*exact, accel, accel_ticks, cruise_ticks, tail_ticks, 1);
    const double lag_m = speed / drive.servo.position_gain_1_s;
    const double static_m = accel * std::abs(built.static_gain(kY, kY));
    // Following error = tool error less deflection (c^T g = 1: the tool rides the nut).
    auto following = [&](int k) {
      return move.outputs[k](kToolErrorRow + kY) - move.outputs[k](kDeflectionRow + kY);
    };
    const int cruise_end = accel_ticks + cruise_ticks - 1;
    if (ff == 0.0) {
      EXPECT_NEAR(following(cruise_end), -lag_m, 0.01 * lag_m);
    }
    if (ff == 1.0) {
      EXPECT_LT(std::abs(following(cruise_end)), 0.01 * lag_m);
    }
    const Eigen::VectorXd& last = move.outputs.back();
    EXPECT_LT(std::abs(following(static_cast<int>(move.outputs.size()) - 1)), 1e-6 * lag_m);
    EXPECT_LT(std::abs(last(kDeflectionRow + kY)), 1e-3 * static_m);
    EXPECT_LT(std::abs(last(kToolErrorRow + kY)), 1e-3 * static_m);
  }
}

// Tests that CVODE's tolerances are sane on every servo state: on the moving column with a
// 200 Hz velocity loop (its motor pole near -1e5 1/s beside the mm-sized following error and
// the um-sized deflection), CVODE at rtol 1e-8 tracks the exact integrator to 2e-5 of the
// static deflection (what the kinematic drive achieves over as many steps: ~5e-6) and
// the tool error to 1e-7 of v / Kp, for FF = 0 (following error from the speed scale) and
// FF = 1 (following error statically 0: the group's other states set its scale).
TEST(ServoDrive, CvodeTracksExactOnEveryState) {
  const double accel = 1.667, dt = 1e-3;
  const int accel_ticks = 100, cruise_ticks = 100, tail_ticks = 200, substeps = 4;
  const double speed = accel * accel_ticks * dt;
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MovingColumnY();
  for (const double ff : {0.0, 1.0}) {
    SCOPED_TRACE("FF = " + std::to_string(ff));
    const DriveConfig drive = Servo(ff, 200.0);
    const MachinePlant built = BuildMachinePlant(machine, drive);
    IntegratorConfig config;
    auto cvode = MakeIntegrator(built.plant, config, dt, substeps, accel, speed);
    config.method = IntegratorMethod::kExact;
    auto exact = MakeIntegrator(built.plant, config, dt, substeps, accel, speed);
    const MoveRecord a = RunMove(*cvode, accel, accel_ticks, cruise_ticks, tail_ticks, substeps);
    const MoveRecord b = RunMove(*exact, accel, accel_ticks, cruise_ticks, tail_ticks, substeps);
    const double static_m = accel * std::abs(built.static_gain(kY, kY));
    const double lag_m = speed / drive.servo.position_gain_1_s;
    double deflection_error = 0.0, tool_error = 0.0;
    for (std::size_t k = 0; k < a.outputs.size(); ++k) {
      deflection_error = std::max(deflection_error, std::abs(a.outputs[k](kDeflectionRow + kY) -
                                                             b.outputs[k](kDeflectionRow + kY)));
      tool_error = std::max(tool_error, std::abs(a.outputs[k](kToolErrorRow + kY) -
                                                 b.outputs[k](kToolErrorRow + kY)));
    }
    EXPECT_LE(deflection_error, 2e-5 * static_m) << deflection_error / static_m;
    EXPECT_LE(tool_error, 1e-7 * lag_m) << tool_error / lag_m;
  }
}

// Tests the velocity loop's static force balance, which checks the motor's reaction: under
// a held acceleration a the PI integral alone pushes the whole moving mass, Ki z =
// (m_m + m_load) a, so z = 4 a / w_v^2 whatever the masses (Ki = (m_m + m_load) w_v^2 / 4);
// the following error and its rate are 0 and the deflection is the kinematic drive's.
TEST(ServoDrive, StaticForceBalance) {
  for (const MachineConfig& structure : {MovingColumnY(), Modal25Hz()}) {
    const ServoConfig servo = Servo(0.0, 200.0).servo;
    const LinearPlant plant = BuildServoAxisPlant(&structure, servo);
    const int n = plant.num_states();
    const Eigen::VectorXd x = plant.A.fullPivLu().solve(-plant.B_accel * 1.0);
    const double w_v = kTwoPi * servo.velocity_loop_hz;
    EXPECT_NEAR(x(n - 1), 4.0 / (w_v * w_v), 1e-9 * 4.0 / (w_v * w_v));  // z
    EXPECT_NEAR(x(n - 3), 0.0, 1e-15);                                     // e
    EXPECT_NEAR(x(n - 2), 0.0, 1e-12);                                     // e'
    const double kinematic = BuildPlant(structure).StaticGain()(0, 0);
    EXPECT_NEAR(plant.StaticGain()(0, 0), kinematic, 1e-9 * std::abs(kinematic));
    EXPECT_NEAR(plant.StaticGain()(1, 0), kinematic, 1e-9 * std::abs(kinematic));
  }
}

// Tests the motor's coupling to a lumped structure in its rigid limit: a 500 kg table on a
// 5 kHz screw (far above the 100 Hz velocity loop) follows like a rigid axis whose motor
// carries the table's mass: the following error matches that rigid axis' within 1e-5 of
// its peak (the screw's compliance shows at order (w_v / w_screw)^2 = 4e-4 of the motor's
// dynamics and less in the error, ~1e-6; a wrong reaction sign or load mass is off by
// far more, or unstable).
TEST(ServoDrive, StiffStructureActsAsRigidMass) {
  const double m_table = 500.0, k = m_table * std::pow(kTwoPi * 5000.0, 2);
  LumpedMachineConfig table;
  table.bodies = {{"table", m_table}};
  table.elements = {{"screw", "driven", "table", k, 0.0}};
  table.output_body = "table";
  const MachineConfig structure{table};
  ServoConfig servo = Servo(0.3, 100.0).servo;
  const LinearPlant with_table = BuildServoAxisPlant(&structure, servo);
  servo.motor_mass_kg += m_table;
  const LinearPlant rigid = BuildServoAxisPlant(nullptr, servo);

  IntegratorConfig config;
  config.method = IntegratorMethod::kExact;
  const double dt = 1e-3, accel = 2.0;
  auto a = MakeIntegrator(with_table, config, dt, 4, accel, 0.1);
  auto b = MakeIntegrator(rigid, config, dt, 4, accel, 0.1);
  a->Reset(Eigen::VectorXd::Zero(1));
  b->Reset(Eigen::VectorXd::Zero(1));
  double peak = 0.0, difference = 0.0;
  for (int tick = 0; tick < 400; ++tick) {
    const double held = tick < 50 ? accel : tick < 100 ? -accel : 0.0;
    a->SetInput(Eigen::VectorXd::Constant(1, held));
    b->SetInput(Eigen::VectorXd::Constant(1, held));
    for (int j = 0; j < 4; ++j) {
      a->Step();
      b->Step();
      peak = std::max(peak, std::abs(b->Output()(1)));
      difference = std::max(difference, std::abs(a->Output()(1) - b->Output()(1)));
    }
  }
  EXPECT_GT(peak, 1e-4);
  EXPECT_LE(difference, 1e-5 * peak) << difference / peak;
}

// Tests that with FF = 1 and ideal inner loops the motor follows the command exactly
// (e' = -Kp e from e = 0), so the structure's deflection is the kinematic drive's.
TEST(ServoDrive, IdealFullFeedforwardIsKinematic) {
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MovingColumnY();
  const MachinePlant servo = BuildMachinePlant(machine, Servo(1.0, 0.0));
  const MachinePlant kinematic = BuildMachinePlant(machine, DriveConfig{});
  IntegratorConfig config;
  config.method = IntegratorMethod::kExact;
  auto a = MakeIntegrator(servo.plant, config, 1e-3, 4, 1.667, 0.5);
  auto b = MakeIntegrator(kinematic.plant, config, 1e-3, 4, 1.667, 0.5);
  const MoveRecord ra = RunMove(*a, 1.667, 30, 20, 100, 4);
  const MoveRecord rb = RunMove(*b, 1.667, 30, 20, 100, 4);
  const double static_m = 1.667 * std::abs(kinematic.static_gain(kY, kY));
  for (std::size_t k = 0; k < ra.outputs.size(); ++k) {
    ASSERT_NEAR(ra.outputs[k](kDeflectionRow + kY), rb.outputs[k](kDeflectionRow + kY),
                1e-9 * static_m);
    ASSERT_NEAR(ra.outputs[k](kToolErrorRow + kY), rb.outputs[k](kToolErrorRow + kY),
                1e-9 * static_m);
  }
}

// Tests that a drive that never breaks free stays at its start: a force limit of 100 N
// against 1000 N of Coulomb friction holds the motor still through a 200 mm move (the
// repro of issue 32 item 16), so the motor, the command u plus the following error (the
// tool-error row less the deflection row), stays at 0, and the structure, which sees no
// motion, stays at rest. Before CVODE integrated the motor's position and velocity in place
// of e = -u and e' = -v, its rtol 1e-8 on them put the motor 2 nm off (rtol x 200 mm).
// 10 pm is rounding's room (the holding force, refined, cancels the velocity loop's
// integral wound up to ~1e8 m/s^2 on the motor); the structure's 1e-10 m (1e-5 of its
// static 8 um) is CVODE's room on it.
TEST(ServoDrive, StuckDriveStaysAtTheStart) {
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MovingColumnY();
  DriveConfig drive = Servo(0.0, 200.0);
  drive.servo.force_limit_n = 100.0;
  drive.servo.friction.model = FrictionModel::kCoulomb;
  drive.servo.friction.coulomb_n = 1000.0;
  const MachinePlant built = BuildMachinePlant(machine, drive);
  ASSERT_FALSE(built.nonlinear.empty());
  const double dt = 1e-3, accel = 0.5 / 0.3;  // 30 m/min reached in 300 ms
  const int substeps = 4;
  auto integrator = MakePlantIntegrator({built.plant, built.nonlinear, built.following_error_axis},
                                        IntegratorConfig{}, dt, substeps, accel, 0.5);
  integrator->Reset(Eigen::VectorXd::Zero(kNumAxes));
  std::vector<double> outputs(static_cast<std::size_t>(substeps) * kNumOutputRows);
  double u = 0.0, v = 0.0, max_motor_m = 0.0, max_deflection_m = 0.0;
  const double h = dt / substeps;
  for (int tick = 0; tick < 800; ++tick) {  // 300 ms up, 100 ms at speed, 300 ms down, rest
    Eigen::VectorXd input = Eigen::VectorXd::Zero(kNumAxes);
    input(kY) = tick < 300 ? accel : tick < 400 ? 0.0 : tick < 700 ? -accel : 0.0;
    integrator->AdvancePeriod(input.data(), 1, outputs.data());
    for (int j = 0; j < substeps; ++j) {
      u += h * (v + 0.5 * h * input(kY));
      v += h * input(kY);
      const double* out = &outputs[static_cast<std::size_t>(j) * kNumOutputRows];
      max_motor_m = std::max(max_motor_m, std::abs(u + out[kToolErrorRow + kY] - out[kDeflectionRow + kY]));
      max_deflection_m = std::max(max_deflection_m, std::abs(out[kDeflectionRow + kY]));
    }
  }
  EXPECT_NEAR(u, 0.2, 1e-9);  // the command did move 200 mm
  EXPECT_LE(max_motor_m, 1e-11);
  EXPECT_LE(max_deflection_m, 1e-10);
  const Eigen::VectorXd last = integrator->Output();  // PlantState's e as well
  EXPECT_LE(std::abs(u + last(kToolErrorRow + kY) - last(kDeflectionRow + kY)), 1e-11);
}

// Tests that a velocity loop refuses a structure the rigid motion stretches (a damper from
// the moving column to the floor), naming the element; the ideal inner loops accept it.
TEST(ServoDrive, VelocityLoopNeedsFreeFollowing) {
  LumpedMachineConfig config = std::get<LumpedMachineConfig>(MovingColumnY().form);
  config.elements.push_back({"cover", "column", "ground", 0.0, 2e3});
  const MachineConfig structure{config};
  try {
    BuildServoAxisPlant(&structure, Servo(0.0, 200.0).servo);
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "elements[5]");
    EXPECT_NE(e.message().find("\"cover\""), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("follows the driven point freely"), std::string::npos)
        << e.message();
  }
  EXPECT_NO_THROW(BuildServoAxisPlant(&structure, Servo(0.0, 0.0).servo));
}

struct ServoFieldCase {
  std::string name;
  void (*mutate)(ServoConfig&);
  std::string field;
};

void PrintTo(const ServoFieldCase& c, std::ostream* os) { *os << c.name; }

class ServoValidation : public testing::TestWithParam<ServoFieldCase> {};

// Tests that each invalid servo setting is refused naming its YAML key, and that the
// kinematic drive ignores the servo settings.
TEST_P(ServoValidation, NamesTheField) {
  DriveConfig drive = Servo(0.0, 200.0);
  EXPECT_NO_THROW(drive.validate());
  GetParam().mutate(drive.servo);
  try {
    drive.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), GetParam().field);
    EXPECT_NE(e.message().find("(got "), std::string::npos) << e.message();
  }
  drive.type = DriveType::kKinematic;
  EXPECT_NO_THROW(drive.validate());
}

INSTANTIATE_TEST_SUITE_P(
    Grid, ServoValidation,
    testing::Values(
        ServoFieldCase{"NegativeGain", [](ServoConfig& s) { s.position_gain_1_s = -1.0; },
                       "position_gain"},
        ServoFieldCase{"FeedforwardAboveOne",
                       [](ServoConfig& s) { s.velocity_feedforward = 1.5; },
                       "velocity_feedforward"},
        ServoFieldCase{"NegativeLoop", [](ServoConfig& s) { s.velocity_loop_hz = -5.0; },
                       "velocity_loop_hz"},
        ServoFieldCase{"ZeroMotorMass", [](ServoConfig& s) { s.motor_mass_kg = 0.0; },
                       "motor_mass_kg"}),
    [](const testing::TestParamInfo<ServoFieldCase>& info) { return info.param.name; });

}  // namespace
}  // namespace shapebench::model
