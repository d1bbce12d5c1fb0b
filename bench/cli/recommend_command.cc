// `shapebench recommend FILE.csv`: a shaper recommended from an accelerometer log
// (bench/measured/shaper_fit.h); the table or JSON, --out DIR with recommend.json, psd.csv
// and recommend.png, --validate SCENARIO (bench/run/recommend_validation.h).
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/config_document.h"
#include "bench/config/config_error.h"
#include "bench/measured/accel_log.h"
#include "bench/measured/accel_spectrum.h"
#include "bench/measured/klipper_calibrate.h"
#include "bench/measured/klipper_psd.h"
#include "bench/measured/klipper_psd_file.h"
#include "bench/measured/log_modes.h"
#include "bench/measured/psd_peaks.h"
#include "bench/measured/shaper_fit.h"
#include "bench/output/output_path.h"
#include "bench/output/recommend_report.h"
#include "bench/run/recommend_validation.h"
#include "common/format.h"
#include "common/interrupt.h"
#include "common/validation_error.h"

namespace shapebench::bench::cli {
namespace {

struct RecommendArgs {
  std::string file;
  std::string axis = "all";  // x, y, z or all
  double damping_ratio = 0.1;
  double max_smoothing_mm = 0.0;
  const CLI::Option* max_smoothing = nullptr;  // given when its count() is not 0
  double feed_mm_min = ShaperFitOptions{}.feed_mm_min;
  double accel_mm_s2 = ShaperFitOptions{}.accel_mm_s2;
  bool json = false;
  std::string out_dir;
  std::string validate;  // a scenario file; empty: no validation runs
  double resolution_hz = 0.0;  // of the modes' fit; 0: the log's length
  const CLI::Option* resolution = nullptr;
};

AccelAxis ParseAxis(const std::string& text) {
  for (const AccelAxis axis : {AccelAxis::kX, AccelAxis::kY, AccelAxis::kZ, AccelAxis::kAll}) {
    if (text == AccelAxisName(axis)) return axis;
  }
  throw ValidationError("--axis", "expected x, y, z or all (the sum of the three PSDs), got '" + text + "'");
}

// Klipper's Welch averages this many segments at least before its PSD is trusted here:
// each bin's relative scatter is about 1 / sqrt(segments).
constexpr int kFewSegments = 8;

// A warning when the log is too short for Klipper's fixed resolution (rate / M).
void WarnShortLog(RecommendReport* report) {
  const KlipperSpectrum& s = report->klipper_spectrum;
  if (s.segments == 0 || s.segments >= kFewSegments) return;
  const double seconds = (kFewSegments + 1) * (s.segment_samples / 2.0) / s.sample_rate_hz;
  report->warnings.push_back(
      report->file + ": the log averages only " + std::to_string(s.segments) + " Welch segments of " +
      std::to_string(s.segment_samples) + " samples (" + FormatNumber(s.sample_rate_hz / s.segment_samples) +
      " Hz bins): each PSD bin scatters by about " + FormatNumber(std::round(100.0 / std::sqrt(s.segments))) +
      "%; record at least " + FormatNumber(std::ceil(seconds * 10.0) / 10.0) + " s for " +
      std::to_string(kFewSegments));
}

// Klipper's fit of the spectrum (the axis chosen), every data set.
void FitKlipper(const AccelAxis axis, RecommendReport* report) {
  std::vector<KlipperFitInput> data;
  for (const KlipperPsd& psd : report->klipper_spectrum.datasets) {
    data.push_back({psd.frequency_hz, KlipperFitPsd(psd, axis, report->file)});
  }
  report->klipper = KlipperFindBestShaper(data, report->klipper_options);
}

// The fit band of Klipper's normalised PSD as its fit reads it (the first data set, the
// axis chosen): shapebench's own view of a Klipper PSD file (a resonances_*.csv normalised
// as Klipper does, a calibration_data_*.csv as read), and where the registry is scored
// under Klipper's normalisation for a log.
AccelSpectrum KlipperBandSpectrum(const RecommendReport& report) {
  AccelSpectrum spectrum;
  spectrum.axis = report.axis;
  const KlipperPsd& psd = report.klipper_spectrum.datasets[0];
  const std::vector<double>& values = KlipperFitPsd(psd, report.axis, report.file);
  for (std::size_t k = 0; k < psd.frequency_hz.size(); ++k) {
    if (psd.frequency_hz[k] < kFitMinHz || psd.frequency_hz[k] > kFitMaxHz) continue;
    spectrum.frequency_hz.push_back(psd.frequency_hz[k]);
    spectrum.psd.push_back(values[k]);
  }
  if (spectrum.psd.empty()) {
    throw ConfigError(report.file, 0, 0, "freq", "no PSD bin between " + FormatNumber(kFitMinHz) + " and " +
                                                     FormatNumber(kFitMaxHz) + " Hz");
  }
  return spectrum;
}

// The log or Klipper PSD file `path`: both spectra and Klipper's fit. A file that is
// neither is named for what it looks like.
void ReadSpectra(const std::string& path, RecommendReport* report) {
  std::string text;
  std::string error;
  if (!ReadInputFile(path, &text, &error)) throw ConfigError(path, 0, 0, "", error);
  if (IsKlipperPsdFile(text)) {
    report->klipper_spectrum = ParseKlipperPsdFile(text, path);
    report->spectrum = KlipperBandSpectrum(*report);
    FitKlipper(report->axis, report);
    return;
  }
  const std::string kind = ForeignFileKind(text);
  if (!kind.empty()) {
    throw ConfigError(path, 1, 1, "header",
                      "this looks like " + kind + "; recommend reads an accelerometer log "
                      "(#time,accel_x,accel_y,accel_z) or Klipper's resonances_*.csv / calibration_data_*.csv");
  }
  const AccelLog log = ParseAccelLog(text, path);
  report->spectrum = ComputeAccelSpectrum(log, report->axis);
  report->klipper_spectrum = KlipperLogSpectrum(log);
  FitKlipper(report->axis, report);
  WarnShortLog(report);
}

// --resolution-hz before the file is read: positive, at most kMaxModeResolutionHz.
void ValidateResolution(const RecommendArgs& args) {
  if (args.resolution->count() == 0) return;
  if (args.validate.empty()) {
    throw ValidationError("--resolution-hz", "sets the resolution of --validate's modes: give --validate too");
  }
  if (!(args.resolution_hz > 0.0) || args.resolution_hz > kMaxModeResolutionHz) {
    throw ValidationError("--resolution-hz", "must be above 0 and at most " + FormatNumber(kMaxModeResolutionHz) +
                                                 " Hz (a peak must span a few bins), got " + FormatNumber(args.resolution_hz));
  }
}

// The log's modes for --validate: the peaks of shapebench's PSD, each measured by the modal
// fit (bench/measured/log_modes.h) on the log's samples, or on a PSD file's bins.
LogModes FitModes(const RecommendArgs& args, const RecommendReport& report) {
  const std::vector<LogMode> found = PickPsdPeaks(report.spectrum.frequency_hz, report.spectrum.psd);
  if (report.spectrum.samples.accel_mm_s2[0].empty()) {
    if (args.resolution->count() > 0) {
      throw ValidationError("--resolution-hz", "a PSD file's resolution is the file's (" +
                                                   FormatNumber(report.spectrum.frequency_hz.size() > 1
                                                                    ? report.spectrum.frequency_hz[1] -
                                                                          report.spectrum.frequency_hz[0]
                                                                    : 0.0) +
                                                   " Hz); give an accelerometer log");
    }
    return FitPsdModes(report.spectrum.frequency_hz, report.spectrum.psd, found);
  }
  return FitLogModes(report.spectrum.samples, report.axis, found, args.resolution_hz);
}

// Reads the log, fits every method, runs --validate. Throws ConfigError (the log, the
// scenario), ValidationError (an option, named), model::SolverError.
RecommendReport ComputeRecommendation(const RecommendArgs& args) {
  RecommendReport report;
  report.file = args.file;
  report.options.design_damping_ratio = args.damping_ratio;
  report.options.feed_mm_min = args.feed_mm_min;
  report.options.accel_mm_s2 = args.accel_mm_s2;
  report.options.validate();  // before the file is read
  report.klipper_options.damping_ratio = args.damping_ratio;
  if (args.max_smoothing->count() > 0) report.klipper_options.max_smoothing_mm = args.max_smoothing_mm;
  report.klipper_options.validate();
  report.axis = ParseAxis(args.axis);
  ValidateResolution(args);
  ReadSpectra(args.file, &report);
  report.recommendation = RecommendShapers(report.spectrum.frequency_hz, report.spectrum.psd, report.options);
  const AccelSpectrum normalised = KlipperBandSpectrum(report);
  report.normalised = RecommendShapers(normalised.frequency_hz, normalised.psd, report.options);
  if (!args.validate.empty()) {
    report.modes = FitModes(args, report);
    for (const std::string& warning : report.modes.warnings) report.warnings.push_back(args.file + ": " + warning);
    report.validation = RunValidation(args.validate, report.modes.modes, KlipperPattern(report.klipper_recommended()));
  }
  return report;
}

int RecommendCommand(const RecommendArgs& args) {
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the fit
  Doing("fitting the shapers to " + args.file);
  const RecommendReport report = ComputeRecommendation(args);
  for (const std::string& warning : report.warnings) std::cerr << "warning: " << warning << "\n";
  std::vector<std::string> written;
  if (!args.out_dir.empty()) {
    const DeferInterrupts defer;
    written = WriteRecommendOutputs(args.out_dir, report);
    ThrowIfInterrupted("the output in " + args.out_dir + " is complete");
  }
  if (args.json) {
    std::cout << RecommendJson(report).dump(2) << std::endl;
  } else {
    PrintRecommendation(std::cout, report);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

}  // namespace

Command AddRecommendCommand(CLI::App* app) {
  auto args = std::make_shared<RecommendArgs>();
  CLI::App* recommend = app->add_subcommand(
      "recommend",
      "recommend a shaper from an accelerometer log as Klipper's calibrate_shaper does, shapebench's own fit beside it");
  recommend->add_option("file", args->file, "accelerometer log: #time,accel_x,accel_y,accel_z (s, mm/s^2)")
      ->required()
      ->type_name("FILE.csv");
  recommend->add_option("--axis", args->axis, "x, y, z or all (the sum of the three PSDs; default)")
      ->type_name("AXIS");
  recommend->add_option("--damping-ratio", args->damping_ratio,
                        "the shapers' design damping, Klipper's --damping_ratio (default 0.1)")
      ->type_name("ZETA");
  args->max_smoothing = recommend->add_option("--max-smoothing", args->max_smoothing_mm,
                        "Klipper's --max_smoothing: the most smoothing allowed, mm (at least 0.05)")
      ->type_name("MM");
  recommend->add_option("--feed-mm-min", args->feed_mm_min, "feed of the smoothing's circle (default 6000)")
      ->type_name("F");
  recommend->add_option("--accel-mm-s2", args->accel_mm_s2, "acceleration of the smoothing's circle (default 5000)")
      ->type_name("A");
  recommend->add_flag("--json", args->json, "print the fit as one JSON object");
  recommend->add_option("--out", args->out_dir, "write recommend.json, psd.csv and recommend.png into DIR")
      ->type_name("DIR");
  recommend
      ->add_option("--validate", args->validate,
                   "run SCENARIO with the log's modes in place of its machine, unshaped and with the "
                   "recommendation")
      ->type_name("SCENARIO.yaml");
  args->resolution = recommend->add_option("--resolution-hz", args->resolution_hz,
                                           "resolution of the spectrum --validate's modes are fitted to, Hz "
                                           "(default: 1 / the log's length)")
                         ->type_name("HZ");
  recommend->footer("docs/measured-data.md#accelerometer-logs");
  return {recommend, [args] { return RecommendCommand(*args); }};
}

}  // namespace shapebench::bench::cli
