// Klipper's spectrum of an accelerometer log, as calibrate_shaper computes it at the
// pinned commit (kKlipperCommit, bench/measured/klipper_calibrate.h; the algorithm read
// from klippy/extras/shaper_calibrate.py, calc_freq_response, _psd and
// normalize_to_frequencies; the code is shapebench's own):
// - the sample rate is N / (t_last - t_first) and the samples are used as logged, in
//   order, without resampling (bench/measured/accel_spectrum.h resamples for
//   shapebench's own view);
// - Welch: segments of M = 1 << bit_length(int(rate * 0.5 - 1)) samples overlapping by
//   M / 2, each segment's mean removed, numpy's kaiser(M, 6) window (symmetric: I0(6
//   sqrt(1 - (2n / (M - 1) - 1)^2)) / I0(6)), one-sided density (bench/measured/welch_psd.h);
// - the PSD of each axis and their sum, at the bins k rate / M from 0 Hz;
// - normalize_to_frequencies: every PSD divided by (f + 0.1 Hz), and below 10 Hz (twice
//   MIN_FREQ) multiplied by exp(1 - (10 / (f + 0.1))^2): a resonance test's excitation
//   tilts the raw spectrum toward its low end, which would otherwise dominate the fit.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "bench/measured/accel_log.h"
#include "bench/measured/accel_spectrum.h"

namespace shapebench::bench {

// One of Klipper's data sets (CalibrationData): bins from 0 Hz, the sum of the axes'
// PSDs and each axis's (empty when a file does not carry them).
struct KlipperPsd {
  std::string name;
  std::vector<double> frequency_hz;
  std::vector<double> psd_sum;
  std::array<std::vector<double>, 3> psd_axis;
};

struct KlipperSpectrum {
  std::string source;  // "accelerometer log", "resonances csv" or "calibration_data csv"
  std::vector<KlipperPsd> datasets;  // one from a log; a calibration_data file may hold several
  bool normalized_in_file = false;  // calibration_data: read as normalised; else normalised here
  // From a log only (0 otherwise):
  double sample_rate_hz = 0.0;  // N / (t_last - t_first)
  int segment_samples = 0;
  int segments = 0;
};

// numpy.kaiser(m, beta).
std::vector<double> KaiserWindow(int m, double beta);

// Klipper's spectrum of `log`, normalised. Throws ConfigError at the last sample's time
// field when the log has no more samples than one segment (Klipper's "Internal error").
KlipperSpectrum KlipperLogSpectrum(const AccelLog& log);

// normalize_to_frequencies on every PSD of `psd` (above).
void NormalizeToFrequencies(KlipperPsd* psd);

// The PSD the fit reads: the sum for `all` (what Klipper fits), one axis's otherwise.
// Throws ConfigError naming `file` when the data set holds no per-axis PSDs.
const std::vector<double>& KlipperFitPsd(const KlipperPsd& psd, AccelAxis axis, const std::string& file);

}  // namespace shapebench::bench
