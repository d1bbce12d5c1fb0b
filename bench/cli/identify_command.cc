// `shapebench identify FILE.uff`: modes from measured FRFs (bench/measured/frf_identification.h)
// as a table or JSON, modes.json and the stabilisation diagram in the output directory
// (docs/measured-data.md).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/measured/frf_identification.h"
#include "bench/output/identify_report.h"
#include "bench/output/output_path.h"
#include "common/decimal.h"
#include "common/format.h"
#include "common/interrupt.h"
#include "common/shown_text.h"

namespace shapebench::bench::cli {
namespace {

struct IdentifyArgs {
  std::string file;
  std::string axis;   // "", "x", "y", "z"
  std::string band;   // "", "MIN:MAX" in Hz, "auto"
  std::string max_order = "30";  // 1..200 or "auto"
  std::string max_work;  // "": the default
  bool json = false;
  double max_fit_error_percent = kDefaultMaxFitErrorPercent;
  std::string out_dir;  // "": identify_out/STEM
};

// --max-order N (1 to 200) or auto (the order chosen up to 200: FrfSelection::auto_order).
void ParseMaxOrder(const std::string& text, FrfSelection* selection) {
  if (text == "auto") {
    selection->auto_order = true;
    selection->max_order = 200;
    return;
  }
  double order = 0.0;
  if (!ParseDecimal(text, &order) || order != std::floor(order) || !(order >= 1.0 && order <= 200.0)) {
    throw std::runtime_error("--max-order: expected an integer from 1 to 200 or auto, got '" +
                             TerminalSafe(text, false) + "'");
  }
  selection->max_order = static_cast<int>(order);
}

// --band MIN:MAX in Hz, or auto (FrfSelection::auto_band).
void ParseBand(const std::string& text, FrfSelection* selection) {
  if (text == "auto") {
    selection->auto_band = true;
    return;
  }
  const std::size_t colon = text.find(':');
  bool ok = colon != std::string::npos && colon > 0 && colon + 1 < text.size();
  if (ok) {
    ok = ParseDecimal(text.substr(0, colon), &selection->min_frequency_hz) &&
         ParseDecimal(text.substr(colon + 1), &selection->max_frequency_hz);
  }
  if (!ok || !(selection->min_frequency_hz >= 0.0) || !(selection->max_frequency_hz > selection->min_frequency_hz) ||
      !std::isfinite(selection->max_frequency_hz)) {
    throw std::runtime_error("--band: expected MIN:MAX in Hz with 0 <= MIN < MAX (e.g. 5:200), got '" +
                             TerminalSafe(text, false) + "'");
  }
  selection->band_source = "--band " + text;
}

// The table (or JSON) on stdout, then a "wrote" line for modes.json and
// stabilisation.png (on stderr with --json). Throws ConfigError (exit 2) for bad input.
int IdentifyCommand(const IdentifyArgs& args) {
  Doing("identifying the modes of " + args.file);
  FrfSelection selection;
  if (!args.axis.empty()) selection.axis = static_cast<int>(std::string("xyz").find(args.axis));
  if (!args.band.empty()) ParseBand(args.band, &selection);
  ParseMaxOrder(args.max_order, &selection);
  if (!args.max_work.empty() &&
      (!ParseDecimal(args.max_work, &selection.max_work) || !(selection.max_work >= 1.0) ||
       !std::isfinite(selection.max_work))) {
    throw std::runtime_error("--max-work: expected a number >= 1 (multiply-adds, e.g. 1e12), got '" +
                             TerminalSafe(args.max_work, false) + "'");
  }
  const std::string out_dir =
      args.out_dir.empty() ? (std::filesystem::path("identify_out") / std::filesystem::path(args.file).stem()).string()
                           : args.out_dir;
  RequireWritableOutputDir("--out", out_dir);  // before the identification
  const IdentifiedFrfs frfs = IdentifyFrfFile(args.file, selection);
  for (const std::string& warning : frfs.warnings) std::cerr << "warning: " << TerminalSafe(warning, false) << "\n";
  {
    const DeferInterrupts defer;
    WriteIdentifyOutputs(out_dir, frfs, args.file);
    ThrowIfInterrupted("the output in " + out_dir + " is complete");
  }
  if (args.json) {
    std::cout << IdentifyJson(frfs).dump(2) << std::endl;
  } else {
    PrintIdentifyTable(std::cout, frfs);
  }
  std::ostream& wrote = args.json ? std::cerr : std::cout;
  for (const char* file : {"modes.json", "stabilisation.png"}) {
    wrote << "wrote " << TerminalSafe((std::filesystem::path(out_dir) / file).string(), false) << "\n";
  }
  wrote.flush();
  const double error = frfs.identification.fit_error_percent;
  if (error > args.max_fit_error_percent) {
    std::cerr << "warning: " << TerminalSafe(args.file, false) << ": fit error " << FormatNumber(error, 4)
              << " % is above --max-fit-error (" << FormatNumber(args.max_fit_error_percent, 4) << " %) with "
              << frfs.identification.modes.size() << " mode" << (frfs.identification.modes.size() == 1 ? "" : "s")
              << ": the modes do not explain the data; narrow the band (--band) around the peaks of interest or "
                 "raise --max-order\n";
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace

Command AddIdentifyCommand(CLI::App* app) {
  auto args = std::make_shared<IdentifyArgs>();
  CLI::App* identify = app->add_subcommand(
      "identify", "modal parameters from measured FRFs (UFF 58): table or JSON, stabilisation diagram");
  identify->add_option("file", args->file, "UFF file of dataset 58 FRF records (ASCII or 58b)")
      ->required()
      ->type_name("FILE.uff");
  identify->add_option("--axis", args->axis, "only the records whose response is along this axis")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->type_name("x|y|z");
  identify
      ->add_option("--band", args->band,
                   "the band in Hz the modes are identified in (default: all lines); auto: around the records' peaks")
      ->type_name("MIN:MAX|auto");
  identify
      ->add_option("--max-order", args->max_order,
                   "highest model order in pole pairs, 1 to 200 (default 30); auto: doubled from 8 until the "
                   "picked modes repeat")
      ->type_name("N|auto");
  identify
      ->add_option("--max-work", args->max_work,
                   "the most work the fit may take, in multiply-adds estimated before it starts (default 1e11); "
                   "beyond, exit 3")
      ->type_name("N");
  identify
      ->add_option("--max-fit-error", args->max_fit_error_percent,
                   "the largest fit error in % the modes may leave (default 20); above, a warning and exit 3")
      ->check(CLI::Range(0.0, 100.0))
      ->type_name("PERCENT");
  identify->add_flag("--json", args->json, "print one JSON object");
  identify
      ->add_option("--out", args->out_dir,
                   "write modes.json and stabilisation.png into DIR (default: identify_out/STEM)")
      ->type_name("DIR");
  return {identify, [args] { return IdentifyCommand(*args); }};
}

}  // namespace shapebench::bench::cli
