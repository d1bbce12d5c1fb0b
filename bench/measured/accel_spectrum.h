// From an accelerometer log to the spectrum a shaper is fitted to: the samples on a
// uniform time grid, the Welch PSD of the chosen axis (or the sum of the three), cut to
// the fit band 5-200 Hz (Klipper's MIN_FREQ and MAX_FREQ).
//
// The sample rate is (N - 1) / (t_last - t_first) (Klipper takes N / (t_last - t_first),
// 1/N high). The uniform grid is t_first + k / rate, k = 0 .. N - 1. When every time
// stamp lies within 1% of a sample period of its grid point (a steady logger; Klipper's
// six decimals round by 0.5 us, 0.16% of a period at 3.2 kHz) the samples are used as
// they are; otherwise (jitter, a gap of dropped samples) each axis is resampled onto the
// grid by linear interpolation between the two samples around each grid time: its
// response, sinc^2(f / rate), costs 1.5% at 200 Hz for 3.2 kHz.
#pragma once

#include <string>
#include <vector>

#include "bench/measured/accel_log.h"
#include "bench/measured/welch_psd.h"

namespace shapebench::bench {

// The fit band (Klipper's shaper_calibrate.py MIN_FREQ, MAX_FREQ) and what it asks of
// the sampling: the PSD must reach 200 Hz, so the rate must be at least 400 Hz.
inline constexpr double kFitMinHz = 5.0;
inline constexpr double kFitMaxHz = 200.0;

// Which PSD: one axis or the sum of the three (Klipper's default, `all`).
enum class AccelAxis { kX, kY, kZ, kAll };
// "x", "y", "z", "all"
const char* AccelAxisName(AccelAxis axis);

struct UniformAccel {
  double sample_rate_hz = 0.0;
  double start_s = 0.0;
  std::array<std::vector<double>, 3> accel_mm_s2;
  bool resampled = false;      // the time stamps were off the grid: interpolated
  double max_offset_s = 0.0;   // the largest |t_i - grid_i|
};

// The log on its uniform grid. Throws ConfigError at the last sample's time field when
// the record is too slow (rate below 2 x 200 Hz) or too short for one Welch segment
// (N <= WelchSegmentLength(rate): Klipper's limit), each naming what it needs.
UniformAccel ToUniformGrid(const AccelLog& log);

struct AccelSpectrum {
  AccelAxis axis = AccelAxis::kAll;
  UniformAccel samples;
  Psd full;                          // 0 .. rate/2
  std::vector<double> frequency_hz;  // the bins in [5, 200] Hz
  std::vector<double> psd;           // (mm/s^2)^2/Hz at those bins
};

AccelSpectrum ComputeAccelSpectrum(const AccelLog& log, AccelAxis axis);

}  // namespace shapebench::bench
