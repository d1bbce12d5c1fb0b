// `shapebench recommend`'s fit: every method of the shaper registry scanned over its
// design frequency against an accelerometer log's PSD, scored by the vibration it would
// leave as Klipper's shaper_calibrate.py scores it (fit_shaper,
// _estimate_remaining_vibrations, _estimate_shaper), and one recommended.
//
// Remaining vibration of a shaper (impulses A_j at t_j, designed for frequency f_s):
//   V_zeta(f) = ResidualVibration(impulses, f, zeta)  (controller/impulse.h: Klipper's
//              _estimate_shaper, the standard formula), for each test damping ratio zeta
//              in 0.075, 0.1, 0.15 (Klipper's TEST_DAMPING_RATIOS: the machine's damping
//              is not known);
//   R_zeta = sum_k max(V_zeta(f_k) P_k - P_max / 20, 0) / sum_k max(P_k - P_max / 20, 0)
//            over the PSD bins f_k in [5, 200] Hz, P_max the largest of them (a shaper
//            cannot reduce vibration more than 20 times: what is below 1/20 of the peak
//            is not counted, SHAPER_VIBRATION_REDUCTION);
//   remaining vibration = max over zeta of R_zeta (a fraction: 0 none left, 1 all).
// Klipper also divides the PSD by (f + 0.1 Hz) and damps it below 10 Hz before fitting
// (normalize_to_frequencies); shapebench fits the PSD as measured, cut to 5-200 Hz.
//
// The design: a library shaper (kImpulse) at `design_damping_ratio` (--damping-ratio,
// Klipper's 0.1), the patent's methods 1-4 undamped, as the patent designs them (method
// 3 with its default k1, method 4 with t1 = T/12, the middle of para. 45's [0, T/6]);
// every other key at its default. `none` and `custom` (impulses given, no design
// frequency) are not fitted; a method whose design fails (a damping beyond its branch) is
// skipped with the reason.
//
// The scan: design frequencies from 5 to 200 Hz in 0.2 Hz steps (976; Klipper's step,
// its range for every method). The frequency chosen minimises the remaining vibration;
// when several do (a plateau at 0: every bin's V P under the threshold), the middle of
// the longest run of them, the design frequency that can drift farthest either way
// before vibration counts again (Klipper takes the highest).
//
// Per method, at the chosen frequency:
//   duration_s   the impulse sequence's duration (its last impulse);
//   added_time_s what the pattern adds to a rest-to-rest move that reaches the feed and
//                cruises 1 s at it (controller/linear_acc_dec.h PlanRestToRest, mode
//                both, with and without the pattern). A library shaper convolves each
//                acc/dec phase: the phase grows by the duration D, the cruise shrinks by
//                it, the move by D. The patent's two steps run at the phase's start and,
//                reversed, at its end (JP2551868B2 para. 49): the phase grows by twice
//                their mean time mu = sum A_j t_j, the move by 2 mu, which is D for the
//                symmetric methods 1-3 and less for method 4;
//   smoothing_m  the contour error of per-axis shaping (a post-interpolation profile
//                table, Klipper's input shaper) on the tightest circle the feed allows at
//                the acceleration: radius r = v^2 / a (v = --feed-mm-min, a =
//                --accel-mm-s2), each axis filtered by H(s) = sum A_j e^{-s t_j}, the
//                circle's radius becomes r |H(i v / r)|: r (1 - |H(i v / r)|), absolute.
//                For small v / r times the duration it is a sigma^2 / 2 (sigma^2 the
//                impulses' variance in time), Klipper's 180-degree offset of
//                _get_shaper_smoothing; Klipper's smoothing takes the larger of that and
//                a 90-degree corner's offset, which adds a square-corner-velocity term.
//
// Recommendation (Klipper's tolerance of fit_shaper): of the methods whose remaining
// vibration is at most 1.1 x the lowest + 0.0005, the one of least smoothing (equal
// smoothing: the first in registry order).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "controller/impulse.h"
#include "controller/pattern_config.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {

struct ShaperFitOptions {
  double design_damping_ratio = 0.1;  // --damping-ratio
  std::vector<double> test_damping_ratios = {0.075, 0.1, 0.15};
  double from_hz = 5.0;
  double to_hz = 200.0;
  double step_hz = 0.2;
  double feed_mm_min = 6000.0;  // --feed-mm-min
  double accel_mm_s2 = 5000.0;  // --accel-mm-s2 (Klipper's smoothing uses 5000 mm/s^2)
  // Throws ValidationError naming the option: "--damping-ratio", "--feed-mm-min" or
  // "--accel-mm-s2".
  void validate() const;
};

// Klipper's remaining vibration (above) of `impulses` against the PSD `psd` at the bins
// `frequency_hz`. `worst`, when given, receives V(f_k) worst over the test dampings.
double RemainingVibration(const std::vector<controller::Impulse>& impulses,
                          const std::vector<double>& frequency_hz, const std::vector<double>& psd,
                          const std::vector<double>& test_damping_ratios, std::vector<double>* worst = nullptr);

// The pattern `entry` is fitted with at `frequency_hz` (above); not yet validated.
controller::PatternConfig FitPattern(const controller::ShaperEntry& entry, double frequency_hz,
                                     double design_damping_ratio);

// added_time_s and smoothing_m (above), in s and m; feed in mm/min, acceleration in mm/s^2.
double AddedMotionTimeS(const controller::PatternConfig& pattern, double feed_mm_min, double accel_mm_s2);
double CircleContourErrorM(const std::vector<controller::Impulse>& impulses, double feed_mm_min,
                           double accel_mm_s2);

// The design frequencies scanned: from_hz + k step_hz up to to_hz, rounded to 1e-9 Hz.
std::vector<double> ScanFrequencies(const ShaperFitOptions& options);

// The index chosen from a scan's scores (above): the minimum, the middle of the longest
// run of equal minima (within 1e-12).
std::size_t ChosenIndex(const std::vector<double>& scores);

struct ShaperFit {
  std::string method;      // the registry key
  std::string parameters;  // the keys the design read besides frequency and damping, "k1=0.675"
  controller::PatternConfig pattern;  // as fitted, at frequency_hz
  double frequency_hz = 0.0;
  double remaining_vibration = 0.0;
  double duration_s = 0.0;
  double added_time_s = 0.0;
  double smoothing_m = 0.0;
  std::vector<double> vibration;  // V at the PSD's bins, worst over the test dampings
};

struct SkippedShaper {
  std::string method;
  std::string reason;
};

struct ShaperRecommendation {
  std::vector<ShaperFit> fits;  // registry order
  std::vector<SkippedShaper> skipped;
  std::size_t recommended = 0;   // into fits
  double tolerance = 0.0;        // 1.1 x the lowest remaining vibration + 0.0005
};

// Every method fitted and one recommended; throws ValidationError for bad options and
// std::runtime_error when no method could be fitted.
ShaperRecommendation RecommendShapers(const std::vector<double>& frequency_hz, const std::vector<double>& psd,
                                      const ShaperFitOptions& options);

}  // namespace shapebench::bench
