// A run of a plant with nonlinear elements (docs/nonlinear.md): which integrator it gets,
// what exact says, the metrics measured from its free response, its YAML keys' errors and
// the cross-check of its linear part.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario.h"
#include "common/math_constants.h"
#include "tests/support/bench_test_support.h"
#include "model/cvode_cross_check.h"
#include "model/integrator.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench {
namespace {

using testing::ExpectError;
using testing::ScratchDir;


// One 10 Hz body on a spring to the driven point, undamped; `friction` from it to the
// ground (model none: a linear plant).
Scenario BodyScenario(const model::FrictionConfig& friction, model::IntegratorMethod method) {
  Scenario s;
  model::LumpedMachineConfig lumped;
  lumped.bodies = {{"mass", 100.0}};
  lumped.elements = {{"spring", "mass", "driven", 100.0 * std::pow(2.0 * kPi * 10.0, 2), 0.0}};
  if (friction.present()) {
    model::LumpedElement guide{"guide", "mass", "ground"};
    guide.friction = friction;
    lumped.elements.push_back(guide);
  }
  lumped.output_body = "mass";
  s.machine.axes[s.machine.driven_axis] = model::MachineConfig{lumped};
  s.controller.period_s = 0.001;
  s.controller.feed_mm_min = 6000;
  s.controller.accel_time_s = 0.05;
  s.controller.pattern.method = "none";
  s.move.distance_mm = 52.5;
  s.integrator.method = method;
  s.integrator.output_substeps = 20;
  return s;
}

// configs/machines/moving_column.yaml with friction on the Y guides (the column on the
// bed) written into `dir`; its path.
std::string MovingColumnWithGuideFriction(ScratchDir* dir, const std::string& friction) {
  std::string text = testing::ReadText(std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/machines/moving_column.yaml");
  const std::string anchor = "      - {name: y_guides, from: column, to: driven";
  const std::size_t at = text.find(anchor);
  EXPECT_NE(at, std::string::npos);
  text.insert(at, "      - {name: y_guides_friction, from: column, to: bed, friction: " + friction + "}\n");
  return dir->Write("moving_column_friction.yaml", text);
}

model::FrictionConfig Coulomb(double coulomb_n) {
  model::FrictionConfig f;
  f.model = model::FrictionModel::kCoulomb;
  f.coulomb_n = coulomb_n;
  return f;
}

// Tests that integrator.method auto runs a plant with a friction element on CVODE (right-hand
// sides, events) and a linear plant on the exact discretisation (none).
TEST(NonlinearRun, AutoPicksCvodeForAFrictionElement) {
  const RunResult friction = RunScenario(BodyScenario(Coulomb(5.0), model::IntegratorMethod::kAuto), {false});
  EXPECT_GT(friction.stats.rhs_evals, 0);
  EXPECT_GT(friction.stats.events, 0);
  EXPECT_FALSE(std::isnan(friction.metrics.dead_band_m));
  const RunResult linear = RunScenario(BodyScenario({}, model::IntegratorMethod::kAuto), {false});
  EXPECT_EQ(linear.stats.rhs_evals, 0);
  EXPECT_TRUE(std::isnan(linear.metrics.dead_band_m));
  EXPECT_TRUE(std::isnan(linear.metrics.quadrant_glitch_m));
}

// Tests that exact refuses a plant with a nonlinear element, naming it, both where the
// integrator is made and at integrator.method in the scenario (FILE:LINE:COL).
TEST(NonlinearRun, ExactRefusesNamingTheElement) {
  const Scenario s = BodyScenario(Coulomb(5.0), model::IntegratorMethod::kExact);
  try {
    RunScenario(s, {false});
    FAIL() << "exact ran a friction element";
  } catch (const ValidationError& error) {
    EXPECT_EQ(error.field(), "method");
    EXPECT_NE(error.message().find("machine.elements[1] (guide)"), std::string::npos) << error.what();
    EXPECT_NE(error.message().find("use cvode or auto"), std::string::npos) << error.what();
  }
  ScratchDir dir;
  const std::string path = dir.Write(
      "s.yaml",
      "machine:\n"
      "  bodies: [{name: table, mass_kg: 50}]\n"
      "  elements:\n"
      "    - {name: screw, from: driven, to: table, stiffness_n_m: 1.0e+8}\n"
      "    - {name: ways, from: table, to: ground, friction: {model: coulomb, coulomb_n: 30}}\n"
      "  output: {body: table}\n"
      "move: {distance_mm: 10}\n"
      "integrator: {method: exact}\n");
  ExpectError(testing::ErrorOf([&] { LoadScenario(path, {}); }), path, 8, 22, "integrator.method",
              "exact cannot integrate a plant with nonlinear elements (machine.elements[1] (ways))");
}

// Tests the friction keys' errors: each at its key, with what is allowed, and did you mean
// for a misspelt key or model.
TEST(NonlinearRun, FrictionKeysAreValidatedWhereTheyStand) {
  ScratchDir dir;
  const std::string head =
      "machine:\n"
      "  bodies: [{name: table, mass_kg: 50}]\n"
      "  elements:\n"
      "    - {name: screw, from: driven, to: table, stiffness_n_m: 1.0e+8}\n";
  const std::string tail = "  output: {body: table}\nmove: {distance_mm: 10}\n";
  auto load = [&](const std::string& name, const std::string& element) {
    const std::string path = dir.Write(name, head + element + tail);
    return std::make_pair(path, testing::ErrorOf([&] { LoadScenario(path, {}); }));
  };
  auto [p1, e1] = load("1.yaml", "    - {name: ways, from: table, to: ground, friction: {model: coulomb, colomb_n: 3}}\n");
  ExpectError(e1, p1, 5, 72, "machine.elements[1].friction.colomb_n", "did you mean 'coulomb_n'?");
  auto [p2, e2] = load("2.yaml", "    - {name: ways, from: table, to: ground, friction: {model: lugr}}\n");
  ExpectError(e2, p2, 5, 63, "machine.elements[1].friction.model",
              "expected one of none|coulomb|stribeck|lugre, got 'lugr'; did you mean 'lugre'?");
  auto [p3, e3] = load("3.yaml", "    - {name: ways, from: table, to: ground, friction: {model: coulomb, coulomb_n: 5, static_n: 4}}\n");
  ExpectError(e3, p3, 5, 96, "machine.elements[1].friction.static_n", "must be >= coulomb_n (5)");
  auto [p4, e4] = load("4.yaml", "    - {name: ways, from: table, to: ground, friction: {model: lugre, coulomb_n: 5}}\n");
  // A key left at its default is reported at the mapping that should hold it.
  ExpectError(e4, p4, 5, 55, "machine.elements[1].friction.stribeck_velocity_m_s",
              "must be finite and > 0 for model lugre");
  auto [p5, e5] = load("5.yaml", "    - {name: ways, from: table, to: ground, stiffness_n_m: 3, friction: {model: coulomb}}\n");
  ExpectError(e5, p5, 5, 60, "machine.elements[1].stiffness_n_m", "must be 0 in a friction element");
  auto [p6, e6] = load("6.yaml", "    - {name: ways, from: table, to: ground, friction: {model: coulomb, sigma0_n_m: 1e6}}\n");
  ExpectError(e6, p6, 5, 84, "machine.elements[1].friction.sigma0_n_m", "is not used by model coulomb (only by lugre)");
}

// Tests that a nonlinear plant's residual, half the peak-to-peak of its free response, is
// the modal amplitude where the two must agree: one undamped mode with a friction element
// of zero force (the plant's dynamics linear, its run through the nonlinear path). Bound:
// the sampled extremes' error 1 - cos(pi / 2000) = 1.2e-6 of the amplitude (2000 samples a
// period), and CVODE's 1e-8 tolerance over the run's 34 periods, far below 1e-4.
TEST(NonlinearResidual, HalfPeakToPeakOfTheFreeResponseIsTheModalAmplitude) {
  const RunResult nonlinear = RunScenario(BodyScenario(Coulomb(0.0), model::IntegratorMethod::kCvode), {false});
  const RunResult linear = RunScenario(BodyScenario({}, model::IntegratorMethod::kExact), {false});
  ASSERT_GT(linear.metrics.residual_amplitude_m, 0.1 * linear.metrics.static_displacement_m);
  EXPECT_NEAR(nonlinear.metrics.residual_amplitude_m, linear.metrics.residual_amplitude_m,
              1e-4 * linear.metrics.residual_amplitude_m);
  EXPECT_NEAR(nonlinear.metrics.residual_ratio, linear.metrics.residual_ratio, 1e-4);
  EXPECT_NEAR(nonlinear.metrics.peak_ratio, linear.metrics.peak_ratio, 1e-4);
  EXPECT_TRUE(std::isnan(nonlinear.metrics.cruise_residual_ratio));
  EXPECT_TRUE(nonlinear.residual_modes.empty());
}

// Tests that the cross-check applies to a nonlinear plant's linear part through the
// integrator that runs it: the moving column's Y axis with friction on its guides at rtol
// 1e-6 is refused (BDF on the linear part is 1.2e-3 off the exact path there,
// docs/accuracy.md), naming the linear part, and at the default rtol it runs.
TEST(NonlinearCrossCheck, TheLinearPartIsCheckedThroughTheNonlinearIntegrator) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "s.yaml", "machine: " + MovingColumnWithGuideFriction(&dir, "{model: coulomb, coulomb_n: 150}") +
                    "\ncontroller: {feed_mm_min: 30000, accel_time_s: 0.3}\nmove: {distance_mm: 200}\n"
                    "integrator: {method: auto}\n");
  try {
    RunScenario(LoadScenario(path, {{"integrator.rtol", "1e-6"}}), {false});
    FAIL() << "rtol 1e-6 passed the cross-check";
  } catch (const model::SolverError& error) {
    EXPECT_EQ(error.flag_name(), "CROSS_CHECK_FAILED");
    EXPECT_NE(std::string(error.what()).find("this plant's linear part"), std::string::npos) << error.what();
  }
  const RunResult run = RunScenario(LoadScenario(path, {}), {false});
  EXPECT_TRUE(run.warnings.empty());
  EXPECT_GT(run.stats.events, 0);
}

