// `shapebench recommend FILE.csv`: a shaper recommended from an accelerometer log
// (bench/measured/shaper_fit.h), its table, JSON, PSD CSV and plot, and the optional
// --validate runs (bench/sim/recommend_validation.h). docs/measured-data.md#accelerometer-logs.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/measured/accel_spectrum.h"
#include "bench/measured/log_modes.h"
#include "bench/measured/shaper_fit.h"
#include "bench/sim/recommend_validation.h"

namespace shapebench::bench {

struct RecommendArgs {
  std::string file;
  std::string axis = "all";  // x, y, z or all
  double damping_ratio = 0.1;
  double feed_mm_min = ShaperFitOptions{}.feed_mm_min;
  double accel_mm_s2 = ShaperFitOptions{}.accel_mm_s2;
  bool json = false;
  std::string out_dir;
  std::string validate;  // a scenario file; empty: no validation runs
};

struct RecommendReport {
  std::string file;
  AccelSpectrum spectrum;
  ShaperFitOptions options;
  ShaperRecommendation recommendation;
  std::vector<LogMode> modes;             // --validate only
  std::optional<ValidationRuns> validation;
  const ShaperFit& recommended() const { return recommendation.fits[recommendation.recommended]; }
};

// Reads the log, fits every method, runs --validate. Throws ConfigError (the log, the
// scenario), ValidationError (an option, named), model::SolverError.
RecommendReport ComputeRecommendation(const RecommendArgs& args);

// The table: the log, the PSD, one row per method, the recommendation and why, skipped
// methods; then the validation's modes and both runs' metrics side by side.
void PrintRecommendation(std::ostream& out, const RecommendReport& report);

// {"file", "axis", "samples": {...}, "psd": {...}, "design_damping_ratio",
// "test_damping_ratios", "feed_mm_min", "accel_mm_s2", "shapers": [{method, parameters,
// frequency_hz, remaining_vibration, duration_s, added_time_s, smoothing_m}, ...],
// "skipped": [{method, reason}], "recommended": {the same fields, "rule"}, and with
// --validate "validate": {scenario, axis, static_deflection_per_accel_s2, modes: [...],
// none: {metrics}, recommended: {metrics}}}; SI units.
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
