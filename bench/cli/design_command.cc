// `shapebench design SCENARIO.yaml`: the shortest pattern whose residual vibration stays
// within a tolerance over a band around each participating mode of the scenario's machine
// (controller/pattern_design.h, docs/design.md); the table or JSON, the scenario fragment,
// --out DIR with design.json, design.yaml and design.png.
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/output/design_report.h"
#include "bench/output/output_path.h"
#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/scenario_loader.h"
#include "common/format.h"
#include "common/interrupt.h"
#include "common/validation_error.h"

namespace shapebench::bench::cli {
namespace {

// A band left to the mode: its frequency +/- this fraction, its own damping ratio.
constexpr double kDefaultBandFraction = 0.10;
// The impulses form's grid when --grid-s is not given: the patent's 0.1 ms step units.
constexpr double kDefaultImpulseGridS = 1e-4;
// The longest pattern searched, in periods of the lowest band's lowest frequency.
constexpr double kMaxDurationPeriods = 20.0;

struct DesignArgs {
  std::string file;
  std::vector<std::string> sets;
  std::vector<std::string> bands;
  std::vector<std::string> dampings;
  double tolerance = 0.05;
  int derivatives = 0;
  std::string form = "profile_table";
  std::optional<double> grid_s;
  std::optional<double> margin;
  bool registry = true;
  bool validate = false;
  bool json = false;
  std::string out_dir;
};

// "MODE=LO:HI" of `option`: MODE an index below `modes`, LO <= HI finite numbers.
std::pair<int, std::pair<double, double>> ParseModeRange(const std::string& option, const std::string& text,
                                                         const DesignModes& modes, const std::string& unit) {
  const std::string allowed = "allowed: MODE=LO:HI, MODE 0 to " + std::to_string(modes.modes.size() - 1) +
                              " (the participating modes of axes " + modes.axes + ", lowest first), LO <= HI" + unit;
  const std::size_t eq = text.find('=');
  const std::size_t colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || colon == std::string::npos) {
    throw ValidationError(option, "'" + text + "' is not MODE=LO:HI; " + allowed);
  }
  int mode = -1;
  double lo = NAN;
  double hi = NAN;
  try {
    std::size_t used = 0;
    mode = std::stoi(text.substr(0, eq), &used);
    if (used != eq) mode = -1;
    lo = std::stod(text.substr(eq + 1, colon - eq - 1));
    hi = std::stod(text.substr(colon + 1));
  } catch (const std::exception&) {
    throw ValidationError(option, "'" + text + "' is not MODE=LO:HI with numbers; " + allowed);
  }
  if (mode < 0 || mode >= static_cast<int>(modes.modes.size())) {
    throw ValidationError(option, "'" + text + "': no participating mode " + text.substr(0, eq) + "; " + allowed);
  }
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) {
    throw ValidationError(option, "'" + text + "': LO must be <= HI, both finite; " + allowed);
  }
  return {mode, {lo, hi}};
}

// The report's bands: one per participating mode, or per mode named by --band/--damping.
void BuildBands(const DesignArgs& args, const DesignModes& modes, DesignReport* report) {
  std::map<int, std::pair<double, double>> freq;
  std::map<int, std::pair<double, double>> damp;
  for (const std::string& text : args.bands) {
    const auto parsed = ParseModeRange("--band", text, modes, " Hz, LO > 0");
    if (!(parsed.second.first > 0.0)) {
      throw ValidationError("--band", "'" + text + "': LO must be > 0 Hz");
    }
    freq[parsed.first] = parsed.second;
  }
  for (const std::string& text : args.dampings) {
    const auto parsed = ParseModeRange("--damping", text, modes, ", in [0, 0.7]");
    if (parsed.second.first < 0.0 || parsed.second.second > 0.7) {
      throw ValidationError("--damping", "'" + text + "': damping ratios must be in [0, 0.7]");
    }
    damp[parsed.first] = parsed.second;
  }
  for (std::size_t m = 0; m < modes.modes.size(); ++m) {
    const model::ModeInfo& mode = modes.modes[m];
    const int i = static_cast<int>(m);
    // With --band given, only the modes named are designed for.
    if (!freq.empty() && freq.count(i) == 0) continue;
    controller::DesignBand band;
    const auto f = freq.count(i) ? freq[i]
                                 : std::make_pair(mode.frequency_hz * (1.0 - kDefaultBandFraction),
                                                  mode.frequency_hz * (1.0 + kDefaultBandFraction));
    const auto z = damp.count(i) ? damp[i] : std::make_pair(mode.damping_ratio, mode.damping_ratio);
    band = {f.first, f.second, z.first, z.second};
    report->spec.bands.push_back(band);
    report->modes.push_back(i);
    report->mode_frequency_hz.push_back(mode.frequency_hz);
    report->mode_damping_ratio.push_back(mode.damping_ratio);
  }
}

// The spec's own checks, named by the option that set the value.
void ValidateSpec(const controller::DesignSpec& spec) {
  try {
    spec.validate();
  } catch (const ValidationError& error) {
    static const std::map<std::string, std::string> kOptions{
        {"tolerance", "--tolerance"}, {"derivatives", "--derivatives"}, {"grid_s", "--grid-s"},
        {"margin", "--margin"},       {"max_duration_s", "--grid-s"}};
    const auto it = kOptions.find(error.field());
    throw ValidationError(it != kOptions.end() ? it->second : "--band/--damping (" + error.field() + ")",
                          error.message());
  }
}