// Tests drive.force_limit_n: a rigid servo axis (100 kg on the motor) asked for 50 m/s^2 by
// its command while its motor may push 500 N: the motor's acceleration (second differences
// of the actual position over a period: a mean of the acceleration, and 1e-10 m of
// interpolation error is 1e-4 m/s^2 of it) reaches 5 m/s^2 = F_limit / m and never exceeds
// it by more than 0.1%.
TEST(DriveForceLimit, CapsTheMotorAcceleration) {
  Scenario s;
  s.machine.axes = {};
  s.machine.rigid[s.machine.driven_axis] = true;
  s.drive.type = model::DriveType::kServo;
  s.drive.servo.motor_mass_kg = 100.0;
  s.drive.servo.force_limit_n = 500.0;
  s.controller.period_s = 0.001;
  s.controller.feed_mm_min = 30000;
  s.controller.accel_time_s = 0.01;
  s.move.distance_mm = 100;
  s.integrator.method = model::IntegratorMethod::kAuto;
  s.integrator.output_substeps = 10;
  const RunResult run = RunScenario(s);
  const Trace& t = run.trace;
  const std::size_t step = 10;  // a whole period: CVODE's 1e-8 on the positions stays 1e-3 of it
  const double h = t.time_s[step] - t.time_s[0];
  double largest = 0.0;
  for (std::size_t i = step; i + step < t.time_s.size(); ++i) {
    const double a = (t.actual_m[i + step](1) - 2.0 * t.actual_m[i](1) + t.actual_m[i - step](1)) / (h * h);
    largest = std::max(largest, std::abs(a));
  }
  EXPECT_NEAR(largest, 5.0, 5e-3);
  EXPECT_GT(run.stats.events, 0);  // the limit reached and left
}

