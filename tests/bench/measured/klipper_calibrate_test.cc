// Klipper's calibrate_shaper rule (bench/measured/klipper_calibrate.h, klipper_psd.h)
// against the numbers Klipper's own code printed at the pinned commit on the logs of
// tests/data/klipper (tests/data/klipper/README.md says how they were made).
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/config/config_error.h"
#include "bench/measured/accel_log.h"
#include "bench/measured/klipper_calibrate.h"
#include "bench/measured/klipper_psd.h"
#include "bench/measured/klipper_psd_file.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

nlohmann::json Fixtures(const std::string& name) {
  std::ifstream in(kSourceDir + "/tests/data/klipper/" + name);
  return nlohmann::json::parse(in);
}

KlipperRecommendation Fit(const KlipperSpectrum& spectrum, const nlohmann::json& fixture) {
  KlipperFitOptions options;
  if (!fixture["max_smoothing"].is_null()) options.max_smoothing_mm = fixture["max_smoothing"].get<double>();
  if (!fixture["damping_ratio"].is_null()) options.damping_ratio = fixture["damping_ratio"].get<double>();
  std::vector<KlipperFitInput> data;
  for (const KlipperPsd& psd : spectrum.datasets) data.push_back({psd.frequency_hz, psd.psd_sum});
  return KlipperFindBestShaper(data, options);
}

// Every shaper's frequency within 0.2 Hz, remaining vibration within 1e-3 (a fraction),
// smoothing within 1e-3 mm, and the same recommendation as Klipper's.
void ExpectKlipper(const KlipperRecommendation& got, const nlohmann::json& fixture) {
  const std::string file = fixture["file"];
  ASSERT_EQ(got.shapers.size(), fixture["shapers"].size()) << file;
  for (std::size_t i = 0; i < got.shapers.size(); ++i) {
    const nlohmann::json& want = fixture["shapers"][i];
    const KlipperShaperResult& r = got.shapers[i];
    EXPECT_EQ(r.name, want["name"]) << file;
    EXPECT_NEAR(r.frequency_hz, want["frequency_hz"].get<double>(), 0.2) << file << " " << r.name;
    EXPECT_NEAR(r.remaining_vibration, want["remaining_vibration"].get<double>(), 1e-3) << file << " " << r.name;
    EXPECT_NEAR(r.smoothing_mm, want["smoothing_mm"].get<double>(), 1e-3) << file << " " << r.name;
  }
  EXPECT_EQ(got.shapers[got.recommended].name, fixture["recommended"]) << file;
  EXPECT_NEAR(got.shapers[got.recommended].frequency_hz, fixture["recommended_frequency_hz"].get<double>(), 0.2)
      << file;
}

// Tests that the three synthetic machines' logs and the shipped log give Klipper's
// per-shaper frequency, remaining vibration, smoothing and recommendation, also with
// --max-smoothing and another design damping.
TEST(KlipperCalibrate, LogsGiveKlippersNumbers) {
  const nlohmann::json fixtures = Fixtures("calibrate_shaper_fixtures.json");
  EXPECT_EQ(fixtures["klipper_commit"], kKlipperCommit);
  ASSERT_GE(fixtures["cases"].size(), 6u);
  for (const nlohmann::json& fixture : fixtures["cases"]) {
    const AccelLog log = ReadAccelLog(kSourceDir + "/" + fixture["file"].get<std::string>());
    ExpectKlipper(Fit(KlipperLogSpectrum(log), fixture), fixture);
  }
}

