// `shapebench fmu` through the built CLI: the archive's layout for both parts and both FMI
// versions, every modelDescription.xml it writes against the standard's XML schema
// (xmllint) and the FMU's own consistency check, a broken one refused by both (issue 40,
// must-show 3), and bad input located with exit 2.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/fmu/model_description.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/fmu_files.h"

namespace shapebench::bench::fmu_cli_test {
namespace {

using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;

// Replaces the first `from` in `text` with `to` (the test's way to break a description).
std::string Broken(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Tests that for the demo (a lumped machine on three axes, kinematic) and the method-1
// scenario (one mode), both parts in FMI 2.0 and 3.0 give a zip with modelDescription.xml,
// the library under the version's platform folder named by the model identifier, and the
// scenario under resources/, and that every description passes the schema and the check.
TEST(FmuCli, EveryFmuHasItsFilesAndAValidDescription) {
  for (const char* scenario : {"configs/demo.yaml", "configs/scenarios/method1.yaml"}) {
    for (const char* part : {"machine", "controller"}) {
      for (int version : {2, 3}) {
        SCOPED_TRACE(std::string(scenario) + " " + part + " FMI " + std::to_string(version));
        ScratchDir dir;
        const std::string out = dir.File("my_part.fmu");
        const CliResult result = RunCli({"fmu", scenario, "--part", part, "--out", out, "--fmi-version",
                                         std::to_string(version)}, kSourceDir);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        EXPECT_NE(result.out.find("wrote " + out), std::string::npos) << result.out;
        ASSERT_TRUE(testing::UnpackFmu(out, dir.path() / "x"));
        const std::string platform = version == 3 ? "x86_64-linux" : "linux64";
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "x/binaries" / platform / "my_part.so"));
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "x/resources/scenario.yaml"));
        const std::string description = (dir.path() / "x/modelDescription.xml").string();
        const CliResult schema = testing::ValidateAgainstSchema(description, version);
        EXPECT_EQ(schema.exit_code, 0) << schema.err;
        const std::vector<std::string> problems = fmu::CheckModelDescription(testing::ReadText(description));
        EXPECT_TRUE(problems.empty()) << problems.front();
      }
    }
  }
}

// Tests that a modelDescription broken on purpose is refused: by the schema (an unknown
// causality, FMI 2.0 and 3.0) and by the FMU's own check (a value reference used twice, a
// start value on a calculated output, a unit not declared, an output left out of the model
// structure), each problem named.
TEST(FmuCli, BrokenDescriptionsAreRefused) {
  for (int version : {2, 3}) {
    SCOPED_TRACE("FMI " + std::to_string(version));
    ScratchDir dir;
    const std::string out = dir.File("m.fmu");
    ASSERT_EQ(RunCli({"fmu", "configs/scenarios/method1.yaml", "--part", "machine", "--out", out, "--fmi-version",
                      std::to_string(version)}, kSourceDir).exit_code, 0);
    ASSERT_TRUE(testing::UnpackFmu(out, dir.path() / "x"));
    const std::string good = testing::ReadText((dir.path() / "x/modelDescription.xml").string());
    const std::string bad_schema = dir.Write("bad.xml", Broken(good, "causality=\"output\"", "causality=\"outlet\""));
    const CliResult schema = testing::ValidateAgainstSchema(bad_schema, version);
    EXPECT_NE(schema.exit_code, 0);
    EXPECT_NE(schema.err.find("outlet"), std::string::npos) << schema.err;

    const auto problems = [](const std::string& xml) {
      std::string all;
      for (const std::string& p : fmu::CheckModelDescription(xml)) all += p + "\n";
      return all;
    };
    EXPECT_EQ(problems(good), "");
    EXPECT_NE(problems(Broken(good, "valueReference=\"2\"", "valueReference=\"1\"")).find("valueReference 1 is also variable"),
              std::string::npos);
    const std::string with_start = version == 3 ? Broken(good, "unit=\"m\" />", "unit=\"m\" start=\"1\" />")
                                                : Broken(good, "<Real unit=\"m\" />", "<Real unit=\"m\" start=\"1\" />");
    EXPECT_NE(problems(with_start).find("a start value is not allowed"), std::string::npos) << problems(with_start);
    EXPECT_NE(problems(Broken(good, "unit=\"m\"", "unit=\"mm\"")).find("unit mm is not in UnitDefinitions"),
              std::string::npos);
    const std::string unlisted = version == 3 ? Broken(good, "<Output valueReference=\"2\" />", "")
                                              : Broken(good, "<Unknown index=\"3\" />", "");
    EXPECT_NE(problems(unlisted).find("output missing from ModelStructure"), std::string::npos) << problems(unlisted);
  }
}

// Tests that bad input exits 2 with the file and key named: a scenario key refused (the
// --set located), a missing scenario, a part that does not exist, and a scenario that
// refers to a G-code file the FMU cannot carry.
TEST(FmuCli, BadInputExitsTwoNamingTheProblem) {
  ScratchDir dir;
  const std::string out = dir.File("x.fmu");
  CliResult result = RunCli({"fmu", "configs/demo.yaml", "--part", "machine", "--out", out, "--set",
                             "controller.period_s=-1"}, kSourceDir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("controller.period_s"), std::string::npos) << result.err;
  result = RunCli({"fmu", "configs/nothing.yaml", "--part", "machine", "--out", out}, kSourceDir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("configs/nothing.yaml"), std::string::npos) << result.err;
  result = RunCli({"fmu", "configs/demo.yaml", "--part", "spindle", "--out", out}, kSourceDir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("--part"), std::string::npos) << result.err;
  result = RunCli({"fmu", "configs/scenarios/pocket_gcode.yaml", "--part", "controller", "--out", out}, kSourceDir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("configs/scenarios/pocket_gcode.yaml"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("does not load"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace shapebench::bench::fmu_cli_test
