// `shapebench recommend` as Klipper's calibrate_shaper through the built CLI: the
// default rule on logs and on Klipper's own PSD files against the numbers Klipper printed
// (tests/data/klipper/README.md), --max-smoothing, files that are neither, short logs.
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace recommend_klipper_cli_test {
namespace {

using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

nlohmann::json Fixtures(const std::string& name) {
  std::ifstream in(kSourceDir + "/tests/data/klipper/" + name);
  return nlohmann::json::parse(in);
}

// recommend --json on the fixture's file with its options: every shaper's frequency
// within 0.2 Hz, remaining vibration within 1e-3, the same recommendation.
void ExpectKlipper(const nlohmann::json& fixture) {
  const std::string file = fixture["file"];
  std::vector<std::string> args = {"recommend", file, "--json"};
  if (!fixture["max_smoothing"].is_null()) {
    args.insert(args.end(), {"--max-smoothing", std::to_string(fixture["max_smoothing"].get<double>())});
  }
  if (!fixture["damping_ratio"].is_null()) {
    args.insert(args.end(), {"--damping-ratio", std::to_string(fixture["damping_ratio"].get<double>())});
  }
  const CliResult r = RunCli(args, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << file << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["shapers"].size(), fixture["shapers"].size()) << file;
  for (std::size_t i = 0; i < json["shapers"].size(); ++i) {
    const nlohmann::json& got = json["shapers"][i];
    const nlohmann::json& want = fixture["shapers"][i];
    EXPECT_EQ(got["method"], want["name"]) << file;
    EXPECT_NEAR(got["frequency_hz"].get<double>(), want["frequency_hz"].get<double>(), 0.2) << file << want["name"];
    EXPECT_NEAR(got["remaining_vibration"].get<double>(), want["remaining_vibration"].get<double>(), 1e-3)
        << file << want["name"];
  }
  EXPECT_EQ(json["recommended"]["method"], fixture["recommended"]) << file;
  EXPECT_NEAR(json["recommended"]["frequency_hz"].get<double>(), fixture["recommended_frequency_hz"].get<double>(),
              0.2)
      << file;
  EXPECT_TRUE(json["recommended_shapebench"]["method"].is_string()) << file;
}

// Tests that the default rule gives Klipper's numbers and recommendation on the three
// synthetic machines' logs and the shipped log, with --max-smoothing and --damping-ratio.
TEST(RecommendKlipperCli, LogsGiveKlippersRecommendation) {
  // The fixtures held in a local: a range-for over a temporary's ["cases"] would walk freed
  // memory (it ran no case).
  const nlohmann::json fixtures = Fixtures("calibrate_shaper_fixtures.json");
  ASSERT_EQ(fixtures["cases"].size(), 6u);
  for (const nlohmann::json& fixture : fixtures["cases"]) ExpectKlipper(fixture);
}

// Tests that Klipper's resonances_*.csv (not normalised) and calibration_data_*.csv
// (normalised, shapers: columns) give Klipper's recommendation on each, and that a
// per-axis PSD of the resonances file is what --axis x fits.
TEST(RecommendKlipperCli, PsdFilesGiveKlippersRecommendation) {
  const nlohmann::json fixtures = Fixtures("psd_file_fixtures.json");
  ASSERT_EQ(fixtures["cases"].size(), 4u);
  for (const nlohmann::json& fixture : fixtures["cases"]) ExpectKlipper(fixture);
  const CliResult sum = RunCli({"recommend", "tests/data/klipper/resonances_x_corexy.csv", "--json"}, kSourceDir);
  const CliResult x =
      RunCli({"recommend", "tests/data/klipper/resonances_x_corexy.csv", "--axis", "x", "--json"}, kSourceDir);
  ASSERT_EQ(x.exit_code, 0) << x.err;
  EXPECT_EQ(nlohmann::json::parse(sum.out)["klipper"]["psd"]["source"], "resonances csv");
  EXPECT_NE(nlohmann::json::parse(x.out)["shapers"][0]["remaining_vibration"],
            nlohmann::json::parse(sum.out)["shapers"][0]["remaining_vibration"]);
}

// Tests that a file that is neither a log nor a Klipper PSD file exits 2 named for what
// it looks like, and that a bad number in a PSD file names its line and column.
TEST(RecommendKlipperCli, OtherFilesAreNamedForWhatTheyLookLike) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"frequency_hz,psd,vibration_1\n10,1,1\n", "this looks like the psd.csv `shapebench recommend --out` writes"},
      {"    -1\n    58\n", "this looks like a UFF (universal file format) file"},
      {"time;accel_x\n0;1\n", "this looks like a semicolon-separated table"},
  };
  for (const auto& [text, message] : cases) {
    const std::string path = dir.Write("file.csv", text);
    const CliResult r = RunCli({"recommend", path}, kSourceDir);
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_TRUE(Has(r.err, "error: " + path + ":1:1: header: " + message)) << r.err;
  }
  const std::string bad = dir.Write("bad.csv", "freq,psd_x,psd_y,psd_z,psd_xyz\n0.0,1,1,1,3\n1.6,1,abc,1,3\n");
  const CliResult r = RunCli({"recommend", bad}, kSourceDir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "error: " + bad + ":3:7: psd_y: not a finite number: 'abc'")) << r.err;
}

