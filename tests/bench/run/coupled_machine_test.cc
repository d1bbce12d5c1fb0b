// Coupled modal machines through the bench (model/coupled_modes.h): a Y move deflects X by
// the closed-form static compliance computed here from the YAML's numbers, the exact and
// CVODE paths agree, `modes --json` reports that compliance, the gain shorthand runs bit for
// bit as its coupled spelling, a modal_file loads the machine of the same modes in YAML, and
// the loader's errors for coupling in the wrong place.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "common/math_constants.h"
#include "tests/support/axes.h"
#include "tests/support/bench_test_support.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ErrorOf;
using testing::ExpectError;
using testing::RunCli;
using testing::ScratchDir;


// Two modes, both damped 20 % so that a held acceleration settles within a second
// (e^(-zeta w t) < 1e-13 after 1 s): a 25 Hz sway along Y and a 38 Hz rocking mode that
// X and Y excite and that deflects X, Y and Z.
const char* const kDampedModes =
    "machine:\n"
    "  modes:\n"
    "    - {frequency_hz: 25.0, damping_ratio: 0.2, participation: {y: 49.0}, shape: {y: 2.4166e-3}}\n"
    "    - {frequency_hz: 38.0, damping_ratio: 0.2, participation: {x: 3.0, y: 12.0},\n"
    "       shape: {x: 1.5e-3, y: 0.8e-3, z: 0.6e-3}}\n"
    "  driven_axis: y\n";

// Column a of C: C_ba = sum_i shape_b,i participation_a,i / w_i^2, from kDampedModes.
Eigen::Vector3d ComplianceColumn(int a) {
  const double w1 = 2.0 * kPi * 25.0;
  const double w2 = 2.0 * kPi * 38.0;
  const Eigen::Vector3d p1(0.0, 49.0, 0.0), s1(0.0, 2.4166e-3, 0.0);
  const Eigen::Vector3d p2(3.0, 12.0, 0.0), s2(1.5e-3, 0.8e-3, 0.6e-3);
  return s1 * p1(a) / (w1 * w1) + s2 * p2(a) / (w2 * w2);
}

// Tests that a Y move held at 1 m/s^2 for a second (feed 1 m/s reached in 1 s) deflects the
// tool along X, Y and Z by -C e_y a at the end of the acceleration, C the closed form: to
// 1e-6 of each component (what is left of the start's transient is below 1e-13, the exact
// integrator's error about 1e-12). The run's static_displacement_{x,y,z}_m are C e_y a
// (a taken along +Y, the axis it lies along) to 1e-12; static_displacement_m
// is the Y one.
TEST(CoupledMachine, YMoveDeflectsXByTheStaticCompliance) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "held.yaml", std::string(kDampedModes) +
                       "controller: {period_s: 0.001, feed_mm_min: 60000, accel_time_s: 1.0}\n"
                       "move: {distance_mm: 1500}\n"
                       "integrator: {method: exact}\n");
  const RunResult result = RunScenario(LoadScenario(path, {}), RunOptions{true});
  std::size_t at = 0;
  for (std::size_t i = 0; i < result.trace.time_s.size(); ++i) {
    if (result.trace.time_s[i] <= 1.0 + 1e-12) at = i;
  }
  ASSERT_NEAR(result.trace.time_s[at], 1.0, 1e-12);
  const double accel = result.trace.command_accel_m_s2[at];  // 1 m/s^2 up to rounding
  ASSERT_NEAR(accel, 1.0, 1e-12);
  const Eigen::Vector3d expected = ComplianceColumn(kY) * accel;
  ASSERT_GT(expected(kX), 3e-7);
  const Eigen::Vector3d deflection = result.trace.deflection_axes_m[at];
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(deflection(b), -expected(b), 1e-6 * expected(b)) << "axis " << b;
  }
  const Metrics& m = result.metrics;
  EXPECT_NEAR(m.static_displacement_x_m, expected(kX), 1e-12 * expected(kX));
  EXPECT_NEAR(m.static_displacement_y_m, expected(kY), 1e-12 * expected(kY));
  EXPECT_NEAR(m.static_displacement_z_m, expected(kZ), 1e-12 * expected(kZ));
  EXPECT_EQ(m.static_displacement_m, m.static_displacement_y_m);
}

