// `shapebench bode` through the built CLI: the pattern's V(f) against the residual formula,
// the model's FRF against the modal sum, a measured machine's curves and fit error.
#include <cmath>
#include <complex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/math_constants.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench::bode_cli_test {
namespace {

using testing::CliResult;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;

nlohmann::json BodeJsonOf(const std::vector<std::string>& args) {
  const CliResult result = RunCli(args, kSourceDir);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return nlohmann::json::parse(result.out);
}

// The residual vibration of impulses A_j at t_j after the last, as a fraction of a step's:
// |sum A_j exp((zeta w + i w_d) t_j)| exp(-zeta w t_N) / |sum A_j| (Singer and Seering).
double ResidualFormula(const nlohmann::json& impulses, double frequency_hz, double zeta) {
  const double w = 2.0 * kPi * frequency_hz;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  std::complex<double> sum = 0.0;
  double total = 0.0;
  const double t_last = impulses.back()["time_s"].get<double>();
  for (const auto& impulse : impulses) {
    const double t = impulse["time_s"].get<double>();
    const double a = impulse["amplitude"].get<double>();
    sum += a * std::exp(std::complex<double>(-zeta * w * (t_last - t), wd * t));
    total += a;
  }
  return std::abs(sum) / std::abs(total);
}

// Tests that the pattern's V(f) in `bode --json` equals the residual formula at every one of
// its frequencies to 1e-12, for the patent's method 1 (undamped design) and for a ZV
// shaper designed for 10 % damping.
TEST(BodeCli, PatternResidualEqualsTheFormula) {
  for (const std::vector<std::string>& sets :
       {std::vector<std::string>{}, std::vector<std::string>{"--set", "controller.pattern.method=zv", "--set",
                                                            "controller.pattern.design_damping_ratio=0.1"}}) {
    std::vector<std::string> args = {"bode", "configs/demo.yaml", "--json"};
    args.insert(args.end(), sets.begin(), sets.end());
    const nlohmann::json bode = BodeJsonOf(args);
    const nlohmann::json& pattern = bode["pattern"];
    const double zeta = pattern["damping_ratio"].get<double>();
    EXPECT_EQ(zeta, sets.empty() ? 0.0 : 0.1);
    ASSERT_GE(pattern["impulses"].size(), 2u);
    ASSERT_EQ(pattern["residual"].size(), bode["frequency_hz"].size());
    for (std::size_t i = 0; i < bode["frequency_hz"].size(); ++i) {
      const double f = bode["frequency_hz"][i].get<double>();
      EXPECT_NEAR(pattern["residual"][i].get<double>(), ResidualFormula(pattern["impulses"], f, zeta), 1e-12)
          << "at " << f << " Hz";
    }
  }
}

// Tests that the model's FRF (magnitude and phase) equals the modal sum
// H(w) = sum_i -gain_i / (w_i^2 - w^2 + 2 i zeta_i w_i w) at 5 frequencies of its grid, for a
// machine of two modes on Y.
TEST(BodeCli, ModelResponseEqualsTheModalSum) {
  const ScratchDir dir;
  const std::string scenario = dir.Write("two_modes.yaml", R"(machine:
  modes:
    - {frequency_hz: 25, damping_ratio: 0.03, gain: 1.0e-3}
    - {frequency_hz: 61, damping_ratio: 0.05, gain: 2.5e-4}
drive: {type: kinematic}
controller: {period_s: 0.001, feed_mm_min: 30000, accel_time_s: 0.3, pattern: {method: none}}
move: {distance_mm: 200}
)");
  const nlohmann::json bode = BodeJsonOf({"bode", scenario, "--json", "--axis", "y"});
  ASSERT_EQ(bode["axes"].size(), 1u);
  const nlohmann::json& axis = bode["axes"][0];
  EXPECT_EQ(axis["axis"], "y");
  const double modes[2][3] = {{25.0, 0.03, 1.0e-3}, {61.0, 0.05, 2.5e-4}};
  for (const std::size_t i : {0, 97, 180, 251, 399}) {
    const double f = bode["frequency_hz"][i].get<double>();
    const double w = 2.0 * kPi * f;
    std::complex<double> h = 0.0;
    for (const auto& mode : modes) {
      const double wn = 2.0 * kPi * mode[0];
      h += -mode[2] / std::complex<double>(wn * wn - w * w, 2.0 * mode[1] * wn * w);
    }
    EXPECT_NEAR(axis["magnitude_m_per_m_s2"][i].get<double>(), std::abs(h), 1e-9 * std::abs(h)) << f << " Hz";
    const double phase_deg = std::arg(h) * 180.0 / kPi;
    const double difference = std::remainder(axis["phase_deg"][i].get<double>() - phase_deg, 360.0);
    EXPECT_NEAR(difference, 0.0, 1e-6) << f << " Hz";
  }
}

// Tests that a measured machine (configs/scenarios/measured_frf.yaml) shows its measured FRF
// and the identified model's synthesis on the band's lines with the fit error `identify`
// reports for the file, and that --out writes bode.json, bode.png and frf.png.
TEST(BodeCli, MeasuredMachineShowsMeasuredAndIdentifiedCurves) {
  const ScratchDir dir;
  const std::string out = dir.File("bode");
  const CliResult result = RunCli({"bode", "configs/scenarios/measured_frf.yaml", "--out", out}, kSourceDir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("measured axis y ("), std::string::npos) << result.out;
  for (const char* file : {"bode.json", "bode.png", "frf.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
  }
  const nlohmann::json bode = nlohmann::json::parse(ReadText(out + "/bode.json"));
  ASSERT_EQ(bode["measured"].size(), 1u);
  const nlohmann::json& measured = bode["measured"][0];
  EXPECT_EQ(measured["axis"], "y");
  const std::size_t lines = measured["frequency_hz"].size();
  EXPECT_GT(lines, 10u);
  EXPECT_EQ(measured["measured_magnitude"].size(), lines);
  EXPECT_EQ(measured["identified_magnitude"].size(), lines);
  EXPECT_GE(measured["frequency_hz"].front().get<double>(), 5.0);
  EXPECT_LE(measured["frequency_hz"].back().get<double>(), 80.0);
  const CliResult identify = RunCli({"identify", "configs/measurements/column_y_accelerance.uff", "--axis", "y",
                                     "--band", "5:80", "--json", "--out", dir.File("identify")}, kSourceDir);
  ASSERT_EQ(identify.exit_code, 0) << identify.err;
  const nlohmann::json modes = nlohmann::json::parse(identify.out);
  ASSERT_EQ(modes["records"].size(), 1u);
  EXPECT_NEAR(measured["fit_error_percent"].get<double>(), modes["records"][0]["fit_error_percent"].get<double>(), 1e-9);
}

// Tests that --axis naming an axis the machine does not model is refused with exit 2.
TEST(BodeCli, AxisWithoutModelIsRefused) {
  const CliResult result = RunCli({"bode", "configs/scenarios/method1.yaml", "--axis", "x"}, kSourceDir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("--axis: the machine has no model along x"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace shapebench::bench::bode_cli_test
