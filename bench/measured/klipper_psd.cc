// Klipper's spectrum of a log (see the header).
#include "bench/measured/klipper_psd.h"

#include <algorithm>
#include <cmath>

#include "bench/config/config_error.h"
#include "bench/measured/welch_psd.h"
#include "common/format.h"

namespace shapebench::bench {

std::vector<double> KaiserWindow(int m, double beta) {
  std::vector<double> window(static_cast<std::size_t>(m), 1.0);
  if (m < 2) return window;
  const double alpha = (m - 1) / 2.0;
  const double scale = std::cyl_bessel_i(0.0, beta);
  for (int n = 0; n < m; ++n) {
    const double r = (n - alpha) / alpha;
    window[n] = std::cyl_bessel_i(0.0, beta * std::sqrt(std::max(0.0, 1.0 - r * r))) / scale;
  }
  return window;
}

KlipperSpectrum KlipperLogSpectrum(const AccelLog& log) {
  const std::size_t n = log.time_s.size();
  KlipperSpectrum spectrum;
  spectrum.source = "accelerometer log";
  const double span_s = n > 1 ? log.time_s.back() - log.time_s.front() : 0.0;
  spectrum.sample_rate_hz = span_s > 0.0 ? static_cast<double>(n) / span_s : 0.0;
  const int m = WelchSegmentLength(spectrum.sample_rate_hz);
  if (n <= static_cast<std::size_t>(m)) {
    throw ConfigError(log.file, log.line.back(), log.last_time_column, "time",
                      "too few samples for Klipper's PSD: " + std::to_string(n) + " samples at " +
                          FormatNumber(spectrum.sample_rate_hz) + " Hz, not more than one segment of " +
                          std::to_string(m));
  }
  const std::vector<double> window = KaiserWindow(m, 6.0);
  KlipperPsd psd;
  psd.name = log.file;
  for (int axis = 0; axis < 3; ++axis) {
    const Psd one = WelchPsdWindowed(log.accel_mm_s2[axis], spectrum.sample_rate_hz, window);
    psd.psd_axis[axis] = one.density;
    if (axis == 0) {
      psd.frequency_hz = one.frequency_hz;
      spectrum.segment_samples = one.segment_samples;
      spectrum.segments = one.segments;
    }
  }
  psd.psd_sum.resize(psd.frequency_hz.size());
  for (std::size_t k = 0; k < psd.psd_sum.size(); ++k) {
    psd.psd_sum[k] = psd.psd_axis[0][k] + psd.psd_axis[1][k] + psd.psd_axis[2][k];
  }
  NormalizeToFrequencies(&psd);
  spectrum.datasets.push_back(std::move(psd));
  return spectrum;
}

void NormalizeToFrequencies(KlipperPsd* psd) {
  constexpr double kMinFreqHz = 5.0;  // Klipper's MIN_FREQ
  auto normalize = [&](std::vector<double>& values) {
    for (std::size_t k = 0; k < values.size(); ++k) {
      const double f = psd->frequency_hz[k];
      values[k] /= f + 0.1;
      if (f < 2.0 * kMinFreqHz) values[k] *= std::exp(-std::pow(2.0 * kMinFreqHz / (f + 0.1), 2) + 1.0);
    }
  };
  normalize(psd->psd_sum);
  for (std::vector<double>& axis : psd->psd_axis) normalize(axis);
}

const std::vector<double>& KlipperFitPsd(const KlipperPsd& psd, AccelAxis axis, const std::string& file) {
  if (axis == AccelAxis::kAll) return psd.psd_sum;
  const std::vector<double>& one = psd.psd_axis[static_cast<int>(axis)];
  if (one.empty()) {
    throw ConfigError(file, 0, 0, "--axis",
                      std::string(AccelAxisName(axis)) + ": the file holds no per-axis PSD (only the sum of the " +
                          "axes or named data sets): use --axis all");
  }
  return one;
}

}  // namespace shapebench::bench
