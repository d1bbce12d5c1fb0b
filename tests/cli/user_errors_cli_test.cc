// A new user's errors through the built CLI (docs/reliability.md): --set errors located at
// --set:N:1 in every subcommand, "did you mean" for misspelt keys and choices, output paths
// checked before anything runs, an axis the program moves without a model, and the stroke
// alarm that drops the rest of the program.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"
#include "common/closest_name.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;

// A short, valid scenario (method 1 on one 25 Hz mode).
constexpr const char* kScenario =
    "machine:\n"
    "  modes:\n"
    "    - {frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}\n"
    "controller:\n"
    "  period_s: 0.001\n"
    "  feed_mm_min: 6000\n"
    "  accel_time_s: 0.1\n"
    "  pattern: {method: zvd, mode: both, frequency_hz: 25.0}\n"
    "move: {distance_mm: 50}\n"
    "checks:\n"
    "  peak_ratio: {max: 10}\n";

constexpr const char* kSweep =
    "base: ok.yaml\n"
    "grid:\n"
    "  controller.accel_time_s: [0.1, 0.12]\n"
    "checks:\n"
    "  peak_ratio: {max: 10}\n";

bool HasText(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Tests that the edit distance counts a swap of neighbours as one edit and finds the
// nearest name within two edits only.
TEST(ClosestName, DamerauDistanceWithinTwo) {
  EXPECT_EQ(EditDistance("patern", "pattern"), 1u);
  EXPECT_EQ(EditDistance("zdv", "zvd"), 1u);
  EXPECT_EQ(EditDistance("abc", "abc"), 0u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(ClosestName("patern", {"period_s", "pattern", "post_interp"}), "pattern");
  EXPECT_EQ(ClosestName("zdv", {"zv", "zvd", "zvdd"}), "zvd");
  EXPECT_EQ(ClosestName("bogus", {"name", "base", "grid"}), "");
  EXPECT_EQ(ClosestName("pattern", {"pattern"}), "");
}

// Tests that an unknown key and a bad value given by the 2nd --set are located at
// --set:2:1 in run, check, sweep and compare, not in the scenario file.
TEST(UserErrors, SetErrorsAreLocatedAtTheOptionInEverySubcommand) {
  ScratchDir dir;
  dir.Write("ok.yaml", kScenario);
  dir.Write("sw.yaml", kSweep);
  const std::string work = dir.path().string();
  const std::vector<std::vector<std::string>> commands = {
      {"run", "ok.yaml"}, {"check", "ok.yaml"}, {"sweep", "sw.yaml", "--out", "o"},
      {"check", "sw.yaml"}, {"compare", "ok.yaml", "ok.yaml"}, {"compare", "sw.yaml", "sw.yaml"}};
  for (const auto& base : commands) {
    for (const std::string& bad : {std::string("controller.patern=3"),
                                   std::string("controller.pattern.method=zdv")}) {
      std::vector<std::string> args = base;
      for (const std::string& set : {std::string("controller.period_s=0.001"), bad}) {
        args.push_back("--set");
        args.push_back(set);
      }
      const CliResult r = RunCli(args, work);
      EXPECT_EQ(r.exit_code, 2) << base[0] << " " << bad << "\n" << r.err;
      EXPECT_TRUE(HasText(r.err, "error: --set:2:1: controller.pat")) << base[0] << " " << bad << "\n" << r.err;
      EXPECT_FALSE(HasText(r.err, "ok.yaml:")) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir.File("o"))) << base[0];
  }
}

// Tests that a misspelt key, in a file and in --set, and a misspelt choice get the
// nearest allowed name; a name near none gets no suggestion.
TEST(UserErrors, DidYouMeanForKeysAndChoices) {
  ScratchDir dir;
  dir.Write("ok.yaml", kScenario);
  const std::string work = dir.path().string();
  CliResult r = RunCli({"run", "ok.yaml", "--set", "controller.patern=3"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: --set:1:1: controller.patern: unknown key 'patern'; allowed: period_s, "))
      << r.err;
  EXPECT_TRUE(HasText(r.err, "; did you mean 'pattern'?")) << r.err;
  r = RunCli({"run", "ok.yaml", "--set", "controller.pattern.method=zdv"}, work);
  EXPECT_TRUE(HasText(r.err, "got 'zdv'; did you mean 'zvd'?")) << r.err;
  std::string text = kScenario;
  text.replace(text.find("move:"), 5, "mvoe:");
  dir.Write("typo.yaml", text);
  r = RunCli({"run", "typo.yaml"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "typo.yaml:9:1: mvoe: unknown key 'mvoe'; allowed: ")) << r.err;
  EXPECT_TRUE(HasText(r.err, "; did you mean 'move'?")) << r.err;
  r = RunCli({"run", "ok.yaml", "--set", "controller.qqqqqq=3"}, work);
  EXPECT_FALSE(HasText(r.err, "did you mean")) << r.err;
}

// Tests that a bad --out (under a regular file, or a regular file itself) and a --junit
// in a missing directory are refused before anything is loaded or run, naming the option,
// the path and the cause, and leave nothing behind.
TEST(UserErrors, OutputPathsAreCheckedBeforeTheRun) {
  ScratchDir dir;
  dir.Write("file", "x");
  // The scenario is not even read: a missing one would be the error otherwise.
  const std::string work = dir.path().string();
  CliResult r = RunCli({"run", "missing.yaml", "--out", "file/sub"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: --out file/sub: cannot write there: ")) << r.err;
  EXPECT_TRUE(HasText(r.err, "is not a directory")) << r.err;
  r = RunCli({"run", "missing.yaml", "--out", "file"}, work);
  EXPECT_TRUE(HasText(r.err, "error: --out file: cannot write there: it exists and is not a directory")) << r.err;
  r = RunCli({"sweep", "missing.yaml", "--out", "file/s"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: --out file/s: cannot write there: ")) << r.err;
  r = RunCli({"compare", "missing.yaml", "missing.yaml", "--out", "file/c"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: --out file/c: cannot write there: ")) << r.err;
  r = RunCli({"check", "missing.yaml", "--junit", "nodir/r.xml"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: --junit nodir/r.xml: cannot write there: ")) << r.err;
  EXPECT_TRUE(HasText(r.err, "No such file or directory")) << r.err;
  r = RunCli({"check", "missing.yaml", "--junit", "."}, work);
  EXPECT_TRUE(HasText(r.err, "error: --junit .: cannot write there: it is a directory")) << r.err;
  // A newline in an output path is refused before the run (issue 32 item 16: accepted, and
  // --out refused only after the run).
  for (const char* option : {"--out", "--report", "--junit"}) {
    r = RunCli({std::string(option) == "--junit" ? "check" : "run", "missing.yaml", option, "a\nb"}, work);
    EXPECT_EQ(r.exit_code, 2) << option;
    EXPECT_TRUE(HasText(r.err, "cannot write there: the path holds a control character (a newline?)")) << r.err;
  }
  // Nothing left behind: the scratch directory holds only `file`.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) entries += entry.path().filename() != "file";
  EXPECT_EQ(entries, 0);
  // A good --out that does not exist yet is accepted and created by the run.
  dir.Write("ok.yaml", kScenario);
  r = RunCli({"run", "ok.yaml", "--out", "new/deeper"}, work);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.File("new/deeper/metrics.json")));
}

// Tests that a program moving an axis the machine does not model is refused, naming the
// axis and the machine file, unless the machine lists it under rigid:; `axes: {}` stays
// an all-rigid machine.
TEST(UserErrors, UnmodelledMovedAxisNeedsRigid) {
  ScratchDir dir;
  dir.Write("m.yaml", "modes:\n  - {frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}\n");
  const std::string program =
      "controller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.1,"
      " pattern: {method: zvd, mode: both, frequency_hz: 25.0}}\n"
      "program:\n  - {g: 1, x: 20, y: 20}\n";
  dir.Write("s.yaml", "machine: m.yaml\n" + program);
  const std::string work = dir.path().string();
  CliResult r = RunCli({"run", "s.yaml"}, work);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(HasText(r.err, "error: m.yaml:1:1: machine: the program moves axis x, which the machine (m.yaml) "
                         "does not model (it models y)")) << r.err;
  EXPECT_TRUE(HasText(r.err, "rigid: [x]")) << r.err;
  dir.Write("m.yaml", "modes:\n  - {frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}\nrigid: [x]\n");
  r = RunCli({"run", "s.yaml"}, work);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  dir.Write("m.yaml", "modes:\n  - {frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}\nrigid: [y]\n");
  r = RunCli({"run", "s.yaml"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "rigid[0]: axis y has a model in this machine")) << r.err;
  dir.Write("a.yaml", "machine: {axes: {}}\ncontroller: {period_s: 0.001, feed_mm_min: 6000, accel_time_s: 0.1,"
                      " pattern: {method: none}}\n"
                      "program:\n  - {g: 1, x: 20, y: 20}\n");
  r = RunCli({"run", "a.yaml"}, work);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  dir.Write("b.yaml", "machine: {axes: {y: {modes: [{frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}]}}}\n" +
                          program);
  r = RunCli({"run", "b.yaml"}, work);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(HasText(r.err, "error: b.yaml:1:10: machine: the program moves axis x")) << r.err;
}

// Tests that a stroke alarm that drops the rest of the program is reported on stderr with
// the axis, the position, the limit and the block, in run and in check.
TEST(UserErrors, StrokeAlarmIsAWarning) {
  const std::string scenario = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/stroke_end.yaml";
  ScratchDir dir;
  for (const std::string command : {"run", "check"}) {
    const CliResult r = RunCli({command, scenario, "--set", "controller.stroke_end.enabled=false"},
                               dir.path().string());
    EXPECT_EQ(r.exit_code, command == "run" ? 0 : 1) << r.err;
    EXPECT_TRUE(HasText(r.err, "warning: " + scenario + ": stroke alarm at Y = 0.5")) << r.err;
    EXPECT_TRUE(HasText(r.err, " m (limit 0.5 m) in block 1: the rest of the program was not run")) << r.err;
  }
  // A G-code program: the block and its line.
  dir.Write("p.nc", "G1 Y100 F30000\nY600\n");
  dir.Write("pg.yaml", "machine: " + std::string(SHAPEBENCH_SOURCE_DIR) +
                           "/configs/machines/moving_column.yaml\n"
                           "controller: {period_s: 0.001, feed_mm_min: 30000, accel_time_s: 0.3}\n"
                           "program_file: p.nc\n");
  const CliResult gcode = RunCli({"run", "pg.yaml"}, dir.path().string());
  EXPECT_EQ(gcode.exit_code, 0) << gcode.err;
  EXPECT_TRUE(HasText(gcode.err, "warning: pg.yaml: stroke alarm at Y = 0.5")) << gcode.err;
  EXPECT_TRUE(HasText(gcode.err, " m (limit 0.5 m) in block 2 (line 2): the rest of the program was not run"))
      << gcode.err;
  const CliResult quiet = RunCli({"run", std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/method1.yaml"},
                                 dir.path().string());
  EXPECT_FALSE(HasText(quiet.err, "stroke alarm")) << quiet.err;
}

// Tests that a stroke alarm that cut the program fails a check `stroke_alarm: {max: 0}`
// (exit 1) saying where it fired, and that run's table and JSON say where (issue 32 item
// 15): the time, the axis at its limit, the block and its G-code line.
TEST(UserErrors, StrokeAlarmCheckFailsAndTheTableSaysWhere) {
  ScratchDir dir;
  dir.Write("p.nc", "G1 Y100 F30000\nY600\n");
  dir.Write("pg.yaml", "machine: " + std::string(SHAPEBENCH_SOURCE_DIR) +
                           "/configs/machines/moving_column.yaml\n"
                           "controller: {period_s: 0.001, feed_mm_min: 30000, accel_time_s: 0.3}\n"
                           "program_file: p.nc\n"
                           "checks: {stroke_alarm: {max: 0}}\n");
  const CliResult check = RunCli({"check", "pg.yaml"}, dir.path().string());
  EXPECT_EQ(check.exit_code, 1) << check.out << check.err;
  EXPECT_TRUE(HasText(check.out, "FAIL pg.yaml stroke_alarm = 1 (max 0): above max 0 (the alarm fired at ")) << check.out;
  EXPECT_TRUE(HasText(check.out, " s, Y = 0.5")) << check.out;
  EXPECT_TRUE(HasText(check.out, " m (limit 0.5 m), block 2 (line 2))")) << check.out;
  const CliResult run = RunCli({"run", "pg.yaml"}, dir.path().string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::size_t row = run.out.find("stroke_alarm ");
  ASSERT_NE(row, std::string::npos) << run.out;
  const std::string line = run.out.substr(row, run.out.find('\n', row) - row);
  EXPECT_TRUE(HasText(line, "true (at ")) << line;
  EXPECT_TRUE(HasText(line, "(limit 0.5 m), block 2 (line 2))")) << line;
  const CliResult json = RunCli({"run", "pg.yaml", "--json"}, dir.path().string());
  const nlohmann::json source = nlohmann::json::parse(json.out).at("stroke_alarm_source");
  EXPECT_EQ(source.at("block"), 2);
  EXPECT_EQ(source.at("line"), 2);
  EXPECT_EQ(source.at("axis"), "y");
  EXPECT_EQ(source.at("limit_m").get<double>(), 0.5);
  EXPECT_GT(source.at("time_s").get<double>(), 0.2);
  EXPECT_GE(source.at("position_m").get<double>(), 0.5);
  // A run without an alarm has no such key, and its table row says only false.
  const CliResult quiet = RunCli({"run", std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/method1.yaml", "--json"},
                                 dir.path().string());
  EXPECT_FALSE(nlohmann::json::parse(quiet.out).contains("stroke_alarm_source")) << quiet.out;
}

// Tests that the likely unit slips of issue 32 item 15 reach stderr as warnings naming the
// file, the key, the value and the slip, while the run still exits 0.
TEST(UserErrors, UnitSlipsAreWarningsOnStderr) {
  ScratchDir dir;
  dir.Write("slip.yaml",
            "machine: {modes: [{frequency_hz: 0.01, damping_ratio: 0.03, gain: 1.0}]}\n"
            "controller: {period_s: 1, feed_mm_min: 6000, accel_time_s: 200}\n"
            "move: {distance_mm: 100}\n");
  const CliResult r = RunCli({"run", "slip.yaml"}, dir.path().string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(HasText(r.err, "warning: slip.yaml: controller.period_s: 1 s is longer than any CNC's")) << r.err;
  EXPECT_TRUE(HasText(r.err, "did you mean 1 ms (controller.period_s: 0.001)?")) << r.err;
  EXPECT_TRUE(HasText(r.err, "warning: slip.yaml: controller.accel_time_s: 200 s")) << r.err;
  EXPECT_TRUE(HasText(r.err, "warning: slip.yaml: machine.modes[0].frequency_hz: 0.01 Hz")) << r.err;
  EXPECT_TRUE(HasText(r.err, "warning: slip.yaml: static_displacement_m: ")) << r.err;
}

}  // namespace
}  // namespace shapebench::bench
