// What `shapebench recommend FILE.csv` writes (bench/cli/recommend_command.cc): a shaper
// recommended from an accelerometer log by Klipper's calibrate_shaper rule
// (bench/measured/klipper_calibrate.h), shapebench's own fit beside it
// (bench/measured/shaper_fit.h), their table, JSON, PSD CSV and plot, and the optional
// --validate runs (bench/run/recommend_validation.h). docs/measured-data.md#accelerometer-logs.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/measured/accel_spectrum.h"
#include "bench/measured/klipper_calibrate.h"
#include "bench/measured/klipper_psd.h"
#include "bench/measured/log_modes.h"
#include "bench/measured/psd_peaks.h"
#include "bench/measured/shaper_fit.h"
#include "bench/run/recommend_validation.h"

namespace shapebench::bench {

struct RecommendReport {
  std::string file;
  AccelAxis axis = AccelAxis::kAll;
  // Klipper's rule: what `recommended` is.
  KlipperSpectrum klipper_spectrum;
  KlipperFitOptions klipper_options;
  KlipperRecommendation klipper;
  // shapebench's own view: what `recommended_shapebench` is.
  AccelSpectrum spectrum;
  ShaperFitOptions options;
  ShaperRecommendation recommendation;
  // shapebench's registry scored the same way on Klipper's normalised PSD (its first data
  // set, the axis chosen, 5-200 Hz): what `recommended_shapebench_normalised` is.
  ShaperRecommendation normalised;
  std::vector<std::string> warnings;      // printed on stderr and listed in the JSON
  LogModes modes;                         // --validate only
  std::optional<ValidationRuns> validation;
  const KlipperShaperResult& klipper_recommended() const { return klipper.shapers[klipper.recommended]; }
  const ShaperFit& recommended() const { return recommendation.fits[recommendation.recommended]; }
};

// Klipper's recommendation as a pattern (`custom`: its impulses, amplitudes normalised),
// what --validate runs.
controller::PatternConfig KlipperPattern(const KlipperShaperResult& result);

// Klipper's section of the table and of the JSON (bench/output/recommend_klipper_report.cc).
void PrintKlipperRecommendation(std::ostream& out, const RecommendReport& report);
void AddKlipperJson(const RecommendReport& report, nlohmann::ordered_json* json);

// The table: the log, the PSD, one row per method, the recommendation and why, skipped
// methods; then the validation's modes and both runs' metrics side by side.
void PrintRecommendation(std::ostream& out, const RecommendReport& report);

// {"file", "axis", "rule", "klipper": {commit, source, psd, options}, "shapers": [Klipper's
// candidates: {method, frequency_hz, remaining_vibration, duration_s, added_time_s,
// smoothing_m, smoothing_mm, score, max_accel_mm_s2, rule}], "recommended": {the same,
// "rule"}, "shapebench": {"samples", "psd", "design_damping_ratio", "test_damping_ratios",
// "feed_mm_min", "accel_mm_s2", "shapers": [{method, parameters, frequency_hz,
// remaining_vibration, duration_s, added_time_s, smoothing_m, rule}], "skipped"},
// "recommended_shapebench": {the same fields, "rule"}, "shapebench_normalised": {"psd",
// "shapers", "skipped"} and "recommended_shapebench_normalised" (the registry on Klipper's
// normalised PSD), "warnings", and with --validate
// "validate": {scenario, pattern, axis, static_deflection_per_accel_s2, modes: [...], none:
// {metrics}, recommended: {metrics}}}; SI units (Klipper's smoothing also in its mm).
nlohmann::ordered_json RecommendJson(const RecommendReport& report);

// frequency_hz, psd (mm/s^2)^2/Hz, then per method V(f) worst over the test dampings,
// "vibration_<method>": the fit band's bins.
void WriteRecommendCsv(const std::string& path, const RecommendReport& report);

// The PSD over the fit band with each method's V(f) x PSD, the recommended one bold, and
// the threshold P_max / 20 dashed; pngcairo via gnuplot.
void WriteRecommendPlot(const std::string& path_png, const RecommendReport& report);

// The files `recommend --out DIR` writes, in order: recommend.json, psd.csv, recommend.png.
std::vector<std::string> WriteRecommendOutputs(const std::string& out_dir, const RecommendReport& report);

}  // namespace shapebench::bench
