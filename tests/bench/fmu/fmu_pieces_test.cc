// The pieces of an exported FMU without the library: the exact stepper (any step size, the
// peaks inside a step), the variable layout, the resource location URI.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "bench/fmu/exact_stepper.h"
#include "bench/fmu/fmu_instance.h"
#include "bench/fmu/fmu_layout.h"
#include "bench/scenario/scenario_loader.h"
#include "model/multi_axis_machine.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench::fmu_pieces_test {
namespace {

model::LinearPlant MethodOnePlant() {
  const Scenario scenario = LoadScenario(kSourceDir + "/configs/scenarios/method1.yaml", {});
  return model::BuildMachinePlant(scenario.machine, scenario.drive).plant;
}

// Tests that one step of 10 ms gives the state of ten steps of 1 ms to 1e-12 of its size
// (the exact discretisation takes any step), under a held 2 m/s2 on Y.
TEST(FmuExactStepper, AnyStepSizeGivesTheSameState) {
  const model::LinearPlant plant = MethodOnePlant();
  fmu::ExactStepper one(plant, 0.001, 10), ten(plant, 0.001, 10);
  const double accel[3] = {0.0, 2.0, 0.0};
  one.Step(accel, 0.01);
  for (int k = 0; k < 10; ++k) ten.Step(accel, 0.001);
  const int row = model::kDeflectionRow + 1;
  ASSERT_NE(one.Output(row), 0.0);
  EXPECT_NEAR(one.Output(row), ten.Output(row), 1e-12 * std::abs(ten.Output(row)));
  EXPECT_LE((one.State() - ten.State()).norm(), 1e-12 * ten.State().norm());
}

// Tests that the peak of one long step (50 ms: the undamped 25 Hz mode peaks at 20 ms, twice
// its end's deflection at 50 ms) is the largest |deflection| of the same step cut into 5000
// pieces, to 1e-9, and larger than either end.
TEST(FmuExactStepper, PeakInsideAStepSurvives) {
  const model::LinearPlant plant = MethodOnePlant();
  fmu::ExactStepper coarse(plant, 0.001, 10), fine(plant, 0.001, 10);
  const double accel[3] = {0.0, 2.0, 0.0};
  const int row = model::kDeflectionRow + 1;
  coarse.Step(accel, 0.05);
  double finest = 0.0;
  for (int k = 0; k < 5000; ++k) {
    fine.Step(accel, 1e-5);
    finest = std::max(finest, std::abs(fine.Output(row)));
  }
  EXPECT_NEAR(coarse.Peak(row), finest, 1e-9 * finest);
  EXPECT_GT(coarse.Peak(row), std::abs(coarse.Output(row)) * 1.01);
}

// Tests that the machine's layout has time at value reference 0, unique value references
// and names, the Y input and outputs, and one frequency and one damping parameter per mode
// named as --set names them; the controller's has position, velocity and acceleration per axis.
TEST(FmuLayout, VariablesOfBothParts) {
  const Scenario scenario = LoadScenario(kSourceDir + "/configs/scenarios/method1.yaml", {});
  const fmu::Layout machine = fmu::MakeLayout(scenario, fmu::Part::kMachine);
  EXPECT_EQ(machine.variables.front().name, "time");
  std::set<std::string> names;
  for (std::size_t i = 0; i < machine.variables.size(); ++i) {
    EXPECT_EQ(machine.variables[i].value_reference, i);
    EXPECT_TRUE(names.insert(machine.variables[i].name).second) << machine.variables[i].name;
  }
  EXPECT_NE(machine.input[1], fmu::kNoVariable);
  EXPECT_EQ(machine.input[0], fmu::kNoVariable);
  EXPECT_EQ(machine.variables[static_cast<std::size_t>(machine.deflection_peak[1])].name, "deflection_peak_y");
  ASSERT_EQ(machine.parameters.size(), 2u);  // one mode
  EXPECT_EQ(machine.parameters[0].key_path, "machine.modes[0].frequency_hz");
  EXPECT_EQ(machine.parameters[1].key_path, "machine.modes[0].damping_ratio");
  EXPECT_EQ(machine.step_s, scenario.controller.period_s);
  const fmu::Layout controller = fmu::MakeLayout(scenario, fmu::Part::kController);
  EXPECT_EQ(controller.variables.size(), 10u);
  EXPECT_EQ(controller.variables[static_cast<std::size_t>(controller.accel[2])].name, "accel_z");
}

// Tests that an FMI 2.0 resource location is read as the standard's URI forms give it
// (file:///, file:/, file://localhost/, percent-encoded) and a plain path as it is.
TEST(FmuInstance, ResourceLocationUris) {
  EXPECT_EQ(fmu::ResourceDirFromUri("file:///tmp/a%20b/resources/"), "/tmp/a b/resources");
  EXPECT_EQ(fmu::ResourceDirFromUri("file:/tmp/r"), "/tmp/r");
  EXPECT_EQ(fmu::ResourceDirFromUri("file://localhost/tmp/r"), "/tmp/r");
  EXPECT_EQ(fmu::ResourceDirFromUri("/tmp/r/"), "/tmp/r");
}

}  // namespace
}  // namespace shapebench::bench::fmu_pieces_test
