// The log's samples on a uniform grid and their PSD in the fit band (see the header).
#include "bench/measured/accel_spectrum.h"

#include <algorithm>
#include <cmath>

#include "bench/config/config_error.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

// Stamps within this fraction of a period of their grid point count as on the grid.
constexpr double kOnGridFraction = 0.01;

ConfigError RecordError(const AccelLog& log, const std::string& message) {
  return ConfigError(log.file, log.line.back(), log.last_time_column, "time", message);
}

}  // namespace

const char* AccelAxisName(AccelAxis axis) {
  switch (axis) {
    case AccelAxis::kX: return "x";
    case AccelAxis::kY: return "y";
    case AccelAxis::kZ: return "z";
    case AccelAxis::kAll: return "all";
  }
  return "all";
}

UniformAccel ToUniformGrid(const AccelLog& log) {
  const std::size_t n = log.time_s.size();
  const std::string needs = "a shaper fit needs a PSD to " + FormatNumber(kFitMaxHz) + " Hz: at least " +
                            FormatNumber(2.0 * kFitMaxHz) + " samples a second (Nyquist)";
  if (n < 2) throw RecordError(log, "one sample: " + needs + " and more samples than one Welch segment");
  const double span_s = log.time_s.back() - log.time_s.front();
  UniformAccel uniform;
  uniform.sample_rate_hz = static_cast<double>(n - 1) / span_s;
  uniform.start_s = log.time_s.front();
  const double rate = uniform.sample_rate_hz;
  const std::string record = std::to_string(n) + " samples over " + FormatNumber(span_s) + " s";
  if (!(rate >= 2.0 * kFitMaxHz * (1.0 - 1e-9))) {  // 400 Hz stamped to the microsecond reads a hair below
    throw RecordError(log, "sample rate " + FormatNumber(rate) + " Hz (" + record + ") is too low: " + needs);
  }
  const int segment = WelchSegmentLength(rate);
  if (n <= static_cast<std::size_t>(segment)) {
    throw RecordError(log, "too few samples for the PSD: " + record + " at " + FormatNumber(rate) +
                               " Hz; the Welch PSD needs more than one segment of " + std::to_string(segment) +
                               " samples (0.5 s rounded up to a power of 2): record at least " +
                               FormatNumber(static_cast<double>(segment + 1) / rate) + " s");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double grid = uniform.start_s + static_cast<double>(i) / rate;
    uniform.max_offset_s = std::max(uniform.max_offset_s, std::abs(log.time_s[i] - grid));
  }
  uniform.resampled = uniform.max_offset_s > kOnGridFraction / rate;
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<double>& values = log.accel_mm_s2[axis];
    if (!uniform.resampled) {
      uniform.accel_mm_s2[axis] = values;
      continue;
    }
    std::vector<double>& out = uniform.accel_mm_s2[axis];
    out.resize(n);
    std::size_t i = 0;  // log.time_s[i] <= grid time < log.time_s[i + 1]
    for (std::size_t k = 0; k < n; ++k) {
      const double t = std::min(uniform.start_s + static_cast<double>(k) / rate, log.time_s.back());
      while (i + 2 < n && log.time_s[i + 1] <= t) ++i;
      const double fraction = (t - log.time_s[i]) / (log.time_s[i + 1] - log.time_s[i]);
      out[k] = values[i] + std::clamp(fraction, 0.0, 1.0) * (values[i + 1] - values[i]);
    }
  }
  return uniform;
}

AccelSpectrum ComputeAccelSpectrum(const AccelLog& log, AccelAxis axis) {
  AccelSpectrum spectrum;
  spectrum.axis = axis;
  spectrum.samples = ToUniformGrid(log);
  const double rate = spectrum.samples.sample_rate_hz;
  const int segment = WelchSegmentLength(rate);
  for (int a = 0; a < 3; ++a) {
    if (axis != AccelAxis::kAll && static_cast<int>(axis) != a) continue;
    const Psd psd = WelchPsd(spectrum.samples.accel_mm_s2[a], rate, segment);
    if (spectrum.full.density.empty()) {
      spectrum.full = psd;
    } else {
      for (std::size_t k = 0; k < psd.density.size(); ++k) spectrum.full.density[k] += psd.density[k];
    }
  }
  for (std::size_t k = 0; k < spectrum.full.frequency_hz.size(); ++k) {
    const double f = spectrum.full.frequency_hz[k];
    if (f >= kFitMinHz && f <= kFitMaxHz) {
      spectrum.frequency_hz.push_back(f);
      spectrum.psd.push_back(spectrum.full.density[k]);
    }
  }
  // Nothing to fit: constant accelerations (all zero), or values so large that their
  // squares overflow.
  const double peak = *std::max_element(spectrum.psd.begin(), spectrum.psd.end());
  const std::string column = axis == AccelAxis::kAll ? "accel_x" : kAccelColumns[static_cast<int>(axis)];
  bool finite = true;
  for (const double value : spectrum.psd) finite = finite && std::isfinite(value);
  if (!finite || !(peak > 0.0)) {
    throw ConfigError(log.file, log.line.front(), 1, column,
                      std::string(finite ? "no vibration in " : "accelerations too large for a PSD in ") +
                          FormatNumber(kFitMinHz) + "-" + FormatNumber(kFitMaxHz) + " Hz on axis " +
                          AccelAxisName(axis) + (finite ? " (the accelerations are constant, or too small to square)" : " (it overflows)") +
                          ": nothing to fit a shaper to");
  }
  return spectrum;
}

}  // namespace shapebench::bench