// Tests that the static deflection vector follows the machine and the move, not the output
// view (issue 32 item 16: Z's entry changed sign with output.direction): a rocking mode
// that deflects Z against Y gives C e_y a, Z negative, for the Y move viewed along Y, along
// Z and as the magnitude, and for the reverse move.
TEST(CoupledMachine, StaticVectorDoesNotDependOnTheOutputView) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "view.yaml",
      "machine:\n"
      "  modes:\n"
      "    - {frequency_hz: 25.0, damping_ratio: 0.2, participation: {y: 49.0}, shape: {y: 2.4166e-3}}\n"
      "    - {frequency_hz: 38.0, damping_ratio: 0.2, participation: {x: 3.0, y: 12.0},\n"
      "       shape: {x: 1.5e-3, y: 0.8e-3, z: -3.0e-3}}\n"
      "  driven_axis: y\n"
      "controller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.1}\n"
      "move: {distance_mm: 50}\n");
  const double w1 = 2.0 * kPi * 25.0;
  const double w2 = 2.0 * kPi * 38.0;
  const Eigen::Vector3d expected = Eigen::Vector3d(0.0, 2.4166e-3, 0.0) * 49.0 / (w1 * w1) +
                                   Eigen::Vector3d(1.5e-3, 0.8e-3, -3.0e-3) * 12.0 / (w2 * w2);  // a = 1 m/s^2
  ASSERT_LT(expected(kZ), 0.0);
  ASSERT_GT(expected(kY), 0.0);
  for (const char* direction : {"y", "z", "magnitude"}) {
    for (const char* distance : {"50", "-50"}) {
      SCOPED_TRACE(std::string(direction) + " " + distance);
      const Metrics m = RunScenario(LoadScenario(path, {{"output.direction", direction}, {"move.distance_mm", distance}}),
                                    RunOptions{false})
                            .metrics;
      EXPECT_NEAR(m.static_displacement_x_m, expected(kX), 1e-12 * expected.norm());
      EXPECT_NEAR(m.static_displacement_y_m, expected(kY), 1e-12 * expected.norm());
      EXPECT_NEAR(m.static_displacement_z_m, expected(kZ), 1e-12 * expected.norm());
    }
  }
}

// Tests that an X move on the coupled machine runs (its modes model every axis: no
// "does not model" error) and deflects Y and X by C e_x a: the rocking mode alone.
TEST(CoupledMachine, XMoveRunsOnTheCoupledModes) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "x.yaml", std::string(kDampedModes) +
                    "controller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.1}\n"
                    "move: {distance_mm: 50, axis: x}\n"
                    "integrator: {method: exact}\n");
  const Metrics m = RunScenario(LoadScenario(path, {}), RunOptions{false}).metrics;
  const Eigen::Vector3d expected = ComplianceColumn(kX) * 1.0;  // 0.1 m/s over 0.1 s
  EXPECT_NEAR(m.static_displacement_x_m, expected(kX), 1e-12 * expected(kX));
  EXPECT_NEAR(m.static_displacement_y_m, expected(kY), 1e-12 * expected(kY));
  EXPECT_NEAR(m.static_displacement_m, expected(kX), 1e-12 * expected(kX));
}

// Tests that CVODE and the exact path agree on a coupled machine within docs/accuracy.md's
// promise: the ratio metrics within 1e-4, and the X peak (the cross-coupled deflection)
// within 1e-4 of the static displacement; unshaped and method 1, magnitude view.
TEST(CoupledMachine, ExactAndCvodeAgree) {
  for (const char* method : {"none", "1"}) {
    SCOPED_TRACE(method);
    const std::vector<Override> base = {{"controller.pattern.method", method}};
    std::vector<Override> cvode = base;
    cvode.push_back({"integrator.method", "cvode"});
    const Metrics exact = RunScenario(LoadScenario(DataPath("sweeps/coupled_two_modes.yaml"), base), RunOptions{false}).metrics;
    const Metrics approx = RunScenario(LoadScenario(DataPath("sweeps/coupled_two_modes.yaml"), cvode), RunOptions{false}).metrics;
    ASSERT_GT(exact.peak_deflection_x_m, 1e-7);
    EXPECT_NEAR(approx.peak_ratio, exact.peak_ratio, 1e-4);
    EXPECT_NEAR(approx.residual_ratio, exact.residual_ratio, 1e-4);
    EXPECT_NEAR(approx.cruise_residual_ratio, exact.cruise_residual_ratio, 1e-4);
    EXPECT_NEAR(approx.peak_deflection_x_m, exact.peak_deflection_x_m, 1e-4 * exact.static_displacement_m);
    EXPECT_EQ(approx.static_displacement_x_m, exact.static_displacement_x_m);
  }
}