// Tests that --max-smoothing below Klipper's 0.05 mm exits 2 naming the option, and that
// a log of few Welch segments warns on stderr (and in the JSON) but is fitted.
TEST(RecommendKlipperCli, MaxSmoothingAndShortLogs) {
  const CliResult small =
      RunCli({"recommend", "configs/measurements/accel_x.csv", "--max-smoothing", "0.01"}, kSourceDir);
  EXPECT_EQ(small.exit_code, 2);
  EXPECT_TRUE(Has(small.err, "--max-smoothing: must be a finite smoothing of at least 0.05 mm")) << small.err;
  ScratchDir dir;
  std::string text = "#time,accel_x,accel_y,accel_z\n";
  for (int k = 0; k < 4000; ++k) {
    text += std::to_string(k / 3200.0) + "," + std::to_string((k * 7919) % 101 - 50) + ",0,9810\n";
  }
  const std::string path = dir.Write("short.csv", text);
  const CliResult r = RunCli({"recommend", path, "--json"}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(Has(r.err, "warning: " + path + ": the log averages only 2 Welch segments of 2048 samples")) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["warnings"].size(), 1u);
}

// Tests that shapebench's registry is also scored on Klipper's normalised PSD
// (`shapebench_normalised`, `recommended_shapebench_normalised`): on every Klipper
// fixture log without options, every method of shapebench's own view is there (the
// patent's methods 1-4 among them), each under its rule; each of Klipper's candidates
// whose design the registry has leaves at most Klipper's own remaining vibration + 1e-3
// there (the same PSD and formula, the lowest over the same 0.2 Hz grid, EI's curve fits
// within 1e-3 of the registry's designs), and some method scores differently than on
// the unnormalised PSD of shapebench's own view; on a Klipper PSD file, whose PSD both
// views read, the two views are the same.
TEST(RecommendKlipperCli, RegistryScoredUnderKlippersNormalisation) {
  const std::vector<std::pair<std::string, std::string>> counterparts = {
      {"zv", "zv"}, {"mzv", "mzv"}, {"ei", "ei"}, {"2hump_ei", "ei_2hump"}, {"3hump_ei", "ei_3hump"}};
  const nlohmann::json fixtures = Fixtures("calibrate_shaper_fixtures.json");
  ASSERT_EQ(fixtures["cases"].size(), 6u);
  int checked = 0;
  for (const nlohmann::json& fixture : fixtures["cases"]) {
    if (!fixture["max_smoothing"].is_null() || !fixture["damping_ratio"].is_null()) continue;
    const std::string file = fixture["file"];
    SCOPED_TRACE(file);
    ++checked;
    const CliResult r = RunCli({"recommend", file, "--json"}, kSourceDir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(r.out);
    const nlohmann::json& own = json["shapebench"]["shapers"];
    const nlohmann::json& normalised = json["shapebench_normalised"]["shapers"];
    ASSERT_EQ(normalised.size(), own.size());
    std::map<std::string, double> remaining;
    bool differs = false;
    for (std::size_t i = 0; i < own.size(); ++i) {
      EXPECT_EQ(normalised[i]["method"], own[i]["method"]);
      EXPECT_EQ(normalised[i]["rule"], "shapebench on klipper's normalised psd");
      remaining[normalised[i]["method"]] = normalised[i]["remaining_vibration"].get<double>();
      differs |= std::abs(normalised[i]["remaining_vibration"].get<double>() -
                          own[i]["remaining_vibration"].get<double>()) > 1e-3;
    }
    EXPECT_TRUE(differs);
    for (const char* method : {"1", "2", "3", "4"}) EXPECT_EQ(remaining.count(method), 1u) << method;
    for (const nlohmann::json& klipper : fixture["shapers"]) {
      for (const auto& [name, registry] : counterparts) {
        if (klipper["name"] != name || remaining.count(registry) == 0) continue;
        EXPECT_LE(remaining[registry], klipper["remaining_vibration"].get<double>() + 1e-3) << name;
      }
    }
    EXPECT_EQ(json["rule"]["recommended_shapebench_normalised"], "shapebench on klipper's normalised psd");
    EXPECT_EQ(remaining.count(json["recommended_shapebench_normalised"]["method"].get<std::string>()), 1u);
  }
  EXPECT_EQ(checked, 4);
  const CliResult file = RunCli({"recommend", "tests/data/klipper/resonances_x_corexy.csv", "--json"}, kSourceDir);
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const nlohmann::json json = nlohmann::json::parse(file.out);
  ASSERT_EQ(json["shapebench_normalised"]["shapers"].size(), json["shapebench"]["shapers"].size());
  for (std::size_t i = 0; i < json["shapebench"]["shapers"].size(); ++i) {
    EXPECT_EQ(json["shapebench_normalised"]["shapers"][i]["remaining_vibration"],
              json["shapebench"]["shapers"][i]["remaining_vibration"]);
  }
  const CliResult text = RunCli({"recommend", "configs/measurements/accel_x.csv"}, kSourceDir);
  EXPECT_TRUE(Has(text.out, "\nrecommended_shapebench_normalised: ")) << text.out;
}

}  // namespace
}  // namespace recommend_klipper_cli_test
}  // namespace shapebench::bench
