// The scenario keys of the pipeline: program / program_file / move (one of them), move.axis,
// output.direction; and what they do in a run.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ScratchDir;

const std::string kMachine = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/machines/moving_column.yaml";

ConfigError ProgramLoadError(const std::string& path) {
  return testing::ErrorOf([&] { LoadScenario(path, {}); });
}

// Tests that move, program and program_file exclude each other, the second one named.
TEST(ScenarioProgramTest, OnlyOneOfMoveProgramAndProgramFile) {
  ScratchDir dir;
  const std::string path =
      dir.Write("s.yaml", "move: {distance_mm: 10}\nprogram:\n  - {g: 1, x: 10, f: 600}\n");
  const ConfigError error = ProgramLoadError(path);
  EXPECT_EQ(error.line(), 3) << error.what();  // at the list, the value of program:
  EXPECT_EQ(error.key_path(), "program") << error.what();
  EXPECT_NE(error.message().find("only one of move, program and program_file"), std::string::npos);
}

// Tests that program_file is read relative to the scenario and runs to its end point:
// square.nc ends at G91 X-30 from (30, 20), i.e. at (0, 20), after a 200 ms dwell.
TEST(ScenarioProgramTest, ProgramFileRunsToItsEnd) {
  const Scenario s = LoadScenario(testing::DataPath("programs/program_file.yaml"), {});
  ASSERT_TRUE(s.program.has_value());
  const RunResult r = RunScenario(s);
  const Eigen::Vector3d end = r.command.Positions().back();
  EXPECT_NEAR((end - Eigen::Vector3d(0, 0.020, 0)).norm(), 0.0, 1e-12);
  // The dwell: 200 consecutive periods at rest inside the command.
  std::size_t longest = 0, run = 0;
  for (std::size_t k = 1; k < r.command.num_ticks(); ++k) {
    run = r.command.velocity_m_s(k).norm() == 0.0 ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  EXPECT_GE(longest, 200u);
}

// Tests move.axis and output.direction on the three-axis moving column: a move along X
// deflects only X; the y component view of an XY program sees only Y's deflection while
// the magnitude view sees at least the larger of both.
TEST(ScenarioProgramTest, MoveAxisAndOutputDirection) {
  ScratchDir dir;
  const std::string move_x = dir.Write(
      "x.yaml", "machine: " + kMachine + "\ncontroller: {feed_mm_min: 30000, accel_time_s: 0.3}\n"
                "move: {distance_mm: 100, axis: x}\n");
  const Metrics mx = RunScenario(LoadScenario(move_x, {})).metrics;
  EXPECT_GT(mx.peak_deflection_x_m, 1e-6);
  EXPECT_EQ(mx.peak_deflection_y_m, 0.0);
  EXPECT_EQ(mx.peak_deflection_m, mx.peak_deflection_x_m);

  const std::string corner = dir.Write(
      "c.yaml", "machine: " + kMachine + "\ncontroller: {feed_mm_min: 30000, accel_time_s: 0.3}\n"
                "program:\n  - {g: 1, y: 100, f: 30000}\n  - {x: 100}\n");
  const Metrics magnitude = RunScenario(LoadScenario(corner, {})).metrics;
  const Metrics y_only = RunScenario(LoadScenario(corner, {Override{"output.direction", "y"}})).metrics;
  const Metrics x_only = RunScenario(LoadScenario(corner, {Override{"output.direction", "x"}})).metrics;
  EXPECT_EQ(y_only.peak_deflection_m, y_only.peak_deflection_y_m);
  EXPECT_EQ(x_only.peak_deflection_m, x_only.peak_deflection_x_m);
  EXPECT_GE(magnitude.peak_deflection_m, std::max(magnitude.peak_deflection_x_m, magnitude.peak_deflection_y_m));
  EXPECT_GT(magnitude.peak_deflection_m, x_only.peak_deflection_m);
}

// Tests that a bad output.direction lists what is allowed, at its position.
TEST(ScenarioProgramTest, BadOutputDirection) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "move: {distance_mm: 10}\noutput: {direction: w}\n");
  const ConfigError error = ProgramLoadError(path);
  EXPECT_EQ(error.line(), 2);
  EXPECT_EQ(error.column(), 21);
  EXPECT_EQ(error.key_path(), "output.direction");
  EXPECT_NE(error.message().find("auto|magnitude|x|y|z"), std::string::npos) << error.what();
}