// Tests that `modes --json` reports the static compliance matrix (rows: deflection, columns:
// acceleration) of the closed form, to 1e-12 of its largest entry, and each mode's
// participation and shape as the YAML gives them; the text form prints the matrix.
TEST(CoupledMachine, ModesJsonGivesTheClosedFormCompliance) {
  ScratchDir dir;
  const std::string path = dir.Write("m.yaml", kDampedModes);
  const testing::CliResult json = RunCli({"modes", path, "--json"}, dir.path().string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json report = nlohmann::json::parse(json.out);
  const nlohmann::json& matrix = report.at("static_compliance_m_per_m_s2");
  double largest = 0.0;
  for (int a = 0; a < 3; ++a) largest = std::max(largest, ComplianceColumn(a).cwiseAbs().maxCoeff());
  ASSERT_EQ(matrix.size(), 3u);
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(matrix.at(b).at(a).get<double>(), ComplianceColumn(a)(b), 1e-12 * largest) << b << ", " << a;
    }
  }
  const nlohmann::json& rocking = report.at("coupling").at(1);
  EXPECT_EQ(rocking.at("frequency_hz").get<double>(), 38.0);
  EXPECT_EQ(rocking.at("participation").at("x").get<double>(), 3.0);
  EXPECT_EQ(rocking.at("participation").at("y").get<double>(), 12.0);
  EXPECT_EQ(rocking.at("shape").at("z").get<double>(), 0.6e-3);
  const testing::CliResult text = RunCli({"modes", path}, dir.path().string());
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("static compliance, m per m/s^2"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("participation_x"), std::string::npos) << text.out;
}

void ExpectSameRunBits(const RunResult& x, const RunResult& y) {
  const auto a = x.metrics.Named();
  const auto b = y.metrics.Named();
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a[i].second, &b[i].second, sizeof(double)), 0)
        << a[i].first << ": " << a[i].second << " vs " << b[i].second;
  }
  ASSERT_EQ(x.residual_modes.size(), y.residual_modes.size());
  for (std::size_t i = 0; i < x.residual_modes.size(); ++i) {
    EXPECT_EQ(x.residual_modes[i].amplitude, y.residual_modes[i].amplitude);
  }
}

// Tests that `gain: g` and participation p e_y with shape (g / p) e_y (shape x participation
// = gain, p a power of 2) give the same metrics bit for bit, under the exact and the CVODE
// integrator, with a pattern designed from the machine's modes (the analysis too).
TEST(CoupledMachine, GainShorthandGivesTheSameMetricsBitForBit) {
  const std::string rest =
      "controller:\n"
      "  period_s: 0.001\n"
      "  feed_mm_min: 30000\n"
      "  accel_time_s: 0.1\n"
      "  pattern: {method: zvd, mode: both, frequencies_hz: machine, design_damping_ratio: machine}\n"
      "move: {distance_mm: 200}\n";
  ScratchDir dir;
  const std::string gain = dir.Write(
      "gain.yaml", "machine:\n  modes:\n"
                   "    - {frequency_hz: 25.0, damping_ratio: 0.03, gain: 0.5}\n"
                   "    - {frequency_hz: 70.0, damping_ratio: 0.05, gain: -0.2}\n" + rest);
  const std::string coupled = dir.Write(
      "coupled.yaml", "machine:\n  modes:\n"
                      "    - {frequency_hz: 25.0, damping_ratio: 0.03, participation: {y: 2}, shape: {y: 0.25}}\n"
                      "    - {frequency_hz: 70.0, damping_ratio: 0.05, participation: {y: 1}, shape: {y: -0.2}}\n" +
                          rest);
  for (const char* method : {"exact", "cvode"}) {
    SCOPED_TRACE(method);
    const std::vector<Override> set = {{"integrator.method", method}};
    const Scenario a = LoadScenario(gain, set);
    const Scenario b = LoadScenario(coupled, set);
    ASSERT_NE(b.machine.CoupledModes(), nullptr);
    EXPECT_EQ(a.controller.pattern.frequencies_hz, b.controller.pattern.frequencies_hz);
    ExpectSameRunBits(RunScenario(a, RunOptions{false}), RunScenario(b, RunOptions{false}));
  }
}

