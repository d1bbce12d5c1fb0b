// `shapebench design` through the built CLI: the JSON of a two-mode impulses design and of a
// profile table, the fragment a run takes, bad options exit 2 naming the option, an
// unreachable specification exit 3.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench::design_cli_test {

using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;

// Issue 39's two modes on one axis.
const char* kTwoModes = R"(machine:
  modes:
    - {frequency_hz: 18.0, damping_ratio: 0.02, gain: 1.0}
    - {frequency_hz: 47.0, damping_ratio: 0.035, gain: 1.0}
drive: {type: kinematic}
controller: {period_s: 0.001, feed_mm_min: 12000, accel_time_s: 0.1, pattern: {method: none}}
move: {distance_mm: 300}
integrator: {method: exact}
)";

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Tests that a two-mode impulses design prints its duration, impulses summing to 1 on the
// 0.1 ms grid, both bands (+/- 10% of each mode at its damping) with a worst V within the
// guaranteed bound, the motion time it adds, the registry ranked, and that --validate's runs of the bench itself
// (each band swept, shaped over unshaped residual) stay within the same bound (issue 39's
// must-show 2: the impulses run on a 0.1 ms period, so the realisation adds no error).
TEST(DesignCli, TwoModeImpulsesJsonAndValidation) {
  const ScratchDir dir;
  const std::string scenario = dir.Write("two.yaml", kTwoModes);
  const CliResult r =
      RunCli({"design", scenario, "--form", "impulses", "--json", "--validate"}, dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["form"], "impulses");
  EXPECT_DOUBLE_EQ(j["grid_s"].get<double>(), 1e-4);
  double total = 0.0;
  for (const auto& i : j["impulses"]) {
    total += i["amplitude"].get<double>();
    EXPECT_GE(i["amplitude"].get<double>(), 0.0);
    const double steps = i["time_s"].get<double>() / 1e-4;
    EXPECT_NEAR(steps, std::round(steps), 1e-6);
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(j["impulses"].back()["time_s"].get<double>(), j["duration_s"].get<double>());
  ASSERT_EQ(j["bands"].size(), 2u);
  EXPECT_NEAR(j["bands"][0]["frequency_lo_hz"].get<double>(), 16.2, 1e-12);
  EXPECT_NEAR(j["bands"][1]["frequency_hi_hz"].get<double>(), 51.7, 1e-12);
  EXPECT_DOUBLE_EQ(j["bands"][1]["damping_lo"].get<double>(), 0.035);
  for (const auto& band : j["bands"]) EXPECT_LE(band["worst_v"].get<double>(), j["guaranteed_v"].get<double>());
  EXPECT_FALSE(j["registry"].empty());
  // The impulses realised on the 1 ms period: the motion grows by the duration rounded up.
  EXPECT_NEAR(j["added_motion_time_s"].get<double>(), std::ceil(j["duration_s"].get<double>() / 0.001) * 0.001, 1e-9);
  for (const auto& entry : j["registry"]) EXPECT_GE(entry["added_motion_time_s"].get<double>(), 0.0);
  ASSERT_EQ(j["validation"].size(), 2u);
  for (const auto& v : j["validation"]) {
    EXPECT_LE(v["worst_residual_ratio"].get<double>(), j["guaranteed_v"].get<double>());
    EXPECT_GT(v["worst_residual_ratio"].get<double>(), 0.0);
    EXPECT_EQ(v["runs"].get<int>(), 18);
  }
}

// Tests that the profile-table design of a 25 Hz undamped mode has one coefficient per
// controller.period_s, adds its duration to the motion, and that its fragment, given to `run` with --set, leaves at most the
// guaranteed V of the unshaped run's residual.
TEST(DesignCli, ProfileTableFragmentRuns) {
  const ScratchDir dir;
  const std::string scenario = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/method1.yaml";
  const CliResult r = RunCli({"design", scenario, "--json", "--no-registry"}, dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const std::vector<double> table = j["coefficients"].get<std::vector<double>>();
  EXPECT_NEAR((table.size() - 1) * 0.001, j["duration_s"].get<double>(), 1e-12);
  EXPECT_NEAR(j["added_motion_time_s"].get<double>(), j["duration_s"].get<double>(), 1e-9);  // the table's length
  std::string text = "[";
  for (std::size_t k = 0; k < table.size(); ++k) text += (k ? ", " : "") + nlohmann::json(table[k]).dump();
  text += "]";
  const auto residual = [&](const std::vector<std::string>& sets) {
    std::vector<std::string> args{"run", scenario, "--json", "--set", "controller.pattern.method=none"};
    for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
    const CliResult run = RunCli(args, dir.path().string());
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["residual_amplitude_m"].get<double>();
  };
  const double unshaped = residual({});
  const double shaped = residual({"controller.post_interp={type: profile_table, table: " + text + "}"});
  EXPECT_LE(shaped / unshaped, j["guaranteed_v"].get<double>());
}

// Tests that --out writes the JSON, the fragment and the plot, a "wrote" line each.
TEST(DesignCli, OutWritesItsFiles) {
  const ScratchDir dir;
  const std::string scenario = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/method1.yaml";
  const CliResult r = RunCli({"design", scenario, "--out", "d"}, dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string file : {"design.json", "design.yaml", "design.png"}) {
    EXPECT_TRUE(Has(r.out, "wrote d/" + file)) << r.out;
  }
  EXPECT_TRUE(Has(testing::ReadText(dir.File("d/design.yaml")), "type: profile_table"));
  EXPECT_TRUE(Has(r.out, "scenario fragment"));
}

// Tests that a table longer than the scenario's max_table_length says so and that --out
// then also writes the impulses form (design_impulses.yaml, a custom pattern).
TEST(DesignCli, TooLongTableOffersImpulses) {
  const ScratchDir dir;
  const std::string scenario = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/method1.yaml";
  const CliResult r = RunCli({"design", scenario, "--set", "controller.post_interp.max_table_length=10", "--out", "d",
                              "--no-registry"},
                             dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "more than the scenario's controller.post_interp.max_table_length (10)")) << r.out;
  EXPECT_TRUE(Has(r.out, "wrote d/design_impulses.yaml")) << r.out;
  EXPECT_TRUE(Has(testing::ReadText(dir.File("d/design_impulses.yaml")), "method: custom"));
}

struct BadOption {
  std::vector<std::string> args;
  std::string message;  // a part of stderr
};

// Tests that every bad option exits 2 naming the option and what is allowed.
TEST(DesignCli, BadOptionsExit2NamingTheOption) {
  const ScratchDir dir;
  const std::string scenario = dir.Write("two.yaml", kTwoModes);
  const std::vector<BadOption> cases = {
      {{"--band", "2=40:50"}, "--band: '2=40:50': no participating mode 2; allowed: MODE=LO:HI, MODE 0 to 1"},
      {{"--band", "0=20"}, "--band: '0=20' is not MODE=LO:HI"},
      {{"--band", "0=20:10"}, "--band: '0=20:10': LO must be <= HI"},
      {{"--band", "0=x:10"}, "--band: '0=x:10' is not MODE=LO:HI with numbers"},
      {{"--damping", "1=0.1:0.9"}, "--damping: '1=0.1:0.9': damping ratios must be in [0, 0.7]"},
      {{"--tolerance", "1.5"}, "--tolerance: must be in [0, 1)"},
      {{"--derivatives", "7"}, "--derivatives: must be 0 to 4"},
      {{"--form", "steps"}, "--form"},
      {{"--grid-s", "0.001"}, "--grid-s: is for --form impulses only"},
      {{"--form", "impulses", "--grid-s", "0"}, "--grid-s: must be in [1e-7, 1] s"},
      {{"--margin", "0"}, "--margin: must be in [1e-6, 1]"},
  };
  for (const BadOption& c : cases) {
    std::vector<std::string> args{"design", scenario};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliResult r = RunCli(args, dir.path().string());
    EXPECT_EQ(r.exit_code, 2) << c.args[0] << " " << r.err;
    EXPECT_TRUE(Has(r.err, c.message)) << r.err;
  }
}

// Tests that a specification no pattern meets (zero residual over a 10 Hz band) exits 3
// saying what to change.
TEST(DesignCli, UnreachableSpecificationExits3) {
  const ScratchDir dir;
  const std::string scenario = dir.Write("two.yaml", kTwoModes);
  const CliResult r = RunCli({"design", scenario, "--band", "0=15:25", "--tolerance", "0", "--margin", "0.5"}, dir.path().string());
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(Has(r.err, "widen the tolerance")) << r.err;
}

}  // namespace shapebench::bench::design_cli_test
