// Klipper's calibrate_shaper rule (`shapebench recommend`'s default), reproduced from the
// algorithm of klippy/extras/shaper_calibrate.py and shaper_defs.py at the pinned commit
// kKlipperCommit of Klipper3d/klipper (GPLv3: read, not copied; this code is shapebench's).
//
// Candidates (AUTOTUNE_SHAPERS): zv, mzv, ei, 2hump_ei, 3hump_ei, as shaper_defs defines
// them at the design damping (--damping-ratio, Klipper's --damping_ratio, default 0.1):
// zv and ei in closed form (ei for a 5% vibration tolerance), mzv the generalised 3-impulse
// form of duration 0.75 damped period (its amplitudes solved by least squares for zeros
// at 1 and 1.5 times the design frequency, then damped), 2hump_ei and 3hump_ei by the
// cubic-in-damping expansions of their times and amplitudes.
//
// Per candidate (fit_shaper): design frequencies from its min_freq (21, 23, 29, 39, 48 Hz)
// to below 150 Hz in steps of 0.2 Hz (numpy.arange), walked from the top. At each:
//   vibrations = the worst over the test damping ratios 0.075, 0.1, 0.15 and over the
//     data sets of sum_k max(V(f_k) P_k - P_max / 20, 0) / sum_k max(P_k - P_max / 20, 0),
//     over the bins f_k <= 200 Hz (from 0 Hz), P the normalised PSD (klipper_psd.h);
//   smoothing (mm) = the larger of the 90-degree corner's offset sqrt(2) sum_{t_i >= ts}
//     A_i (scv + accel / 2 (t_i - ts)) (t_i - ts) and the 180-degree one
//     sum A_i accel / 2 (t_i - ts)^2 (amplitudes normalised, ts their mean time), at
//     accel 5000 mm/s^2 and scv 5 mm/s;
//   score = smoothing (v^1.5 + 0.2 v + 0.01).
// best: the lowest vibrations (ties: the higher frequency); selected: walking up from the
// lowest frequency, any whose vibrations are below 1.1 x best + 0.0005 and whose score is
// below the selected one's. With --max-smoothing the walk stops at the first frequency
// (from the top) whose smoothing exceeds it once a result exists, and then the best so
// far is the candidate's result, not selected (as Klipper returns early).
//
// Among candidates (find_best_shaper), in order: one replaces the best when its score is
// below best / 1.2, or below best / 1.05 with smoothing below best / 1.1; then any of its
// scanned frequencies with both fewer vibrations and less smoothing than the best
// replaces it (and the candidate's reported result). A best zv yields to the first
// candidate whose vibrations x 1.1 are below zv's.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace shapebench::bench {

inline constexpr const char* kKlipperCommit = "84104bbbd7625d28b4eaaad83f4562972460ecd9";

struct KlipperShaper {
  std::vector<double> amplitude;  // not normalised: Klipper divides by their sum where it matters
  std::vector<double> time_s;
};

// zv, mzv, ei, 2hump_ei, 3hump_ei.
const std::vector<std::string>& KlipperAutotuneShapers();
double KlipperShaperMinFreqHz(const std::string& name);
// Throws std::invalid_argument for an unknown name.
KlipperShaper KlipperInitShaper(const std::string& name, double frequency_hz, double damping_ratio);

// |residual| of the shaper at each frequency for a mode of `damping_ratio` (Klipper's
// _estimate_shaper), 1 at 0 Hz.
std::vector<double> KlipperShaperResponse(const KlipperShaper& shaper, double damping_ratio,
                                          const std::vector<double>& frequency_hz);
double KlipperSmoothingMm(const KlipperShaper& shaper, double accel_mm_s2, double scv_mm_s);
// The acceleration at which the smoothing is 0.12 mm (find_shaper_max_accel's bisection).
double KlipperMaxAccelMmS2(const KlipperShaper& shaper, double scv_mm_s);

struct KlipperFitOptions {
  double damping_ratio = 0.1;  // --damping-ratio
  double scv_mm_s = 5.0;
  std::optional<double> max_smoothing_mm;  // --max-smoothing
  std::vector<double> test_damping_ratios = {0.075, 0.1, 0.15};
  double max_freq_hz = 200.0;
  // Throws ValidationError naming "--damping-ratio" (in (0, 1): Klipper reads 0 as its
  // default) or "--max-smoothing" (>= 0.05 mm, as Klipper's script requires).
  void validate() const;
};

// One data set the fit reads: bins and the normalised PSD.
struct KlipperFitInput {
  std::vector<double> frequency_hz;
  std::vector<double> psd;
};

struct KlipperShaperResult {
  std::string name;
  double frequency_hz = 0.0;
  double remaining_vibration = 0.0;  // a fraction
  double smoothing_mm = 0.0;
  double score = 0.0;
  double max_accel_mm_s2 = 0.0;
  KlipperShaper shaper;
  std::vector<double> vibration;  // the response worst over the test dampings, first data set's bins <= max
};

struct KlipperRecommendation {
  std::vector<KlipperShaperResult> shapers;  // candidate order
  std::size_t recommended = 0;
};

// fit_shaper for one candidate: the selected result (above).
KlipperShaperResult KlipperFitShaper(const std::string& name, const std::vector<KlipperFitInput>& data,
                                     const KlipperFitOptions& options, std::vector<KlipperShaperResult>* scanned);

// find_best_shaper over the candidates. Throws ValidationError for bad options and
// std::runtime_error when no candidate could be fitted.
KlipperRecommendation KlipperFindBestShaper(const std::vector<KlipperFitInput>& data, const KlipperFitOptions& options);

}  // namespace shapebench::bench
