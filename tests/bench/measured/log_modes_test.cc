// --validate's modes from a log (bench/measured/log_modes.h, modal_psd_fit.h): a low,
// lightly damped machine-tool mode under white-noise base acceleration read by the modal
// fit, not by the half-power width on Klipper's 1.56 Hz bins, with an uncertainty that
// covers the truth.
#include <cmath>
#include <complex>
#include <string>
#include <tuple>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "bench/measured/accel_log.h"
#include "bench/measured/accel_spectrum.h"
#include "bench/measured/log_modes.h"
#include "bench/measured/modal_psd_fit.h"
#include "bench/measured/psd_peaks.h"
#include "common/validation_error.h"
#include "tests/support/accel_log_oracle.h"

namespace shapebench::bench::log_modes_test {
namespace {

constexpr double kModeHz = 16.5;
constexpr double kModeDamping = 0.025;

// 60 s at 3.2 kHz of one 16.5 Hz mode at 2.5% damping on a base shaken by white noise
// (1 m/s^2 RMS, no chirp); every axis then gets sensor noise of 5% of the response's RMS
// (its own generator, seeded from `seed`).
AccelLog WhiteNoiseLog(unsigned seed) {
  testing::SyntheticLogSpec spec;
  spec.modes = {{kModeHz, kModeDamping, 1.0}};
  spec.seconds = 60.0;
  spec.rate_hz = 3200.0;
  spec.chirp_mm_s2 = 0.0;
  spec.noise_mm_s2 = 1000.0;
  spec.sensor_noise_mm_s2 = 0.0;
  spec.seed = seed;
  const testing::SyntheticSamples s = testing::Synthesize(spec);
  double power = 0.0;
  for (const double x : s.x) power += x * x;
  const double sensor = 0.05 * std::sqrt(power / static_cast<double>(s.x.size()));
  std::mt19937_64 random(seed + 1000u);
  std::normal_distribution<double> normal(0.0, sensor);
  AccelLog log;
  log.file = "white_noise.csv";
  for (std::size_t k = 0; k < s.x.size(); ++k) {
    log.time_s.push_back(s.time_s[k]);
    log.accel_mm_s2[0].push_back(s.x[k] + normal(random));
    log.accel_mm_s2[1].push_back(s.y[k] + normal(random));
    log.accel_mm_s2[2].push_back(s.z[k] + normal(random));
    log.line.push_back(static_cast<int>(k) + 2);
  }
  return log;
}

// What `recommend --validate` does: the peaks of shapebench's PSD, then the modal fit.
LogModes ModesOf(const AccelLog& log, double resolution_hz = 0.0) {
  const AccelSpectrum spectrum = ComputeAccelSpectrum(log, AccelAxis::kAll);
  return FitLogModes(spectrum.samples, AccelAxis::kAll, PickPsdPeaks(spectrum.frequency_hz, spectrum.psd),
                     resolution_hz);
}

// Tests that a 16.5 Hz mode at 2.5% damping (60 s at 3.2 kHz under white-noise base
// acceleration, sensor noise 5% of the response's RMS) is read within 1% in frequency
// and 25% in damping for each of ten fixed seeds, with a positive uncertainty on each;
// and that the truth lies within two standard deviations in at least 8 of the ten
// (the counts, and within one, print).
TEST(LogModes, WhiteNoiseModeIsReadWithinOnePercentAndAQuarterOfItsDamping) {
  int frequency_one_sigma = 0, damping_one_sigma = 0, frequency_two_sigma = 0, damping_two_sigma = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const LogModes fitted = ModesOf(WhiteNoiseLog(seed));
    ASSERT_EQ(fitted.modes.size(), 1u);
    EXPECT_TRUE(fitted.warnings.empty()) << fitted.warnings.front();
    EXPECT_EQ(fitted.spectrum, "periodogram");
    EXPECT_EQ(fitted.segments, 1);
    EXPECT_NEAR(fitted.resolution_hz, 1.0 / 60.0, 0.02 / 60.0);  // the FFT's length: 7-smooth
    const LogMode& mode = fitted.modes[0];
    EXPECT_NEAR(mode.frequency_hz, kModeHz, 0.01 * kModeHz);
    EXPECT_NEAR(mode.damping_ratio, kModeDamping, 0.25 * kModeDamping);
    EXPECT_GT(mode.frequency_uncertainty_hz, 0.0);
    EXPECT_GT(mode.damping_uncertainty, 0.0);
    const double f_sigmas = std::abs(mode.frequency_hz - kModeHz) / mode.frequency_uncertainty_hz;
    const double z_sigmas = std::abs(mode.damping_ratio - kModeDamping) / mode.damping_uncertainty;
    frequency_one_sigma += f_sigmas <= 1.0;
    damping_one_sigma += z_sigmas <= 1.0;
    frequency_two_sigma += f_sigmas <= 2.0;
    damping_two_sigma += z_sigmas <= 2.0;
    std::cout << "seed " << seed << ": " << mode.frequency_hz << " +/- " << mode.frequency_uncertainty_hz
              << " Hz, damping " << mode.damping_ratio << " +/- " << mode.damping_uncertainty << "\n";
  }
  std::cout << "truth within 1 sigma: frequency " << frequency_one_sigma << "/10, damping " << damping_one_sigma
            << "/10; within 2 sigma: " << frequency_two_sigma << "/10, " << damping_two_sigma << "/10\n";
  EXPECT_GE(frequency_two_sigma, 8);
  EXPECT_GE(damping_two_sigma, 8);
}

// Tests that a coarser --resolution-hz averages Welch segments (0.1 Hz: 11 segments of
// 10 s half overlapping) and still reads the mode within 1% and 25%; and that a resolution
// finer than the log allows is refused naming the option.
TEST(LogModes, ResolutionSetByTheUserAveragesSegments) {
  const AccelLog log = WhiteNoiseLog(3);
  const LogModes fitted = ModesOf(log, 0.1);
  EXPECT_EQ(fitted.spectrum, "welch");
  EXPECT_EQ(fitted.segment_samples, 32000);
  EXPECT_EQ(fitted.segments, 11);
  ASSERT_EQ(fitted.modes.size(), 1u);
  EXPECT_NEAR(fitted.modes[0].frequency_hz, kModeHz, 0.01 * kModeHz);
  EXPECT_NEAR(fitted.modes[0].damping_ratio, kModeDamping, 0.25 * kModeDamping);
  try {
    ModesOf(log, 0.01);
    ADD_FAILURE() << "a resolution of 0.01 Hz from 60 s was accepted";
  } catch (const ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--resolution-hz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("finer than the log allows"), std::string::npos) << e.what();
  }
}

