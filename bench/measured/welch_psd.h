// Power spectral density by Welch's method (FFTW), as Klipper's shaper_calibrate.py
// computes it from an accelerometer log, with a Hann window instead of its Kaiser(6):
// segments of M samples overlapping by M/2 (n = (N - M/2) / (M/2) of them, the samples
// after the last whole segment left out), each segment's mean removed, then multiplied
// by the periodic Hann window w[n] = (1 - cos(2 pi n / M)) / 2; |FFT|^2 / (fs sum w^2),
// doubled except at 0 Hz and fs/2 (one-sided), averaged over the segments. The density
// is in (unit)^2/Hz, at the bins k fs / M, k = 0 .. M/2.
#pragma once

#include <vector>

namespace shapebench::bench {

// Klipper's segment length: the power of two that holds 0.5 s of samples
// (1 << bit_length(int(fs * 0.5 - 1))): 2048 samples at 3200 Hz, bins 1.5625 Hz apart;
// the resolution is between 1 and 2 Hz at any rate. At least 2.
int WelchSegmentLength(double sample_rate_hz);

struct Psd {
  double sample_rate_hz = 0.0;
  int segment_samples = 0;  // M
  int segments = 0;         // the number averaged
  std::vector<double> frequency_hz;  // k fs / M
  std::vector<double> density;       // per bin
};

// The PSD of `samples` (uniformly sampled at `sample_rate_hz`) with segments of
// `segment_samples` (even, >= 2). Throws std::invalid_argument when there are not more
// samples than one segment (Klipper's limit: N > M).
Psd WelchPsd(const std::vector<double>& samples, double sample_rate_hz, int segment_samples);

// The same with `window` (its size the segment length M) in place of Hann: Klipper's own
// PSD uses numpy's kaiser(M, 6) (bench/measured/klipper_psd.h).
Psd WelchPsdWindowed(const std::vector<double>& samples, double sample_rate_hz, const std::vector<double>& window);

}  // namespace shapebench::bench
