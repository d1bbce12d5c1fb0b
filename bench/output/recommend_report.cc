// `shapebench recommend`: the fit's table, JSON, CSV and plot (see the header).
#include "bench/output/recommend_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <typeinfo>

#include "bench/output/gnuplot.h"
#include "bench/output/json_number.h"
#include "bench/output/report.h"
#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/format.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

std::string Percent(double fraction) { return FormatFixed(100.0 * fraction, 2) + " %"; }

double PeakHz(const AccelSpectrum& spectrum) {
  const auto peak = std::max_element(spectrum.psd.begin(), spectrum.psd.end());
  return spectrum.frequency_hz[static_cast<std::size_t>(peak - spectrum.psd.begin())];
}

std::string RuleText(const ShaperRecommendation& r) {
  return "the least smoothing of the methods whose remaining vibration is at most 1.1 x the lowest + 0.0005 (" +
         Percent(r.tolerance) + ")";
}

nlohmann::ordered_json FitJson(const ShaperFit& fit) {
  nlohmann::ordered_json json;
  json["method"] = fit.method;
  json["parameters"] = fit.parameters;
  json["frequency_hz"] = fit.frequency_hz;
  json["remaining_vibration"] = fit.remaining_vibration;
  json["duration_s"] = fit.duration_s;
  json["added_time_s"] = fit.added_time_s;
  json["smoothing_m"] = fit.smoothing_m;
  json["design_damping_ratio"] = fit.pattern.design_damping_ratio;
  json["rule"] = "shapebench";
  return json;
}

// The rule of the registry's scores on Klipper's normalised PSD.
constexpr const char* kNormalisedRule = "shapebench on klipper's normalised psd";

// "shapebench_normalised" {psd, shapers, skipped} and "recommended_shapebench_normalised".
void AddNormalisedJson(const RecommendReport& report, nlohmann::ordered_json* json) {
  nlohmann::ordered_json view;
  view["psd"] = {{"source", "klipper"},
                 {"normalized", true},
                 {"data_set", report.klipper_spectrum.datasets.front().name},
                 {"band_hz", {kFitMinHz, kFitMaxHz}}};
  nlohmann::ordered_json shapers = nlohmann::ordered_json::array();
  for (const ShaperFit& fit : report.normalised.fits) {
    shapers.push_back(FitJson(fit));
    shapers.back()["rule"] = kNormalisedRule;
  }
  view["shapers"] = shapers;
  nlohmann::ordered_json skipped = nlohmann::ordered_json::array();
  for (const SkippedShaper& skip : report.normalised.skipped) {
    skipped.push_back({{"method", skip.method}, {"reason", skip.reason}});
  }
  view["skipped"] = skipped;
  (*json)["shapebench_normalised"] = view;
  nlohmann::ordered_json recommended = FitJson(report.normalised.fits[report.normalised.recommended]);
  recommended["rule"] = std::string(kNormalisedRule) + ": " + RuleText(report.normalised);
  (*json)["recommended_shapebench_normalised"] = recommended;
}

void PrintFitTable(std::ostream& out, const RecommendReport& report) {
  std::size_t width = 6;
  for (const ShaperFit& fit : report.recommendation.fits) width = std::max(width, fit.method.size());
  std::size_t parameters = 10;
  for (const ShaperFit& fit : report.recommendation.fits) parameters = std::max(parameters, fit.parameters.size());
  char line[256];
  std::snprintf(line, sizeof line, "  %-*s  %-*s  %-12s  %-19s  %-10s  %-12s  %s\n", static_cast<int>(width),
                "method", static_cast<int>(parameters), "parameters", "frequency_hz", "remaining_vibration",
                "duration_s", "added_time_s", "smoothing_m");
  out << line;
  for (std::size_t i = 0; i < report.recommendation.fits.size(); ++i) {
    const ShaperFit& fit = report.recommendation.fits[i];
    std::snprintf(line, sizeof line, "%s %-*s  %-*s  %-12.1f  %-19s  %-10s  %-12s  %s\n",
                  i == report.recommendation.recommended ? "*" : " ", static_cast<int>(width), fit.method.c_str(),
                  static_cast<int>(parameters), fit.parameters.c_str(), fit.frequency_hz,
                  Percent(fit.remaining_vibration).c_str(), EngineeringText(fit.duration_s, "s", 4).c_str(),
                  EngineeringText(fit.added_time_s, "s", 4).c_str(), EngineeringText(fit.smoothing_m, "m", 4).c_str());
    out << line;
  }
}

