// Errors that blame their cause (issue 32 items 12-14), through the built CLI: a rule
// between keys blames the key the user gave and names the other with where it came from;
// a misspelt key is located at the option that wrote it and gets its "did you mean"; a
// relative path is read from the current directory when the command line gives it and
// from the file's folder when a file does.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/bench_test_support.h"
#include "common/closest_name.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::DataPath;
using testing::ReadCsv;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

// Method 1 on one 25 Hz mode; feed_mm_min's value at 6:16, accel_time_s' at 7:17.
constexpr const char* kBlameScenario =
    "machine:\n"
    "  modes:\n"
    "    - {frequency_hz: 25.0, damping_ratio: 0.02, gain: 1.0}\n"
    "controller:\n"
    "  period_s: 0.001\n"
    "  feed_mm_min: 6000\n"
    "  accel_time_s: 0.1\n"
    "  pattern: {method: 1, mode: both, frequency_hz: 25.0}\n"
    "move: {distance_mm: 50}\n"
    "checks:\n"
    "  peak_ratio: {max: 10}\n";

bool StartsWith(const std::string& text, const std::string& start) { return text.rfind(start, 0) == 0; }
bool Mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Tests that a feed set in m/min by mistake is blamed at its --set, not at the stroke
// end's minute feed the user never wrote, which is named with its default.
TEST(BlameTheCause, AFeedSetOnTheCommandLineIsBlamedNotTheMinuteFeed) {
  ScratchDir dir;
  dir.Write("s.yaml", kBlameScenario);
  const CliResult r = RunCli({"run", "s.yaml", "--set", "controller.feed_mm_min=24"}, dir.path().string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(StartsWith(r.err, "error: --set:1:1: controller.feed_mm_min: 24 mm/min is below "
                                "controller.stroke_end.minute_feed_mm_min = 100 mm/min (not written, so its "
                                "default): the feed must be at least the stroke end's minute feed"))
      << r.err;
  // The minute feed set on the command line is the one blamed; the feed is named where it is written.
  const CliResult minute = RunCli({"run", "s.yaml", "--set", "controller.stroke_end.minute_feed_mm_min=40000"},
                                  dir.path().string());
  EXPECT_EQ(minute.exit_code, 2) << minute.err;
  EXPECT_TRUE(StartsWith(minute.err, "error: --set:1:1: controller.stroke_end.minute_feed_mm_min: 40000 mm/min is "
                                     "above controller.feed_mm_min = 6000 mm/min (s.yaml:6:16): "))
      << minute.err;
}

// Tests that a pattern frequency set on the command line is blamed against the acc/dec
// time it needs, not the feed (which does not enter the rule).
TEST(BlameTheCause, APatternFrequencySetOnTheCommandLineIsBlamedNotTheFeed) {
  ScratchDir dir;
  dir.Write("s.yaml", kBlameScenario);
  const CliResult r =
      RunCli({"run", "s.yaml", "--set", "controller.pattern.frequency_hz=0.5"}, dir.path().string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(StartsWith(r.err, "error: --set:1:1: controller.pattern.frequency_hz: 0.5 Hz is too low for "
                                "controller.accel_time_s = 0.1 s (s.yaml:7:17): "))
      << r.err;
  EXPECT_TRUE(Mentions(r.err, "at least the pattern's step 1 at each shaped end, 1 s")) << r.err;
  EXPECT_FALSE(Mentions(r.err, "a higher feed")) << r.err;
  const CliResult time = RunCli({"run", "s.yaml", "--set", "controller.accel_time_s=0.01"}, dir.path().string());
  EXPECT_EQ(time.exit_code, 2) << time.err;
  EXPECT_TRUE(StartsWith(time.err, "error: --set:1:1: controller.accel_time_s: 0.01 s is too short for "
                                   "controller.pattern.frequency_hz = 25 Hz (s.yaml:8:50): "))
      << time.err;
}

// Tests that a band check sweeping the feed from 1 blames the band's value, and that a
// sweep's point blames its grid value, a --set renumbered among the --set options.
TEST(BlameTheCause, BandAndGridValuesAreBlamedAtTheirPlace) {
  ScratchDir dir;
  dir.Write("s.yaml", kBlameScenario);
  dir.Write("band.yaml", std::string(kBlameScenario) +
                             "  residual_ratio: {max: 10, band: {key: controller.feed_mm_min, from: 1, to: 6000}}\n");
  const CliResult band = RunCli({"check", "band.yaml"}, dir.path().string());
  EXPECT_EQ(band.exit_code, 2) << band.err;
  EXPECT_TRUE(StartsWith(band.err, "error: band.yaml:12:41: checks.residual_ratio.band.key: band point "
                                   "controller.feed_mm_min = 1: controller.feed_mm_min: 1 mm/min is below "
                                   "controller.stroke_end.minute_feed_mm_min = 100 mm/min"))
      << band.err;
  dir.Write("sw.yaml", "base: s.yaml\ngrid:\n  controller.feed_mm_min: [24, 6000]\n");
  const CliResult swept = RunCli({"sweep", "sw.yaml", "--out", "o", "--set", "controller.stroke_end.minute_feed_mm_min=50"},
                                 dir.path().string());
  EXPECT_EQ(swept.exit_code, 0) << swept.err;
  const std::vector<std::vector<std::string>> rows = ReadCsv(dir.File("o/results.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(StartsWith(rows[1].back(), "--set:1:1: controller.stroke_end.minute_feed_mm_min: 50 mm/min is above "
                                         "controller.feed_mm_min = 24 mm/min (sw.yaml:3:28): "))
      << rows[1].back();
  dir.Write("sw2.yaml", "base: s.yaml\ngrid:\n  controller.feed_mm_min: [24]\n");
  const CliResult grid = RunCli({"sweep", "sw2.yaml", "--out", "o2"}, dir.path().string());
  const std::vector<std::vector<std::string>> grid_rows = ReadCsv(dir.File("o2/results.csv"));
  ASSERT_EQ(grid_rows.size(), 2u) << grid.err;
  EXPECT_TRUE(StartsWith(grid_rows[1].back(), "sw2.yaml:3:28: controller.feed_mm_min: 24 mm/min is below"))
      << grid_rows[1].back();
}

// Tests that a misspelt key inside a --set's created path is located at the option, a
// swept key indexing a misspelt list gets "did you mean", and so does a word's other form.
TEST(BlameTheCause, MisspeltKeysAreLocatedAndSuggested) {
  ScratchDir dir;
  dir.Write("s.yaml", kBlameScenario);
  const std::string work = dir.path().string();
  const CliResult set = RunCli({"run", "s.yaml", "--set", "controller.patern.method=zvd"}, work);
  EXPECT_EQ(set.exit_code, 2) << set.err;
  EXPECT_TRUE(StartsWith(set.err, "error: --set:1:1: controller.patern: unknown key 'patern'")) << set.err;
  EXPECT_TRUE(Mentions(set.err, "did you mean 'pattern'?")) << set.err;
  dir.Write("sw.yaml", "base: s.yaml\ngrid:\n  machine.mode[0].frequency_hz: [20, 25]\n");
  const CliResult swept = RunCli({"sweep", "sw.yaml", "--out", "o"}, work);
  EXPECT_EQ(swept.exit_code, 2) << swept.err;
  EXPECT_TRUE(StartsWith(swept.err, "error: sw.yaml:3:34: machine.mode: unknown key 'mode'; allowed: modes, "))
      << swept.err;
  EXPECT_TRUE(Mentions(swept.err, "did you mean 'modes'?")) << swept.err;
  // A key that is allowed but not written still says how to create it.
  const CliResult absent = RunCli({"run", "s.yaml", "--set", "controller.pattern.frequencies_hz[0]=3"}, work);
  EXPECT_TRUE(StartsWith(absent.err, "error: --set:1:1: controller.pattern.frequencies_hz[0]: cannot index "
                                     "'controller.pattern.frequencies_hz': it does not exist; set the whole sequence"))
      << absent.err;
  dir.Write("settle.yaml", std::string(kBlameScenario) + "  settle_time_s: {max: 1}\n");
  const CliResult settle = RunCli({"check", "settle.yaml"}, work);
  EXPECT_EQ(settle.exit_code, 2) << settle.err;
  EXPECT_TRUE(Mentions(settle.err, "did you mean 'settling_time_s'?")) << settle.err;
  EXPECT_EQ(DidYouMean("freq_hz", {"frequency_hz", "gain"}), "; did you mean 'frequency_hz'?");
  EXPECT_EQ(DidYouMean("peak_time_s", {"settling_time_s", "motion_time_s"}), "");
}

// Tests that a band's key path written unquoted in a flow mapping says to quote it, in a
// file and in a --set value.
TEST(BlameTheCause, AnUnquotedBandKeySaysToQuoteIt) {
  ScratchDir dir;
  dir.Write("band.yaml", std::string(kBlameScenario) +
                             "  residual_ratio: {max: 1, band: {key: machine.modes[0].frequency_hz, from: 24, to: 26}}\n");
  const CliResult file = RunCli({"check", "band.yaml"}, dir.path().string());
  EXPECT_EQ(file.exit_code, 2) << file.err;
  EXPECT_TRUE(StartsWith(file.err, "error: band.yaml:12:53: malformed YAML: end of map flow not found; a key path "
                                   "with [INDEX] inside { } or [ ] must be quoted: write "
                                   "\"machine.modes[0].frequency_hz\""))
      << file.err;
  dir.Write("s.yaml", kBlameScenario);
  const CliResult set = RunCli({"check", "s.yaml", "--set",
                                "checks.residual_ratio={max: 1, band: {key: machine.modes[0].frequency_hz, from: 24, to: 26}}"},
                               dir.path().string());
  EXPECT_EQ(set.exit_code, 2) << set.err;
  EXPECT_TRUE(Mentions(set.err, "must be quoted: write \"machine.modes[0].frequency_hz\"")) << set.err;
}

// Tests the one rule for relative paths: given by a --set (machine, program_file,
// modal_file, frf_file), from the current directory; written in a file (a scenario's, a
// sweep's grid), from that file's folder.
TEST(BlameTheCause, PathsOnTheCommandLineAreFromTheCurrentDirectory) {
  ScratchDir dir;
  const std::string machine = ReadText(DataPath("machines/two_modes.yaml")) + "rigid: [x]\n";
  dir.Write("project/machines/m.yaml", machine);
  dir.Write("project/programs/square.nc", ReadText(DataPath("programs/square.nc")));
  fs::copy_file(std::string(kSourceDir) + "/configs/machines/moving_column_fe.csv",
                dir.File("project/machines/fe.csv"));
  fs::copy_file(std::string(kSourceDir) + "/configs/measurements/column_y_accelerance.uff",
                dir.File("project/machines/frf.uff"));
  dir.Write("project/scenarios/s.yaml", "machine: ../machines/m.yaml\nprogram_file: ../programs/square.nc\n"
                                        "controller: {feed_mm_min: 3000, accel_time_s: 0.05}\n");
  dir.Write("project/sweeps/x.yaml", "base: ../scenarios/s.yaml\ngrid:\n  program_file: [../programs/square.nc]\n"
                                     "metrics: [peak_ratio]\nplots: []\n");
  const std::string work = dir.path().string();
  const std::string scenario = "project/scenarios/s.yaml";
  for (const std::string& set : {std::string("program_file=project/programs/square.nc"),
                                 std::string("machine=project/machines/m.yaml")}) {
    const CliResult r = RunCli({"run", scenario, "--set", set}, work);
    EXPECT_EQ(r.exit_code, 0) << set << "\n" << r.err;
  }
  const CliResult program = RunCli({"run", scenario, "--set", "program_file=../programs/square.nc"}, work);
  EXPECT_EQ(program.exit_code, 2);
  EXPECT_TRUE(StartsWith(program.err, "error: --set:1:1: program_file: G-code file '../programs/square.nc': cannot open"))
      << program.err;
  dir.Write("project/scenarios/line.yaml", "machine: ../machines/m.yaml\nmove: {distance_mm: 20}\n");
  const CliResult modal = RunCli({"modes", "project/scenarios/line.yaml", "--set",
                                  "machine={modal_file: project/machines/fe.csv, driven_axis: y}"},
                                 work);
  EXPECT_EQ(modal.exit_code, 0) << modal.err;
  const CliResult frf = RunCli({"modes", "project/scenarios/line.yaml", "--set",
                                "machine={frf_file: project/machines/frf.uff, axis: y, moving_mass_kg: 2400}"},
                               work);
  EXPECT_EQ(frf.exit_code, 0) << frf.err;
  const CliResult swept = RunCli({"sweep", "project/sweeps/x.yaml", "--out", "o"}, work);
  EXPECT_EQ(swept.exit_code, 0) << swept.err;
  EXPECT_TRUE(Mentions(swept.out, "1 points, 1 ok, 0 error") || Mentions(swept.out, "1 point, 1 ok, 0 error"))
      << swept.out;
}

}  // namespace
}  // namespace shapebench::bench
