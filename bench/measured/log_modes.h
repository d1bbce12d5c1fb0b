// The modes `recommend --validate` puts in place of a scenario's machine: found as peaks
// of the log's PSD (bench/measured/psd_peaks.h, at Klipper's resolution), then each
// measured by a fit of the modal model to a finer spectrum (bench/measured/modal_psd_fit.h),
// with one standard deviation of its frequency and damping ratio.
//
// The spectrum of the fit: the periodogram of the whole log (the axis chosen, or the sum
// of the three), rectangular window, mean removed: its resolution rate / M is about
// 1 / the log's length (M the largest even number below the samples whose prime factors
// are at most 7, for the FFT), and its bins are independent, each exponentially
// distributed about its expected value. `--resolution-hz R` coarsens it: Welch segments
// of M = rate / R samples (even), rectangular, half overlapping, averaged (each bin's
// relative variance (1 + (K - 1) / (2 K)) / K for K segments: neighbours share a
// quarter of their power). The fit models the window's power kernel (sinc^2, sampled
// twice a bin over +/- 8 bins), so the peaks are not widened by it.
//
// The fit's bins: around each peak found, +/- 2 half-power widths of that peak (its
// width as found, at least 5 Hz each way), inside 5-200 Hz; peaks whose ranges are closer
// than the narrower range's width are fitted together (their responses add as complex
// numbers, not as powers). A Klipper PSD file has no samples: its own bins are fitted
// (no kernel), the uncertainty from the residuals' scatter.
//
// Gains: as before (psd_peaks.h), the share g_i / w_i^2 ~ 2 zeta_i sqrt(P_i) / w_i^2 with
// P_i the peak's height, now with the fitted damping ratio.
#pragma once

#include <string>
#include <vector>

#include "bench/measured/accel_spectrum.h"
#include "bench/measured/psd_peaks.h"

namespace shapebench::bench {

// `--resolution-hz`'s bound: a peak must span a few bins of the fit.
inline constexpr double kMaxModeResolutionHz = 5.0;

struct LogModes {
  std::vector<LogMode> modes;
  std::string spectrum;        // "periodogram", "welch" or "psd file"
  double resolution_hz = 0.0;  // of the fitted bins
  int segment_samples = 0;     // 0 for a PSD file
  int segments = 0;
  std::string uncertainty;     // how the standard deviations were found
  std::vector<std::string> warnings;
};

// The modes of the log's samples (`axis`: one or the sum of the three PSDs), starting
// from the peaks `found`; resolution_hz 0 takes the log's length. Throws ValidationError
// ("--resolution-hz") when resolution_hz is finer than the log allows.
LogModes FitLogModes(const UniformAccel& samples, AccelAxis axis, const std::vector<LogMode>& found,
                     double resolution_hz);

// The modes of a PSD as read (a Klipper PSD file's fit band), from the peaks `found`.
LogModes FitPsdModes(const std::vector<double>& frequency_hz, const std::vector<double>& psd,
                     const std::vector<LogMode>& found);

}  // namespace shapebench::bench