// Tests that `modal_file:` reads the machine of the same modes written in YAML: every
// number, the plant entry for entry and the metrics bit for bit (the shipped FE export
// and a scenario of its modes inline).
TEST(CoupledMachine, ModalFileLoadsTheSameMachineAsItsYamlModes) {
  const std::string shipped = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/fe_modes.yaml";
  ScratchDir dir;
  const std::string inline_modes = dir.Write(  // a machine file
      "inline.yaml",
      "modes:\n"
      "  - {frequency_hz: 25.0, damping_ratio: 0.03, participation: {x: 0, y: 49.0, z: 0},\n"
      "     shape: {x: 0, y: 2.4166e-3, z: 0}}\n"
      "  - {frequency_hz: 38.0, damping_ratio: 0.04, participation: {x: 3.0, y: 12.0, z: 0},\n"
      "     shape: {x: 1.5e-3, y: 0.8e-3, z: 0.6e-3}}\n"
      "driven_axis: y\n");
  const std::vector<Override> machine = {{"machine", inline_modes}};
  const Scenario from_file = LoadScenario(shipped, {});
  const Scenario from_yaml = LoadScenario(shipped, machine);
  const model::ModalMachineConfig* a = from_file.machine.CoupledModes();
  const model::ModalMachineConfig* b = from_yaml.machine.CoupledModes();
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_NE(a->modal_file.find("moving_column_fe.csv"), std::string::npos);
  ASSERT_EQ(a->modes.size(), b->modes.size());
  for (std::size_t i = 0; i < a->modes.size(); ++i) {
    EXPECT_EQ(a->modes[i].frequency_hz, b->modes[i].frequency_hz);
    EXPECT_EQ(a->modes[i].damping_ratio, b->modes[i].damping_ratio);
    for (double model::AxisVector::*c : {&model::AxisVector::x, &model::AxisVector::y, &model::AxisVector::z}) {
      EXPECT_EQ((*a->modes[i].participation).*c, (*b->modes[i].participation).*c);
      EXPECT_EQ((*a->modes[i].shape).*c, (*b->modes[i].shape).*c);
    }
  }
  const model::MachinePlant x = model::BuildMachinePlant(from_file.machine, from_file.drive);
  const model::MachinePlant y = model::BuildMachinePlant(from_yaml.machine, from_yaml.drive);
  EXPECT_TRUE(x.plant.A == y.plant.A && x.plant.B_accel == y.plant.B_accel && x.plant.C == y.plant.C);
  EXPECT_TRUE(x.static_gain == y.static_gain);
  ExpectSameRunBits(RunScenario(from_file, RunOptions{false}), RunScenario(from_yaml, RunOptions{false}));
}

ConfigError MachineError(const ScratchDir& dir, const std::string& yaml) {
  const std::string path = dir.Write("m.yaml", yaml);
  return ErrorOf([&] { LoadMachineAxes(path, {}); });
}

// Tests the loader's errors for coupling written wrongly, each at its key: gain beside
// participation, shape without participation, coupled modes under `axes:`, a modal_file
// beside modes or under `axes:`, a rigid axis beside coupled modes, a modal file that is
// not there, `axis` and `driven_axis` both.
TEST(CoupledMachine, LoaderErrorsAtTheKey) {
  ScratchDir dir;
  const std::string m = dir.File("m.yaml");
  ExpectError(MachineError(dir, "modes:\n  - {gain: 2, participation: {y: 1}, shape: {y: 2}}\n"), m, 2, 12,
              "machine.modes[0].gain", "one-axis shorthand of participation and shape");
  ExpectError(MachineError(dir, "modes:\n  - {frequency_hz: 9, shape: {y: 2}}\n"), m, 2, 30,
              "machine.modes[0].shape", "needs participation too");
  ExpectError(MachineError(dir, "axes:\n  x: {modes: [{participation: {x: 1}, shape: {x: 1}}]}\n"), m, 2, 31,
              "machine.axes.x.modes[0].participation", "belong to the single `modes:` form");
  ExpectError(MachineError(dir, "modes: [{}]\nmodal_file: f.csv\n"), m, 2, 13, "machine.modal_file",
              "both give the modes");
  ExpectError(MachineError(dir, "axes:\n  y: {modal_file: f.csv}\n"), m, 2, 19, "machine.axes.y.modal_file",
              "belongs to the single form");
  ExpectError(MachineError(dir, "modes: [{participation: {y: 1}, shape: {y: 1}}]\nrigid: [x]\n"), m, 2, 9,
              "machine.rigid[0]", "coupled modes model every axis");
  ExpectError(MachineError(dir, "modal_file: nope.csv\n"), m, 1, 13, "machine.modal_file",
              "modal file 'nope.csv' (" + dir.File("nope.csv") + ")");
  ExpectError(MachineError(dir, "modes: [{participation: {y: 1}, shape: {y: 1}}]\naxis: y\ndriven_axis: y\n"), m,
              3, 14, "machine.driven_axis", "both name the driven axis");
}

}  // namespace
}  // namespace shapebench::bench