DesignReport PrepareDesign(const DesignArgs& args, Scenario* loaded) {
  DesignReport report;
  report.file = args.file;
  report.form = args.form == "impulses" ? DesignForm::kImpulses : DesignForm::kProfileTable;
  if (args.grid_s && report.form == DesignForm::kProfileTable) {
    throw ValidationError("--grid-s", "is for --form impulses only; allowed: leave it out (profile_table's grid "
                                      "is the scenario's controller.period_s) or add --form impulses");
  }
  LoadOptions options;
  options.plan_move = false;  // the design does not depend on the move
  *loaded = LoadScenario(args.file, ParseOverrides(args.sets), options);
  const Scenario& scenario = *loaded;
  const DesignModes modes = FindDesignModes(scenario.machine, scenario.RunProgram());
  if (modes.modes.empty()) {
    throw ValidationError(args.file, "the machine has no participating mode along the moved axes (" + modes.axes +
                                         "): nothing to design for");
  }
  report.axes = modes.axes;
  report.max_table_length = scenario.controller.post_interp.max_table_length;
  BuildBands(args, modes, &report);
  controller::DesignSpec& spec = report.spec;
  spec.tolerance = args.tolerance;
  spec.derivatives = args.derivatives;
  spec.grid_s = report.form == DesignForm::kImpulses ? args.grid_s.value_or(kDefaultImpulseGridS)
                                                     : scenario.controller.period_s;
  spec.margin = args.margin.value_or(std::max(args.tolerance / 5.0, 1e-3));
  double lowest = spec.bands.front().frequency_lo_hz;
  for (const controller::DesignBand& b : spec.bands) lowest = std::min(lowest, b.frequency_lo_hz);
  spec.max_duration_s = std::max(kMaxDurationPeriods / lowest, spec.grid_s);
  ValidateSpec(spec);
  return report;
}

int DesignCommand(const DesignArgs& args) {
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  Doing("designing a pattern for " + args.file);
  Scenario scenario;
  DesignReport report = PrepareDesign(args, &scenario);
  try {
    report.result = controller::DesignPattern(report.spec);
  } catch (const controller::DesignError& error) {
    std::cerr << "error: " << args.file << ": design: " << Safe(error.what()) << "\n";
    return kExitSolverFailed;
  }
  if (args.registry) report.registry = controller::CompareRegistryShapers(report.spec);
  if (args.validate) {
    Doing("running the design across its bands (--validate) for " + args.file, RunMemory(scenario));
    report.validation = ValidateDesign(scenario, report.spec, report.result, report.form == DesignForm::kImpulses);
  }
  std::vector<std::string> written;
  if (!args.out_dir.empty()) {
    const DeferInterrupts defer;
    written = WriteDesignOutputs(args.out_dir, report);
    ThrowIfInterrupted("the output in " + args.out_dir + " is complete");
  }
  if (args.json) {
    std::cout << DesignJson(report).dump(2) << std::endl;
  } else {
    PrintDesignReport(std::cout, report);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

}  // namespace

Command AddDesignCommand(CLI::App* app) {
  auto args = std::make_shared<DesignArgs>();
  CLI::App* design = app->add_subcommand(
      "design", "the shortest pattern whose residual vibration stays within a tolerance over each mode's band");
  design->add_option("file", args->file, "scenario file (its machine's participating modes)")
      ->required()
      ->type_name("SCENARIO.yaml");
  AddSetOption(design, &args->sets);
  design->add_option("--band", args->bands, "the frequency band of mode MODE (0 the lowest), Hz; "
                                            "default every mode +/- 10% (repeatable)")
      ->type_name("MODE=LO:HI");
  design->add_option("--damping", args->dampings, "the damping ratio band of mode MODE; default the mode's own")
      ->type_name("MODE=LO:HI");
  design->add_option("--tolerance", args->tolerance, "the residual vibration V allowed over every band, in [0, 1) "
                                                     "(default 0.05)")
      ->type_name("V");
  design->add_option("--derivatives", args->derivatives,
                     "also zero the first N frequency derivatives of the residual at each band's centre, 0 to 4")
      ->type_name("N");
  design->add_option("--form", args->form, "profile_table (one coefficient per controller.period_s; default) or "
                                           "impulses (on --grid-s)")
      ->check(CLI::IsMember({"profile_table", "impulses"}));
  design->add_option("--grid-s", args->grid_s, "the impulses form's time grid, s (default 0.0001)")->type_name("S");
  design->add_option("--margin", args->margin, "the sampling margin: V between the band's samples stays within "
                                               "the tolerance plus this (default tolerance/5, at least 0.001)")
      ->type_name("M");
  design->add_flag("--registry,!--no-registry", args->registry,
                   "compare the registry's shapers and the patent's methods (default on)");
  design->add_flag("--validate", args->validate,
                   "run the scenario with the design across each band, one mode at a time, unshaped and shaped, "
                   "and report the worst residual ratio and peak_ratio");
  design->add_flag("--json", args->json, "print the design as one JSON object");
  design->add_option("--out", args->out_dir, "write design.json, design.yaml and design.png into DIR")
      ->type_name("DIR");
  design->footer("docs/design.md");
  return {design, [args] { return DesignCommand(*args); }};
}

}  // namespace shapebench::bench::cli