void PrintValidation(std::ostream& out, const RecommendReport& report) {
  const ValidationRuns& v = *report.validation;
  const KlipperShaperResult& fit = report.klipper_recommended();
  out << "\nvalidate " << v.scenario << ": axis " << model::AxisName(v.axis)
      << " modelled by the log's modes (its static deflection " << FormatNumber(v.static_deflection_per_accel_s2)
      << " m per m/s^2 kept)\n";
  const LogModes& fitted = report.modes;
  out << "  modes fitted to the " << fitted.spectrum << " (" << FormatNumber(fitted.resolution_hz) << " Hz bins"
      << (fitted.segments > 0 ? ", " + std::to_string(fitted.segments) + " segment(s)" : std::string()) << "); +/-: one standard deviation\n";
  out << "  mode  frequency_hz  +/-         damping_ratio  +/-         share     gain\n";
  for (std::size_t m = 0; m < fitted.modes.size(); ++m) {
    const LogMode& mode = fitted.modes[m];
    char line[200];
    std::snprintf(line, sizeof line, "  %-4zu  %-12.4g  %-10.3g  %-13.4g  %-10.3g  %-8.4g  %.6g\n", m + 1,
                  mode.frequency_hz, mode.frequency_uncertainty_hz, mode.damping_ratio, mode.damping_uncertainty,
                  mode.share, v.machine.modes[m].gain);
    out << line;
  }
  const std::string shaped = fit.name + " " + FormatNumber(std::round(fit.frequency_hz * 10.0) / 10.0) + " Hz";
  std::size_t width = 0;
  for (const MetricInfo& info : MetricTable()) width = std::max(width, info.name.size());
  auto cell = [](const MetricInfo& info, double value) -> std::string {
    if (std::isnan(value)) return "n/a";
    if (info.is_bool()) return value != 0.0 ? "true" : "false";
    return EngineeringText(value, info.unit);
  };
  char line[200];
  std::snprintf(line, sizeof line, "  %-*s  %-16s  %s\n", static_cast<int>(width), "metric", "none", shaped.c_str());
  out << line;
  for (const MetricInfo& info : MetricTable()) {
    std::snprintf(line, sizeof line, "  %-*s  %-16s  %s\n", static_cast<int>(width), std::string(info.name).c_str(),
                  cell(info, v.none.*info.field).c_str(), cell(info, v.recommended.*info.field).c_str());
    out << line;
  }
}

}  // namespace

void PrintRecommendation(std::ostream& out, const RecommendReport& report) {
  const AccelSpectrum& s = report.spectrum;
  const UniformAccel& u = s.samples;
  const std::size_t n = u.accel_mm_s2[0].size();
  out << "recommend " << report.file << " (axis " << AccelAxisName(report.axis) << ")\n";
  if (n > 0) {
    out << "samples    " << n << " at " << FormatNumber(u.sample_rate_hz) << " Hz ("
        << EngineeringText(static_cast<double>(n - 1) / u.sample_rate_hz, "s", 4) << ")\n";
  }
  PrintKlipperRecommendation(out, report);
  out << "\nshapebench's own view (not mixed into Klipper's numbers above):\n";
  if (n > 0) {
    out << "samples    "
        << (u.resampled ? "time stamps up to " + EngineeringText(u.max_offset_s, "s", 3) +
                              " off a uniform grid: resampled linearly"
                        : std::string("time stamps on a uniform grid"))
        << "\n";
    out << "psd        Welch, Hann window, " << s.full.segment_samples << "-sample segments ("
        << FormatNumber(u.sample_rate_hz / s.full.segment_samples) << " Hz bins), 50% overlap, " << s.full.segments
        << " segments; fit band " << FormatNumber(kFitMinHz) << "-" << FormatNumber(kFitMaxHz) << " Hz, peak at "
        << FormatNumber(PeakHz(s)) << " Hz\n";
  } else {
    out << "psd        the file's PSD as read, fit band " << FormatNumber(kFitMinHz) << "-" << FormatNumber(kFitMaxHz)
        << " Hz, peak at " << FormatNumber(PeakHz(s)) << " Hz\n";
  }
  out << "design     library shapers at damping ratio " << FormatNumber(report.options.design_damping_ratio)
      << " (methods 1-4 undamped); vibration: the worst at damping ratios";
  for (const double z : report.options.test_damping_ratios) out << " " << FormatNumber(z);
  out << "\nsmoothing  contour error on a circle at " << FormatNumber(report.options.feed_mm_min) << " mm/min and "
      << FormatNumber(report.options.accel_mm_s2) << " mm/s^2 (radius "
      << EngineeringText(std::pow(report.options.feed_mm_min / 60000.0, 2) / (report.options.accel_mm_s2 * 1e-3), "m", 4)
      << "), each axis shaped\n\n";
  PrintFitTable(out, report);
  const ShaperFit& fit = report.recommended();
  out << "\nrecommended_shapebench: " << fit.method << " at "
      << FormatNumber(std::round(fit.frequency_hz * 10.0) / 10.0) << " Hz (remaining vibration "
      << Percent(fit.remaining_vibration) << ", smoothing " << EngineeringText(fit.smoothing_m, "m", 4)
      << "): " << RuleText(report.recommendation) << "\n";
  const ShaperFit& normalised = report.normalised.fits[report.normalised.recommended];
  out << "recommended_shapebench_normalised: " << normalised.method << " at "
      << FormatNumber(std::round(normalised.frequency_hz * 10.0) / 10.0) << " Hz (remaining vibration "
      << Percent(normalised.remaining_vibration) << ", smoothing " << EngineeringText(normalised.smoothing_m, "m", 4)
      << "): the same rule, the registry scored on Klipper's normalised PSD\n";
  for (const SkippedShaper& skipped : report.recommendation.skipped) {
    out << "skipped: " << skipped.method << " (" << skipped.reason << ")\n";
  }
  if (report.validation) PrintValidation(out, report);
}