// Tests that the shipped tool-change pocket runs with one warning listing the words the
// bench ignores, and that program_strict: true refuses its first one (O1000, line 2) at
// its line and column in the G-code file.
TEST(ScenarioProgramTest, ProgramStrictRefusesWhatARunIgnores) {
  const std::string scenario =
      std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/pocket_toolchange.yaml";
  const RunResult r = RunScenario(LoadScenario(scenario, {}));
  ASSERT_EQ(r.command.warnings.size(), 1u);
  EXPECT_EQ(r.command.warnings[0].rfind("ignored words not modelled by the bench: O1000 (line 2), "
                                        "T1 (line 7), M6 (line 7), G54 (line 8)",
                                        0),
            0u)
      << r.command.warnings[0];
  EXPECT_FALSE(r.command.stroke_alarm);

  ScratchDir dir;
  const std::string program = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/programs/pocket_toolchange.nc";
  const std::string path = dir.Write("s.yaml", "program_file: " + program + "\nprogram_strict: true\n");
  const ConfigError error = ProgramLoadError(path);
  EXPECT_EQ(error.line(), 2) << error.what();
  EXPECT_EQ(error.column(), 1) << error.what();
  EXPECT_NE(error.message().find("'O1000' is not modelled by the bench, and program_strict refuses"),
            std::string::npos)
      << error.what();
  // program_strict: false is the default behaviour.
  const std::string lenient = dir.Write("l.yaml", "program_file: " + program + "\nprogram_strict: false\n");
  EXPECT_EQ(LoadScenario(lenient, {}).program->warnings.size(), 1u);
}

// Tests that program_strict needs program_file and takes true or false.
TEST(ScenarioProgramTest, ProgramStrictKeyErrors) {
  ScratchDir dir;
  const ConfigError without = ProgramLoadError(
      dir.Write("a.yaml", "program:\n  - {g: 1, x: 10, f: 600}\nprogram_strict: true\n"));
  EXPECT_EQ(without.key_path(), "program_strict") << without.what();
  EXPECT_NE(without.message().find("give program_file"), std::string::npos) << without.what();
  dir.Write("p.nc", "G1 X1 F600\n");
  const ConfigError not_bool = ProgramLoadError(dir.Write("b.yaml", "program_file: p.nc\nprogram_strict: yes please\n"));
  EXPECT_EQ(not_bool.key_path(), "program_strict") << not_bool.what();
}


// The moving-column machine with `extra` (indented mapping lines) added under machine:.
std::string MachineWith(const std::string& extra) {
  std::string text = "machine:\n";
  std::istringstream lines(testing::ReadText(kMachine));
  for (std::string line; std::getline(lines, line);) text += "  " + line + "\n";
  return text + extra;
}

// Tests that program_dialect, program_arc_tolerance, program_max_iterations and
// machine.reference_mm reach the G-code reader: a LinuxCNC G4 P0.5 is 0.5 s, G28 goes to
// the reference position, a 10 um arc miss (over LinuxCNC's rule) passes a set tolerance.
TEST(ScenarioProgramTest, DialectKeysReachTheReader) {
  ScratchDir dir;
  dir.Write("p.nc", "G1 X10 F600\nG4 P0.5\nG2 X20.01 Y0 I5\nG28 G91 Z0\n");
  const std::string path = dir.Write(
      "s.yaml", MachineWith("  reference_mm: {g28: {x: 0, y: 0, z: 50}}\n") +
                    "program_file: p.nc\nprogram_dialect: linuxcnc\n"
                    "program_arc_tolerance: {absolute_mm: 0.02}\n");
  const Scenario s = LoadScenario(path, {});
  ASSERT_EQ(s.program->blocks.size(), 4u);
  EXPECT_DOUBLE_EQ(s.program->blocks[1].dwell_s, 0.5);
  EXPECT_NEAR(s.program->blocks[3].end_m.z(), 0.05, 1e-15);
  // Fanuc reads no decimal P; without reference_mm G28 is refused naming the key.
  const ConfigError fanuc = ProgramLoadError(dir.Write("f.yaml", "program_file: p.nc\n"));
  EXPECT_EQ(fanuc.line(), 2) << fanuc.what();
  EXPECT_NE(fanuc.message().find("linuxcnc and grbl read a decimal P in seconds"), std::string::npos)
      << fanuc.what();
  dir.Write("g.nc", "G28 G91 Z0\n");
  const ConfigError g28 = ProgramLoadError(
      dir.Write("g.yaml", "program_file: g.nc\nprogram_dialect: grbl\n"));
  EXPECT_NE(g28.message().find("machine.reference_mm.g28, which is not set"), std::string::npos)
      << g28.what();
  const ConfigError dialect = ProgramLoadError(
      dir.Write("d.yaml", "program_file: g.nc\nprogram_dialect: haas\n"));
  EXPECT_EQ(dialect.key_path(), "program_dialect") << dialect.what();
  dir.Write("loop.nc", "o1 do\no1 while [1]\n");
  const ConfigError loop = ProgramLoadError(dir.Write(
      "l.yaml", "program_file: loop.nc\nprogram_dialect: linuxcnc\nprogram_max_iterations: 10\n"));
  EXPECT_NE(loop.message().find("more than 10 loop passes"), std::string::npos) << loop.what();
  // The YAML program: list reads in the dialect too.
  const Scenario list = LoadScenario(
      dir.Write("y.yaml", "program:\n  - {g: 4, p: 0.5}\n  - {g: [91.1, 3], x: 0, y: 0, i: 5}\n"
                          "program_dialect: grbl\n"),
      {});
  ASSERT_EQ(list.program->blocks.size(), 2u);
  EXPECT_DOUBLE_EQ(list.program->blocks[0].dwell_s, 0.5);
  EXPECT_NEAR(list.program->blocks[1].center_m.x(), 5e-3, 1e-15);
}

}  // namespace
}  // namespace shapebench::bench