// Tests Klipper's shaper definitions at the default damping: amplitudes summing as
// Klipper's do (zv 1 + K, the others 1 at zero damping), zv's half damped period, and
// mzv's generalised form equal to the classic MZV (1 - 1/sqrt 2, sqrt 2 - 1, 1 - 1/sqrt 2
// at 0, 0.375, 0.75 periods) when undamped.
TEST(KlipperCalibrate, ShaperDefinitions) {
  const KlipperShaper mzv = KlipperInitShaper("mzv", 40.0, 0.0);
  ASSERT_EQ(mzv.amplitude.size(), 3u);
  const double a1 = 1.0 - 1.0 / std::sqrt(2.0);
  EXPECT_NEAR(mzv.amplitude[0], a1, 1e-12);
  EXPECT_NEAR(mzv.amplitude[1], std::sqrt(2.0) - 1.0, 1e-12);
  EXPECT_NEAR(mzv.amplitude[2], a1, 1e-12);
  EXPECT_NEAR(mzv.time_s[2], 0.75 / 40.0, 1e-15);
  const KlipperShaper zv = KlipperInitShaper("zv", 40.0, 0.1);
  EXPECT_NEAR(zv.time_s[1], 0.5 / (40.0 * std::sqrt(1.0 - 0.01)), 1e-15);
  for (const std::string& name : KlipperAutotuneShapers()) {
    const KlipperShaper s = KlipperInitShaper(name, 50.0, 0.1);
    // A shaper leaves little of its own design mode: the EI forms about their 5% tolerance
    // (ei's fitted polynomials 5.06%), zv and mzv nothing.
    EXPECT_LE(KlipperShaperResponse(s, 0.1, {50.0})[0], 0.051) << name;
    EXPECT_EQ(KlipperShaperResponse(s, 0.1, {0.0})[0], 1.0) << name;
  }
  EXPECT_THROW(KlipperInitShaper("zvd2", 40.0, 0.1), std::invalid_argument);
}

// Tests the options Klipper refuses: a damping ratio outside (0, 1) and a maximum
// smoothing under 0.05 mm, each named.
TEST(KlipperCalibrate, BadOptionsAreNamed) {
  KlipperFitOptions options;
  options.damping_ratio = 0.0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options.damping_ratio = 0.1;
  options.max_smoothing_mm = 0.01;
  try {
    options.validate();
    ADD_FAILURE() << "0.01 mm accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("--max-smoothing"), std::string::npos);
  }
}

// Tests Klipper's parse_log on named data sets: one a column up to `shapers:`, normalised
// unless the header has `,shapers:` (20 / (20 + 0.1) at 20 Hz; below 10 Hz also damped),
// an empty field read as 0, and --axis x refused (no per-axis PSD) naming the option.
TEST(KlipperCalibrate, NamedDataSetsAreReadAsKlipperReadsThem) {
  const std::string rows = "# a comment\nfreq,a,b\n5.0,1,2\n20.0,20,\n";
  const KlipperSpectrum raw = ParseKlipperPsdFile(rows, "f.csv");
  ASSERT_EQ(raw.datasets.size(), 2u);
  EXPECT_EQ(raw.datasets[1].name, "b");
  EXPECT_FALSE(raw.normalized_in_file);
  EXPECT_DOUBLE_EQ(raw.datasets[0].psd_sum[1], 20.0 / 20.1);
  EXPECT_DOUBLE_EQ(raw.datasets[0].psd_sum[0], 1.0 / 5.1 * std::exp(1.0 - std::pow(10.0 / 5.1, 2)));
  EXPECT_EQ(raw.datasets[1].psd_sum[1], 0.0);
  const KlipperSpectrum read =
      ParseKlipperPsdFile("freq,a,b,shapers:,zv(40.0)\n5.0,1,2,,0.5\n20.0,20,3,,0.1\n", "f.csv");
  EXPECT_TRUE(read.normalized_in_file);
  EXPECT_EQ(read.datasets.size(), 2u);
  EXPECT_EQ(read.datasets[0].psd_sum[1], 20.0);
  EXPECT_TRUE(IsKlipperPsdFile(rows));
  EXPECT_FALSE(IsKlipperPsdFile("#time,accel_x,accel_y,accel_z\n0,1,2,3\n"));
  EXPECT_THROW(KlipperFitPsd(read.datasets[0], AccelAxis::kX, "f.csv"), ConfigError);
}

}  // namespace
}  // namespace shapebench::bench