nlohmann::ordered_json RecommendJson(const RecommendReport& report) {
  const AccelSpectrum& s = report.spectrum;
  nlohmann::ordered_json json;
  json["file"] = report.file;
  json["axis"] = AccelAxisName(report.axis);
  json["rule"] = {{"recommended", "klipper"},
                  {"recommended_shapebench", "shapebench"},
                  {"recommended_shapebench_normalised", kNormalisedRule}};
  AddKlipperJson(report, &json);
  nlohmann::ordered_json own;
  if (!s.samples.accel_mm_s2[0].empty()) {
    own["samples"] = {{"count", s.samples.accel_mm_s2[0].size()},
                      {"sample_rate_hz", s.samples.sample_rate_hz},
                      {"resampled", s.samples.resampled},
                      {"max_time_offset_s", s.samples.max_offset_s}};
    own["psd"] = {{"window", "hann"},
                  {"segment_samples", s.full.segment_samples},
                  {"segments", s.full.segments},
                  {"resolution_hz", s.samples.sample_rate_hz / s.full.segment_samples},
                  {"band_hz", {kFitMinHz, kFitMaxHz}},
                  {"peak_hz", PeakHz(s)}};
  } else {
    own["psd"] = {{"window", "as read"}, {"band_hz", {kFitMinHz, kFitMaxHz}}, {"peak_hz", PeakHz(s)}};
  }
  own["design_damping_ratio"] = report.options.design_damping_ratio;
  own["test_damping_ratios"] = report.options.test_damping_ratios;
  own["feed_mm_min"] = report.options.feed_mm_min;
  own["accel_mm_s2"] = report.options.accel_mm_s2;
  nlohmann::ordered_json shapers = nlohmann::ordered_json::array();
  for (const ShaperFit& fit : report.recommendation.fits) shapers.push_back(FitJson(fit));
  own["shapers"] = shapers;
  nlohmann::ordered_json skipped = nlohmann::ordered_json::array();
  for (const SkippedShaper& skip : report.recommendation.skipped) {
    skipped.push_back({{"method", skip.method}, {"reason", skip.reason}});
  }
  own["skipped"] = skipped;
  json["shapebench"] = own;
  nlohmann::ordered_json recommended = FitJson(report.recommended());
  recommended["rule"] = RuleText(report.recommendation);
  json["recommended_shapebench"] = recommended;
  AddNormalisedJson(report, &json);
  json["warnings"] = report.warnings;
  if (report.validation) {
    const ValidationRuns& v = *report.validation;
    nlohmann::ordered_json modes = nlohmann::ordered_json::array();
    const LogModes& fitted = report.modes;
    for (std::size_t m = 0; m < fitted.modes.size(); ++m) {
      const LogMode& mode = fitted.modes[m];
      modes.push_back({{"frequency_hz", mode.frequency_hz},
                       {"frequency_uncertainty_hz", JsonNumber(mode.frequency_uncertainty_hz)},
                       {"damping_ratio", mode.damping_ratio},
                       {"damping_uncertainty", JsonNumber(mode.damping_uncertainty)},
                       {"share", mode.share},
                       {"gain", v.machine.modes[m].gain}});
    }
    const KlipperShaperResult& shaper = report.klipper_recommended();
    json["validate"] = {{"scenario", v.scenario},
                        {"pattern", {{"method", shaper.name}, {"frequency_hz", shaper.frequency_hz}, {"rule", "klipper"}}},
                        {"axis", model::AxisName(v.axis)},
                        {"static_deflection_per_accel_s2", v.static_deflection_per_accel_s2},
                        {"mode_fit", {{"spectrum", fitted.spectrum},
                                      {"resolution_hz", fitted.resolution_hz},
                                      {"segment_samples", fitted.segment_samples},
                                      {"segments", fitted.segments},
                                      {"uncertainty", "one standard deviation: " + fitted.uncertainty}}},
                        {"modes", modes},
                        {"none", MetricsJson(v.none)},
                        {"recommended", MetricsJson(v.recommended)}};
  }
  return json;
}