// Tests the drive's friction and force limit keys: they need the servo (named so under the
// kinematic drive) with a velocity loop, a misspelt friction key gets a did-you-mean, and a
// negative limit is refused at its key.
TEST(NonlinearRun, DriveFrictionKeysAreValidatedWhereTheyStand) {
  ScratchDir dir;
  auto load = [&](const std::string& name, const std::string& drive) {
    const std::string path = dir.Write(name, "machine: {axes: {}}\ndrive: " + drive + "\nmove: {distance_mm: 10}\n");
    return std::make_pair(path, testing::ErrorOf([&] { LoadScenario(path, {}); }));
  };
  auto [p1, e1] = load("1.yaml", "{type: kinematic, friction: {model: coulomb, coulomb_n: 40}}");
  ExpectError(e1, p1, 2, 36, "drive.friction", "'friction' is a servo setting; it needs type: servo");
  auto [p2, e2] = load("2.yaml", "{type: servo, velocity_loop_hz: 0, friction: {model: coulomb, coulomb_n: 40}}");
  ExpectError(e2, p2, 2, 53, "drive.friction", "needs a velocity loop (velocity_loop_hz > 0)");
  auto [p3, e3] = load("3.yaml", "{type: servo, friction: {model: coulomb, coulomb: 40}}");
  ExpectError(e3, p3, 2, 49, "drive.friction.coulomb", "did you mean 'coulomb_n'?");
  auto [p4, e4] = load("4.yaml", "{type: servo, force_limit_n: -5}");
  ExpectError(e4, p4, 2, 37, "drive.force_limit_n", "must be finite and >= 0");
  auto [p5, e5] = load("5.yaml", "{type: servo, friction: {model: stribeck, coulomb_n: 40, static_n: 30}}");
  ExpectError(e5, p5, 2, 75, "drive.friction.static_n", "must be >= coulomb_n (40)");
}

}  // namespace
}  // namespace shapebench::bench
