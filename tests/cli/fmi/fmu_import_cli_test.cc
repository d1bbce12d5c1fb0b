// shapebench as the FMI master of a plant FMU through the built CLI: run, the exit codes
// of a bad key (2) and of an FMU error status (3), fmu_parameters in --set and in a sweep.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"
#include "tests/support/test_fmu.h"

namespace shapebench::bench::fmu_import_cli_test {
namespace {

using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;
using testing::TestPlantFmu;
using testing::TestPlantScenario;

// Tests that `run --json` of `machine: {fmu: test_plant3.fmu}` exits 0 with the static
// displacement of the plant's compliance m/k under the move's 2 m/s^2, and that the table
// of a mapping without documented outputs shows its static displacement as n/a and warns.
TEST(FmuImportCli, RunsThePlantFmu) {
  ScratchDir dir;
  const std::string path = dir.Write("fmu.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(3) + "}"));
  const CliResult json = RunCli({"run", path, "--json"}, dir.path().string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json metrics = nlohmann::json::parse(json.out);
  EXPECT_NEAR(metrics["static_displacement_m"].get<double>(), 2.0 / 24674.011002723397, 1e-15);
  EXPECT_GT(metrics["peak_ratio"].get<double>(), 1.5);
  const std::string bare = dir.Write(
      "bare.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(2) + ", outputs: {deflection: {y: deflection_y}}}"));
  const CliResult table = RunCli({"run", bare}, dir.path().string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("\nstatic_displacement_m           n/a\n"), std::string::npos) << table.out;
  EXPECT_NE(table.err.find("maps no static_compliance output"), std::string::npos) << table.err;
}

// Tests that machine.fmu is a path key: relative to the file that names it, and, given by
// --set, to the current directory (the scenario in sub/, the CLI run from its parent).
TEST(FmuImportCli, FmuPathsFollowThePathRule) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "sub");
  std::filesystem::copy_file(TestPlantFmu(2), dir.File("sub/plant.fmu"));
  const std::string path = dir.Write("sub/fmu.yaml", TestPlantScenario("{fmu: plant.fmu}"));
  const CliResult from_file = RunCli({"run", path, "--json"}, dir.path().string());
  EXPECT_EQ(from_file.exit_code, 0) << from_file.err;
  const CliResult from_set =
      RunCli({"run", "sub/fmu.yaml", "--json", "--set", "machine.fmu=sub/plant.fmu"}, dir.path().string());
  EXPECT_EQ(from_set.exit_code, 0) << from_set.err;
  const CliResult wrong = RunCli({"run", "sub/fmu.yaml", "--set", "machine.fmu=plant.fmu"}, dir.path().string());
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("--set:1:1: machine.fmu: plant.fmu: cannot be opened"), std::string::npos) << wrong.err;
}

// Tests that a variable the FMU does not have exits 2 with the file, line, column and key
// path, and that a parameter making the FMU return fmi2Error in a step exits 3 naming the
// function, the status in words and the FMU's logged message.
TEST(FmuImportCli, BadKeyExitsTwoAndFmuErrorExitsThree) {
  ScratchDir dir;
  const std::string bad = dir.Write(
      "bad.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(2) + ", outputs: {deflection: {y: deflexion_y}}}"));
  const CliResult r = RunCli({"run", bad}, dir.path().string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("error: " + bad + ":1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("machine.outputs.deflection.y: the FMU " + TestPlantFmu(2) + " has no variable 'deflexion_y'"),
            std::string::npos)
      << r.err;
  const std::string good = dir.Write("fmu.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(2) + "}"));
  const CliResult failed = RunCli({"run", good, "--set", "machine.fmu_parameters.fail_at_s=0.1995"}, dir.path().string());
  EXPECT_EQ(failed.exit_code, 3) << failed.err;
  EXPECT_NE(failed.err.find("fmi2DoStep returned fmi2Error at t = 0.199"), std::string::npos) << failed.err;
  EXPECT_NE(failed.err.find("fail_at_s reached"), std::string::npos) << failed.err;
}

// Tests that a sweep over machine.fmu_parameters.stiffness_n_m runs every point (--jobs 2,
// each its own FMU instance) with the static displacement m/k of its stiffness, and that a
// point whose stiffness the FMU refuses at initialisation is an error row, not fatal.
TEST(FmuImportCli, SweepsOverFmuParameters) {
  ScratchDir dir;
  dir.Write("fmu.yaml", TestPlantScenario("{fmu: " + TestPlantFmu(2) + "}"));
  const std::string sweep =
      dir.Write("sweep.yaml", "base: fmu.yaml\ngrid:\n  machine.fmu_parameters.stiffness_n_m: [1.0e4, 4.0e4, -1]\n");
  const CliResult r = RunCli({"sweep", sweep, "--jobs", "2", "--out", "out"}, dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = testing::ReadCsv(dir.File("out/results.csv"));
  ASSERT_EQ(rows.size(), 4u);
  const auto column = [&rows](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const std::size_t stat = column("static_displacement_m"), status = column("status"), error = column("error");
  ASSERT_LT(error, rows[0].size());
  EXPECT_EQ(rows[1][status], "ok");
  EXPECT_NEAR(std::stod(rows[1][stat]), 2.0 / 1.0e4, 1e-15);
  EXPECT_NEAR(std::stod(rows[2][stat]), 2.0 / 4.0e4, 1e-15);
  EXPECT_EQ(rows[3][status], "error");
  EXPECT_NE(rows[3][error].find("fmi2ExitInitializationMode returned fmi2Error"), std::string::npos) << rows[3][error];
}

}  // namespace
}  // namespace shapebench::bench::fmu_import_cli_test
