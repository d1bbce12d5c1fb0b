// `shapebench recommend`: Klipper's section of the table and JSON (see recommend_report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench/output/recommend_report.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

std::string KlipperPercent(double fraction) { return FormatFixed(100.0 * fraction, 2) + " %"; }

std::string KlipperRuleText() {
  return std::string("Klipper's calibrate_shaper (Klipper3d/klipper ") + std::string(kKlipperCommit).substr(0, 9) +
         "): the lowest score smoothing x (v^1.5 + 0.2 v + 0.01) among frequencies within 1.1 x the least vibration "
         "+ 0.0005, then among shapers";
}

double DurationS(const KlipperShaper& shaper) { return shaper.time_s.back() - shaper.time_s.front(); }

nlohmann::ordered_json KlipperResultJson(const KlipperShaperResult& r) {
  nlohmann::ordered_json json;
  json["method"] = r.name;
  json["frequency_hz"] = r.frequency_hz;
  json["remaining_vibration"] = r.remaining_vibration;
  json["duration_s"] = DurationS(r.shaper);
  // A convolved shaper lengthens each acc/dec phase, and so the move, by its duration.
  json["added_time_s"] = DurationS(r.shaper);
  json["smoothing_m"] = r.smoothing_mm * 1e-3;
  json["smoothing_mm"] = r.smoothing_mm;
  json["score"] = r.score;
  json["max_accel_mm_s2"] = r.max_accel_mm_s2;
  json["rule"] = "klipper";
  return json;
}

std::string PsdText(const KlipperSpectrum& s) {
  if (s.source != "accelerometer log") {
    return s.source + ", " + std::to_string(s.datasets.size()) + " data set(s) of " +
           std::to_string(s.datasets[0].frequency_hz.size()) + " bins" +
           (s.normalized_in_file ? ", normalised as read" : ", normalised here");
  }
  return "Welch, Kaiser(6) window, " + std::to_string(s.segment_samples) + "-sample segments (" +
         FormatNumber(s.sample_rate_hz / s.segment_samples) + " Hz bins), 50% overlap, " +
         std::to_string(s.segments) + " segments at N/T = " + FormatNumber(s.sample_rate_hz) +
         " Hz, samples as logged; PSD / (f + 0.1 Hz), damped below 10 Hz";
}

}  // namespace

controller::PatternConfig KlipperPattern(const KlipperShaperResult& result) {
  controller::PatternConfig pattern;
  pattern.method = "custom";
  pattern.frequency_hz = result.frequency_hz;
  double sum = 0.0;
  for (const double a : result.shaper.amplitude) sum += a;
  for (std::size_t i = 0; i < result.shaper.time_s.size(); ++i) {
    pattern.impulses.push_back({result.shaper.time_s[i], result.shaper.amplitude[i] / sum});
  }
  return pattern;
}

void PrintKlipperRecommendation(std::ostream& out, const RecommendReport& report) {
  const KlipperFitOptions& o = report.klipper_options;
  out << "klipper    calibrate_shaper at Klipper3d/klipper " << std::string(kKlipperCommit).substr(0, 9) << "; "
      << PsdText(report.klipper_spectrum) << "\n";
  out << "           shapers at damping ratio " << FormatNumber(o.damping_ratio) << "; vibration: the worst at";
  for (const double z : o.test_damping_ratios) out << " " << FormatNumber(z);
  out << "; smoothing at 5000 mm/s^2, scv " << FormatNumber(o.scv_mm_s) << " mm/s";
  if (o.max_smoothing_mm) out << ", at most " << FormatNumber(*o.max_smoothing_mm) << " mm";
  out << "\n\n";
  char line[200];
  std::snprintf(line, sizeof line, "  %-9s %-12s  %-19s  %-12s  %-15s  %s\n", "shaper", "frequency_hz",
                "remaining_vibration", "smoothing_mm", "max_accel_mm_s2", "score");
  out << line;
  for (std::size_t i = 0; i < report.klipper.shapers.size(); ++i) {
    const KlipperShaperResult& r = report.klipper.shapers[i];
    std::snprintf(line, sizeof line, "%s %-9s %-12.1f  %-19s  %-12.3f  %-15.0f  %.4g\n",
                  i == report.klipper.recommended ? "*" : " ", r.name.c_str(), r.frequency_hz,
                  KlipperPercent(r.remaining_vibration).c_str(), r.smoothing_mm, std::round(r.max_accel_mm_s2 / 100.0) * 100.0,
                  r.score);
    out << line;
  }
  const KlipperShaperResult& best = report.klipper_recommended();
  out << "\nrecommended: " << best.name << " at " << FormatNumber(std::round(best.frequency_hz * 10.0) / 10.0)
      << " Hz (remaining vibration " << KlipperPercent(best.remaining_vibration) << ", smoothing "
      << FormatFixed(best.smoothing_mm, 3) << " mm): " << KlipperRuleText() << "\n";
}

void AddKlipperJson(const RecommendReport& report, nlohmann::ordered_json* json) {
  const KlipperSpectrum& s = report.klipper_spectrum;
  const KlipperFitOptions& o = report.klipper_options;
  nlohmann::ordered_json psd = {{"source", s.source}, {"datasets", s.datasets.size()},
                                 {"normalized_in_file", s.normalized_in_file}};
  if (s.source == "accelerometer log") {
    psd["window"] = "kaiser(6)";
    psd["sample_rate_hz"] = s.sample_rate_hz;
    psd["segment_samples"] = s.segment_samples;
    psd["segments"] = s.segments;
    psd["resolution_hz"] = s.sample_rate_hz / s.segment_samples;
  }
  nlohmann::ordered_json options = {{"damping_ratio", o.damping_ratio},
                                    {"test_damping_ratios", o.test_damping_ratios},
                                    {"scv_mm_s", o.scv_mm_s},
                                    {"smoothing_accel_mm_s2", 5000.0},
                                    {"max_freq_hz", o.max_freq_hz}};
  options["max_smoothing_mm"] = o.max_smoothing_mm ? nlohmann::ordered_json(*o.max_smoothing_mm) : nullptr;
  (*json)["klipper"] = {{"commit", kKlipperCommit}, {"psd", psd}, {"options", options}};
  nlohmann::ordered_json shapers = nlohmann::ordered_json::array();
  for (const KlipperShaperResult& r : report.klipper.shapers) shapers.push_back(KlipperResultJson(r));
  (*json)["shapers"] = shapers;
  nlohmann::ordered_json recommended = KlipperResultJson(report.klipper_recommended());
  recommended["rule"] = KlipperRuleText();
  (*json)["recommended"] = recommended;
}

}  // namespace shapebench::bench
