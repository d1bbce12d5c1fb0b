// `shapebench recommend FILE.csv`: a shaper recommended from an accelerometer log
// (bench/measured/shaper_fit.h); the table or JSON, --out DIR with recommend.json, psd.csv
// and recommend.png, --validate SCENARIO (bench/run/recommend_validation.h).
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/measured/accel_log.h"
#include "bench/measured/accel_spectrum.h"
#include "bench/measured/psd_peaks.h"
#include "bench/measured/shaper_fit.h"
#include "bench/output/output_path.h"
#include "bench/output/recommend_report.h"
#include "bench/run/recommend_validation.h"
#include "common/interrupt.h"
#include "common/validation_error.h"

namespace shapebench::bench::cli {
namespace {

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

AccelAxis ParseAxis(const std::string& text) {
  for (const AccelAxis axis : {AccelAxis::kX, AccelAxis::kY, AccelAxis::kZ, AccelAxis::kAll}) {
    if (text == AccelAxisName(axis)) return axis;
  }
  throw ValidationError("--axis", "expected x, y, z or all (the sum of the three PSDs), got '" + text + "'");
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
  const AccelAxis axis = ParseAxis(args.axis);
  const AccelLog log = ReadAccelLog(args.file);
  report.spectrum = ComputeAccelSpectrum(log, axis);
  report.recommendation = RecommendShapers(report.spectrum.frequency_hz, report.spectrum.psd, report.options);
  if (!args.validate.empty()) {
    report.modes = PickPsdPeaks(report.spectrum.frequency_hz, report.spectrum.psd);
    report.validation = RunValidation(args.validate, report.modes, report.recommended().pattern);
  }
  return report;
}

int RecommendCommand(const RecommendArgs& args) {
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the fit
  Doing("fitting the shapers to " + args.file);
  const RecommendReport report = ComputeRecommendation(args);
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
      "recommend", "fit every shaper of the registry to an accelerometer log's PSD and recommend one");
  recommend->add_option("file", args->file, "accelerometer log: #time,accel_x,accel_y,accel_z (s, mm/s^2)")
      ->required()
      ->type_name("FILE.csv");
  recommend->add_option("--axis", args->axis, "x, y, z or all (the sum of the three PSDs; default)")
      ->type_name("AXIS");
  recommend->add_option("--damping-ratio", args->damping_ratio, "the library shapers' design damping (default 0.1)")
      ->type_name("ZETA");
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
  recommend->footer("docs/measured-data.md#accelerometer-logs");
  return {recommend, [args] { return RecommendCommand(*args); }};
}

}  // namespace shapebench::bench::cli