// Tests that the fit recovers two coupled modes of a noiseless model PSD (the model's own
// bins, no noise floor, read without a kernel) from starting guesses 3% and 60% off:
// frequencies and damping ratios within 1e-4 relative, the gain within 1e-3, no floor.
TEST(ModalPsdFit, RecoversTheModelsOwnParameters) {
  ModalPsdInput input;
  const double bin = 0.05;
  for (int k = 0; k < 1200; ++k) input.frequency_hz.push_back(20.0 + k * bin);
  // A sampled model without the kernel: the kernel {1} reads it as it is.
  for (const double f : input.frequency_hz) {
    const std::complex<double> s(0.0, 2.0 * testing::kOraclePi * f);
    std::complex<double> t = 1.0;
    for (const auto& [fn, zeta, g] : {std::tuple{37.0, 0.05, 0.8}, std::tuple{61.0, 0.03, 0.54}}) {
      const double w = 2.0 * testing::kOraclePi * fn;
      t -= g * s * s / (s * s + 2.0 * zeta * w * s + w * w);
    }
    input.psd.push_back(400.0 * std::norm(t));
  }
  const ModalPsdFit fit = FitModalPsd(input, {{36.0, 0.08}, {62.0, 0.05}}, 25.0, 75.0);
  ASSERT_TRUE(fit.trouble.empty()) << fit.trouble;
  ASSERT_EQ(fit.modes.size(), 2u);
  EXPECT_NEAR(fit.modes[0].frequency_hz, 37.0, 1e-4 * 37.0);
  EXPECT_NEAR(fit.modes[0].damping_ratio, 0.05, 1e-4 * 0.05);
  EXPECT_NEAR(fit.modes[1].frequency_hz, 61.0, 1e-4 * 61.0);
  EXPECT_NEAR(fit.modes[1].damping_ratio, 0.03, 1e-4 * 0.03);
  EXPECT_NEAR(fit.modes[0].gain, 0.8, 1e-3);
  EXPECT_LT(fit.noise_floor, 1e-6 * 400.0);
}

}  // namespace
}  // namespace shapebench::bench::log_modes_test
