// The test plant FMUs (tests/fmu/test_plant_fmu.cc, zipped by tests/CMakeLists.txt into
// <build>/tests/fmu/) and scenarios that drive them: one mass on a spring and a dashpot,
// 25 Hz and 3% damping by default, the modal form's single mode {25 Hz, 0.03, gain 1}.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>

#include "common/math_constants.h"
#include "tests/support/cli_binary.h"

namespace shapebench::bench::testing {

// test_plant2.fmu (FMI 2.0) or test_plant3.fmu (FMI 3.0), next to the build's CLI.
inline std::string TestPlantFmu(int version) {
  return (std::filesystem::path(SHAPEBENCH_DEFAULT_BINARY).parent_path() / "tests" / "fmu" /
          ("test_plant" + std::to_string(version) + ".fmu"))
      .string();
}

constexpr double kTestPlantHz = 25.0;
constexpr double kTestPlantZeta = 0.03;

// A 100 mm unshaped move along y at 6 m/min, 50 ms acc/dec, one output sample a period;
// `machine` the YAML of the machine mapping.
inline std::string TestPlantScenario(const std::string& machine) {
  return "machine: " + machine +
         "\n"
         "controller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.05, pattern: {method: none}}\n"
         "move: {distance_mm: 100}\n"
         "integrator: {method: exact, output_substeps: 1}\n";
}

}  // namespace shapebench::bench::testing
