// Issue check: a run agrees with the exact continuous-time response of the same command.
// The oracle is built here from the patent's formulas alone (step times and ratios of
// paras. 38-45, steps reversed at phase ends, dec = mirrored acc, dec starting at
// distance / feed) and the closed-form undamped response x(t) = -sum dA_j (1 - cos w(t -
// t_j)) / w^2; the run goes through controller, grid, kinematic drive and CVODE.
// Tolerances: 0.005 where every step lies on the 1 ms grid (what is left is the sampling
// of the peak), 0.02 where steps fall between ticks (the grid realisation moves them).
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/run/run_scenario.h"
#include "tests/support/cli_binary.h"
#include "tests/support/sdof_fixture.h"
#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

using controller::PatternMode;

constexpr double kT = 0.04;
constexpr double kFeed = 0.5;           // m/s
constexpr double kAccel = 0.5 / 0.3;    // m/s^2
constexpr double kDistance = 0.213;     // m

struct Step {
  double t;
  double da;
};

struct Oracle {
  double peak_ratio;
  double residual_ratio;
};

// (SR1, ST1, SR2, ST2) from the patent's formulas.
std::array<double, 4> PatentSteps(const std::string& method, double k1, double t1) {
  if (method == "1") return {0.5, kT / 2, 0.0, 0.0};
  if (method == "2") return {1.0, kT / 6, 0.0, kT / 6};
  if (method == "3") {
    const double t = kT / (2 * kPi) * std::acos(1 - 1 / (2 * k1));
    return {k1, t, 1 - k1, t};
  }
  if (method == "4") return {1.0, t1, 1 - 1 / (2 * std::cos(2 * kPi * t1 / kT)), kT / 2 - 2 * t1};
  return {1.0, 0.0, 1.0, 0.0};  // none, the shaper library: not the patent's steps
}

Oracle ContinuousResponse(const std::string& method, double k1, double t1) {
  const auto [sr1, st1, sr2, st2] = PatentSteps(method, k1, t1);
  const double phase = kFeed / kAccel + 2 * ((1 - sr1) * st1 + (1 - sr2) * st2);
  std::vector<Step> steps;
  for (double sign : {1.0, -1.0}) {
    const double t0 = sign > 0 ? 0.0 : kDistance / kFeed;
    const double a = sign * kAccel;
    steps.push_back({t0, sr1 * a});
    steps.push_back({t0 + st1, (sr2 - sr1) * a});
    steps.push_back({t0 + st1 + st2, (1 - sr2) * a});
    steps.push_back({t0 + phase - st1 - st2, (sr2 - 1) * a});
    steps.push_back({t0 + phase - st1, (sr1 - sr2) * a});
    steps.push_back({t0 + phase, -sr1 * a});
  }
  const double w = 2 * kPi / kT;
  const double end = kDistance / kFeed + phase;
  double peak = 0.0;
  for (double t = 0.0; t <= end + 3 * kT; t += kT / 4000) {
    double x = 0.0;
    for (const Step& s : steps) {
      if (t >= s.t) x -= s.da * (1 - std::cos(w * (t - s.t))) / (w * w);
    }
    peak = std::max(peak, std::abs(x));
  }
  std::complex<double> phasor = 0.0;
  for (const Step& s : steps) phasor += s.da * std::exp(std::complex<double>(0, w * s.t));
  const double static_m = kAccel / (w * w);
  return {peak / static_m, std::abs(phasor) / (w * w) / static_m};
}

struct OracleCase {
  std::string method;
  double k1;
  double t1;
  bool on_grid;
};

class ContinuousOracleTest : public ::testing::TestWithParam<OracleCase> {};

// Tests that peak_ratio and residual_ratio of a CVODE run agree with the exact
// continuous-time response of the patent's command.
TEST_P(ContinuousOracleTest, RunAgreesWithContinuousResponse) {
  const OracleCase c = GetParam();
  Scenario s = testing::SdofScenario(25.0, 0.0, model::IntegratorMethod::kCvode);
  s.integrator.rtol = 1e-8;
  s.controller.pattern.method = c.method;
  s.controller.pattern.mode = PatternMode::kBoth;
  s.controller.pattern.k1 = c.k1;
  s.controller.pattern.t1_s = c.t1;
  const Metrics m = RunScenario(s).metrics;
  const Oracle oracle = ContinuousResponse(c.method, c.k1, c.t1);
  const double tolerance = c.on_grid ? 0.005 : 0.02;
  EXPECT_NEAR(m.peak_ratio, oracle.peak_ratio, tolerance);
  EXPECT_NEAR(m.residual_ratio, oracle.residual_ratio, tolerance);
}

INSTANTIATE_TEST_SUITE_P(
    Patterns, ContinuousOracleTest,
    ::testing::Values(OracleCase{"none", 0, 0, true}, OracleCase{"1", 0, 0, true},
                      OracleCase{"4", 0, 0.004, true},
                      OracleCase{"2", 0, 0, false},
                      OracleCase{"3", 0.675, 0, false},
                      OracleCase{"3", 0.8, 0, false},
                      OracleCase{"4", 0, 0.0045, false}));

// Tests the same through the command line: `shapebench run method2.yaml --json`.
TEST(ContinuousOracleCliTest, RunJsonAgreesWithContinuousResponse) {
  const std::string command = std::string(SHAPEBENCH_BINARY) + " run " + SHAPEBENCH_SOURCE_DIR +
                              "/configs/scenarios/method2.yaml --json";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << out;
  const nlohmann::json metrics = nlohmann::json::parse(out);
  const Oracle oracle = ContinuousResponse("2", 0, 0);
  EXPECT_NEAR(metrics.at("peak_ratio").get<double>(), oracle.peak_ratio, 0.02);
  EXPECT_NEAR(metrics.at("residual_ratio").get<double>(), oracle.residual_ratio, 0.02);
}

}  // namespace
}  // namespace shapebench::bench
