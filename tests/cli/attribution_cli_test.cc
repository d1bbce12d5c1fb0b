// The attribution of `run` through the built CLI: which block and line of the program the
// peak deflection, the largest contour error and the largest cruise vibration come from.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench::attribution_cli_test {
namespace {

using testing::CliResult;
using testing::ReadCsv;
using testing::RunCli;
using testing::ScratchDir;

// Five blocks at 3 m/min: three along X (lines 4-6), the third ending in a corner taken at
// speed (a corner allowance larger than the feed: a velocity step within two periods), then
// two along Y: 0.3 mm that turns the corner (line 7, 6 ms) and 80 mm on (line 8). Only Y
// has a mode (25 Hz, 2 %): the corner's step of the Y velocity rings it far above what the
// gentle acc/dec of the start and the end do, and its peak, a quarter period (10 ms) after
// the corner, falls in the fifth block.
constexpr const char* kProgram = R"(%
(attribution: the third block ends in a corner)
G90 G17 G21 F3000
G1 X20
G1 X40
G1 X60
G1 Y0.3
G1 Y80
)";

constexpr const char* kScenario = R"(machine:
  axes:
    y: {modes: [{frequency_hz: 25, damping_ratio: 0.02, gain: 1.0}]}
  rigid: [x]
drive: {type: kinematic}
controller:
  period_s: 0.001
  feed_mm_min: 3000
  accel_time_s: 0.3
  corner_velocity_change_mm_min: 1.0e+9
program_file: corner.nc
)";

// Tests that the run reports the corner: peak_deflection_source's cause is the transition
// out of the third block (line 7, the block that turns the corner, block 3 0-based) at the
// corner's time, and the block executing at the peak's time (its `block`, `line`) is the
// one trace.csv shows at the largest |deflection|: the fifth block (line 8); the table and
// JSON agree, the file is the G-code file, and the report's table and deflection plot show
// the cause.
TEST(AttributionCli, CornerOfTheThirdBlockIsTheCauseOfThePeak) {
  const ScratchDir dir;
  dir.Write("corner.nc", kProgram);
  const std::string scenario = dir.Write("corner.yaml", kScenario);
  const std::string out = dir.File("out");
  const CliResult json_run = RunCli({"run", scenario, "--json", "--out", out}, kSourceDir);
  ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
  const nlohmann::json metrics = nlohmann::json::parse(json_run.out);
  const nlohmann::json& peak = metrics["peak_deflection_source"];
  ASSERT_TRUE(peak.is_object()) << json_run.out;
  const std::string gcode = dir.File("corner.nc");
  EXPECT_EQ(peak["cause"]["file"], gcode);
  EXPECT_EQ(peak["cause"]["line"], 7);
  EXPECT_EQ(peak["cause"]["block"], 3);
  // The corner: X reaches 60 mm at 3 m/min after the start's acc/dec (60 mm / 50 mm/s + 0.3 s / 2).
  EXPECT_NEAR(peak["cause"]["time_s"].get<double>(), 1.351, 1e-9);

  // The block executing at the largest |deflection| in the trace.
  const std::vector<std::vector<std::string>> rows = ReadCsv(out + "/trace.csv");
  ASSERT_GT(rows.size(), 2u);
  std::size_t largest = 1;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (std::abs(std::stod(rows[r][4])) > std::abs(std::stod(rows[largest][4]))) largest = r;
  }
  const double peak_time = std::stod(rows[largest][0]);
  EXPECT_EQ(rows[largest][14], "4");  // `block`
  EXPECT_EQ(peak["block"], 4);
  EXPECT_EQ(peak["line"], 8);
  EXPECT_EQ(peak["file"], gcode);
  EXPECT_GE(peak["time_s"].get<double>(), peak_time - 1e-9);  // the end of the tick holding it
  EXPECT_LT(peak["time_s"].get<double>(), peak_time + 0.001);
  EXPECT_GT(peak_time, 1.35);

  const CliResult table = RunCli({"run", scenario, "--report", dir.File("report.html")}, kSourceDir);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("; cause at 1.351 s in block 3 (" + gcode + ":7)"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("\npeak_deflection_source "), std::string::npos) << table.out;
  // The report: the table of sources, and the deflection plot marks the cause.
  const std::string html = testing::ReadText(dir.File("report.html"));
  EXPECT_NE(html.find("<td>peak_deflection_source</td>"), std::string::npos);
  EXPECT_NE(html.find("cause of the peak: block 3 (line 7)"), std::string::npos);
}

// Tests that a single move (`move:`) reports block 0 and no file (file and line null) for
// its peak deflection, during the motion, and for its cause; the other two sources name no
// file either.
TEST(AttributionCli, SingleMoveReportsBlockZeroAndNoFile) {
  const CliResult run = RunCli({"run", "configs/scenarios/method1.yaml", "--json"}, kSourceDir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json metrics = nlohmann::json::parse(run.out);
  const nlohmann::json& peak = metrics["peak_deflection_source"];
  ASSERT_TRUE(peak.is_object()) << run.out;
  EXPECT_EQ(peak["block"], 0);
  EXPECT_EQ(peak["cause"]["block"], 0);
  EXPECT_LE(peak["cause"]["time_s"].get<double>(), peak["time_s"].get<double>());
  EXPECT_LE(peak["time_s"].get<double>(), metrics["motion_time_s"].get<double>());
  for (const char* key : {"peak_deflection_source", "max_contour_error_source", "cruise_residual_source",
                          "peak_command_acceleration_source"}) {
    const nlohmann::json& source = metrics[key];
    ASSERT_TRUE(source.is_object()) << key;
    EXPECT_TRUE(source["file"].is_null()) << key;
    EXPECT_TRUE(source["line"].is_null()) << key;
    EXPECT_TRUE(source["cause"]["file"].is_null()) << key;
  }
}

}  // namespace
}  // namespace shapebench::bench::attribution_cli_test
