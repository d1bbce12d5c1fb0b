// The shaper fit and recommendation of `shapebench recommend` (see the header).
#include "bench/measured/shaper_fit.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/linear_acc_dec.h"

namespace shapebench::bench {
namespace {

// What the vibration may exceed the lowest by and still count as as good (Klipper's
// fit_shaper: vibrs < best * 1.1 + 0.0005).
constexpr double kToleranceFactor = 1.1;
constexpr double kToleranceFloor = 0.0005;
// The reference move of added_time_s cruises this long at the feed when unshaped.
constexpr double kReferenceCruiseS = 1.0;

// The keys of entry.parameters as the fit set them.
std::string ParameterText(const controller::ShaperEntry& entry, const controller::PatternConfig& p) {
  std::string text;
  for (const std::string& key : entry.parameters) {
    std::string item;
    if (key == "k1") item = "k1=" + FormatNumber(p.k1);
    if (key == "t1_s") item = "t1=T/12";
    if (key == "vibration_tolerance") item = "V=" + FormatNumber(p.vibration_tolerance);
    if (key == "impulse_count") item = "n=" + std::to_string(p.impulse_count);
    if (key == "impulse_spacing_periods") item = "s=" + FormatNumber(p.impulse_spacing_periods);
    if (!item.empty()) text += (text.empty() ? "" : " ") + item;
  }
  return text;
}

// The method's impulses at `scan`'s frequencies. Every built-in design is a sequence of
// phases (w t), so a design at one frequency scaled in time is the design at any other;
// a method checked to scale so (designs at 10 and 37 Hz agree scaled, to 1e-12) is
// designed once, any other at every frequency. Throws ValidationError when a design fails.
std::vector<std::vector<controller::Impulse>> ScanDesigns(const controller::ShaperEntry& entry,
                                                          const std::vector<double>& scan, double damping) {
  auto design = [&](double f) {
    const controller::PatternConfig pattern = FitPattern(entry, f, damping);
    pattern.validate();
    return controller::ShaperImpulses(pattern);
  };
  const std::vector<controller::Impulse> low = design(10.0);
  const std::vector<controller::Impulse> high = design(37.0);
  bool scales = low.size() == high.size();
  for (std::size_t j = 0; scales && j < low.size(); ++j) {
    scales = std::abs(low[j].amplitude - high[j].amplitude) <= 1e-12 &&
             std::abs(low[j].time_s * 10.0 - high[j].time_s * 37.0) <= 1e-12 * (1.0 + low[j].time_s * 10.0);
  }
  std::vector<std::vector<controller::Impulse>> designs;
  designs.reserve(scan.size());
  for (const double f : scan) {
    if (!scales) {
      designs.push_back(design(f));
      continue;
    }
    std::vector<controller::Impulse> scaled = low;
    for (controller::Impulse& impulse : scaled) impulse.time_s *= 10.0 / f;
    designs.push_back(std::move(scaled));
  }
  return designs;
}

// One method's scan; nullopt (and *reason) when its design fails.
std::optional<ShaperFit> FitMethod(const controller::ShaperEntry& entry, const std::vector<double>& frequency_hz,
                                   const std::vector<double>& psd, const ShaperFitOptions& options,
                                   std::string* reason) {
  const std::vector<double> scan = ScanFrequencies(options);
  std::vector<double> scores;
  scores.reserve(scan.size());
  try {
    for (const std::vector<controller::Impulse>& impulses : ScanDesigns(entry, scan, options.design_damping_ratio)) {
      scores.push_back(RemainingVibration(impulses, frequency_hz, psd, options.test_damping_ratios));
    }
  } catch (const ValidationError& error) {
    *reason = error.field() + ": " + error.message();
    return std::nullopt;
  }
  ShaperFit fit;
  fit.method = entry.key;
  fit.frequency_hz = scan[ChosenIndex(scores)];
  fit.pattern = FitPattern(entry, fit.frequency_hz, options.design_damping_ratio);
  fit.parameters = ParameterText(entry, fit.pattern);
  const std::vector<controller::Impulse> impulses = controller::ShaperImpulses(fit.pattern);
  fit.remaining_vibration =
      RemainingVibration(impulses, frequency_hz, psd, options.test_damping_ratios, &fit.vibration);
  fit.duration_s = controller::ShaperDuration(impulses);
  fit.added_time_s = AddedMotionTimeS(fit.pattern, options.feed_mm_min, options.accel_mm_s2);
  fit.smoothing_m = CircleContourErrorM(impulses, options.feed_mm_min, options.accel_mm_s2);
  return fit;
}

}  // namespace

void ShaperFitOptions::validate() const {
  if (!(design_damping_ratio >= 0.0 && design_damping_ratio < 1.0)) {
    throw ValidationError("--damping-ratio", "must be in [0, 1) (got " + FormatNumber(design_damping_ratio) + ")");
  }
  // Bounded as the scenario's feeds are (at most 1e6 mm/min), and the acceleration from
  // 1 mm/s^2 to 1e7 mm/s^2 (1000 g): beyond them the smoothing read 1e285 m or inf.
  if (!(feed_mm_min >= 1.0 && feed_mm_min <= 1.0e6)) {
    throw ValidationError("--feed-mm-min", "must be a finite feed > 0 mm/min, from 1 to 1e6 (got " +
                                               FormatNumber(feed_mm_min) + ")");
  }
  if (!(accel_mm_s2 >= 1.0 && accel_mm_s2 <= 1.0e7)) {
    throw ValidationError("--accel-mm-s2", "must be a finite acceleration > 0 mm/s^2, from 1 to 1e7 (got " +
                                               FormatNumber(accel_mm_s2) + ")");
  }
}

double RemainingVibration(const std::vector<controller::Impulse>& impulses, const std::vector<double>& frequency_hz,
                          const std::vector<double>& psd, const std::vector<double>& test_damping_ratios,
                          std::vector<double>* worst) {
  const double threshold = *std::max_element(psd.begin(), psd.end()) / 20.0;
  double all = 0.0;
  for (const double p : psd) all += std::max(p - threshold, 0.0);
  if (worst) worst->assign(psd.size(), 0.0);
  double remaining = 0.0;
  for (const double zeta : test_damping_ratios) {
    double left = 0.0;
    for (std::size_t k = 0; k < psd.size(); ++k) {
      const double v = controller::ResidualVibration(impulses, frequency_hz[k], zeta);
      left += std::max(v * psd[k] - threshold, 0.0);
      if (worst) (*worst)[k] = std::max((*worst)[k], v);
    }
    remaining = std::max(remaining, left / all);
  }
  return remaining;
}

controller::PatternConfig FitPattern(const controller::ShaperEntry& entry, double frequency_hz,
                                     double design_damping_ratio) {
  controller::PatternConfig pattern;
  pattern.method = entry.key;
  pattern.frequency_hz = frequency_hz;
  // The patent designs methods 1-4 for an undamped mode (PatternConfig refuses a damping).
  if (entry.kind == controller::ShaperKind::kImpulse) pattern.design_damping_ratio = design_damping_ratio;
  pattern.t1_s = 1.0 / (12.0 * frequency_hz);  // method 4: the middle of [0, T/6]
  return pattern;
}

double AddedMotionTimeS(const controller::PatternConfig& pattern, double feed_mm_min, double accel_mm_s2) {
  const double v = feed_mm_min / 60000.0;
  const double a = accel_mm_s2 * 1e-3;
  const double distance_m = v * v / a + v * kReferenceCruiseS;
  controller::PatternConfig unshaped;
  unshaped.method = controller::kNoShaping;
  const double shaped_s =
      controller::PlanRestToRest(distance_m, v, a, controller::MakeStepPattern(pattern)).Duration();
  const double plain_s =
      controller::PlanRestToRest(distance_m, v, a, controller::MakeStepPattern(unshaped)).Duration();
  return shaped_s - plain_s;
}

double CircleContourErrorM(const std::vector<controller::Impulse>& impulses, double feed_mm_min,
                           double accel_mm_s2) {
  const double v = feed_mm_min / 60000.0;
  const double a = accel_mm_s2 * 1e-3;
  const double radius_m = v * v / a;
  const double w = v / radius_m;  // the circle's angular rate, a / v
  std::complex<double> response = 0.0;
  for (const controller::Impulse& impulse : impulses) response += impulse.amplitude * std::polar(1.0, -w * impulse.time_s);
  return std::abs(radius_m * (1.0 - std::abs(response)));
}

std::vector<double> ScanFrequencies(const ShaperFitOptions& options) {
  std::vector<double> scan;
  for (long k = 0;; ++k) {
    const double f = std::round((options.from_hz + static_cast<double>(k) * options.step_hz) * 1e9) / 1e9;
    if (f > options.to_hz + 1e-9) break;
    scan.push_back(f);
  }
  return scan;
}

std::size_t ChosenIndex(const std::vector<double>& scores) {
  const double lowest = *std::min_element(scores.begin(), scores.end());
  std::size_t best_start = 0;
  std::size_t best_length = 0;
  for (std::size_t k = 0; k < scores.size();) {
    if (!(scores[k] <= lowest + 1e-12)) {
      ++k;
      continue;
    }
    std::size_t end = k;
    while (end < scores.size() && scores[end] <= lowest + 1e-12) ++end;
    if (end - k > best_length) {
      best_start = k;
      best_length = end - k;
    }
    k = end;
  }
  return best_start + (best_length - 1) / 2;
}

ShaperRecommendation RecommendShapers(const std::vector<double>& frequency_hz, const std::vector<double>& psd,
                                      const ShaperFitOptions& options) {
  options.validate();
  ShaperRecommendation result;
  for (const controller::ShaperEntry* entry : controller::Shapers()) {
    if (entry->kind == controller::ShaperKind::kNone) continue;
    if (entry->kind == controller::ShaperKind::kCustom) {
      result.skipped.push_back({entry->key, "its impulses are given, not designed for a frequency"});
      continue;
    }
    std::string reason;
    std::optional<ShaperFit> fit = FitMethod(*entry, frequency_hz, psd, options, &reason);
    if (fit) {
      result.fits.push_back(std::move(*fit));
    } else {
      result.skipped.push_back({entry->key, reason});
    }
  }
  if (result.fits.empty()) throw std::runtime_error("recommend: no method of the shaper registry could be fitted");
  double lowest = result.fits.front().remaining_vibration;
  for (const ShaperFit& fit : result.fits) lowest = std::min(lowest, fit.remaining_vibration);
  result.tolerance = kToleranceFactor * lowest + kToleranceFloor;
  bool found = false;
  for (std::size_t i = 0; i < result.fits.size(); ++i) {
    const ShaperFit& fit = result.fits[i];
    if (fit.remaining_vibration > result.tolerance) continue;
    if (!found || fit.smoothing_m < result.fits[result.recommended].smoothing_m) result.recommended = i;
    found = true;
  }
  return result;
}

}  // namespace shapebench::bench