void WriteRecommendCsv(const std::string& path, const RecommendReport& report) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "frequency_hz,psd";
    for (const ShaperFit& fit : report.recommendation.fits) out << ",vibration_" << fit.method;
    out << "\n";
    for (std::size_t k = 0; k < report.spectrum.frequency_hz.size(); ++k) {
      out << ExactDouble(report.spectrum.frequency_hz[k]) << "," << ExactDouble(report.spectrum.psd[k]);
      for (const ShaperFit& fit : report.recommendation.fits) out << "," << ExactDouble(fit.vibration[k]);
      out << "\n";
    }
  });
}

void WriteRecommendPlot(const std::string& path_png, const RecommendReport& report) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  const ShaperRecommendation& r = report.recommendation;
  const AccelSpectrum& s = report.spectrum;
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    std::fprintf(gnuplot, "set terminal pngcairo size 1100,620 noenhanced font 'sans,10'\n");
    std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output_path).c_str());
    const ShaperFit& best = report.recommended();
    const std::string title = "recommend: " + std::filesystem::path(report.file).filename().string() + ", axis " +
                              AccelAxisName(report.axis) + "; shapebench's own fit, recommended_shapebench " + best.method + " at " +
                              FormatNumber(std::round(best.frequency_hz * 10.0) / 10.0) + " Hz";
    std::fprintf(gnuplot, "set title %s\n", GnuplotQuoted(title).c_str());
    std::fprintf(gnuplot, "set xlabel 'frequency [Hz]'\nset ylabel 'PSD [(mm/s^2)^2/Hz]'\nset grid\n");
    std::fprintf(gnuplot, "set key outside right top title 'V(f) x PSD per method'\nset xrange [0:%g]\nset yrange [0:*]\n", kFitMaxHz);
    std::fprintf(gnuplot, "$data << EOD\n");
    for (std::size_t k = 0; k < s.frequency_hz.size(); ++k) {
      std::fprintf(gnuplot, "%.10g %.10g", s.frequency_hz[k], s.psd[k]);
      for (const ShaperFit& fit : r.fits) std::fprintf(gnuplot, " %.10g", fit.vibration[k] * s.psd[k]);
      std::fprintf(gnuplot, "\n");
    }
    const double threshold = *std::max_element(s.psd.begin(), s.psd.end()) / 20.0;
    std::fprintf(gnuplot, "EOD\nplot $data using 1:2 with lines lw 3 lc rgb '#000000' title 'PSD', \\\n");
    std::fprintf(gnuplot, "     %.10g with lines lw 1.5 dt 2 lc rgb '#cc0000' title 'PSD max / 20'", threshold);
    for (std::size_t i = 0; i < r.fits.size(); ++i) {
      const ShaperFit& fit = r.fits[i];
      const bool chosen = i == r.recommended;
      const bool patent = controller::FindShaper(fit.method).kind == controller::ShaperKind::kPatentStep;
      const std::string name = (patent ? "method " : "") + fit.method + " " +
                               FormatNumber(std::round(fit.frequency_hz * 10.0) / 10.0) + " Hz: " +
                               Percent(fit.remaining_vibration) + (chosen ? " (recommended)" : "");
      std::fprintf(gnuplot, ", \\\n     $data using 1:%zu with lines lw %g dt %d lc rgb '%s' title %s", i + 3,
                   chosen ? 3.0 : 1.2, chosen ? 1 : static_cast<int>(i / 10) + 1, kColours[i % 10],
                   GnuplotQuoted(name).c_str());
    }
    std::fprintf(gnuplot, "\nunset output\nquit\n");
  });
}

std::vector<std::string> WriteRecommendOutputs(const std::string& out_dir, const RecommendReport& report) {
  StagedDirectory staged(out_dir);
  const std::filesystem::path dir(staged.path());
  try {
    WriteFileAtomically((dir / "recommend.json").string(),
                        [&](std::ostream& out) { out << RecommendJson(report).dump(2) << "\n"; });
    WriteRecommendCsv((dir / "psd.csv").string(), report);
    WriteRecommendPlot((dir / "recommend.png").string(), report);
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  return {"recommend.json", "psd.csv", "recommend.png"};
}

}  // namespace shapebench::bench
