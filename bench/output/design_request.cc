// The request of `design` (CLI and Python) to its report; see the header.
#include "bench/output/design_request.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "bench/config/override.h"
#include "bench/output/pattern_report.h"
#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/scenario_loader.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

// A band left to the mode: its frequency +/- this fraction, its own damping ratio.
constexpr double kDefaultBandFraction = 0.10;
// The impulses form's grid when --grid-s is not given: the patent's 0.1 ms step units.
constexpr double kDefaultImpulseGridS = 1e-4;
// The longest pattern searched, in periods of the lowest band's lowest frequency.
constexpr double kMaxDurationPeriods = 20.0;

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
void BuildBands(const DesignRequest& args, const DesignModes& modes, DesignReport* report) {
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

// The motion time of `base`'s move or program with `pattern` and `post_interp` in place of
// its own (NaN when it cannot be planned).
double MotionTimeWith(const Scenario& base, const controller::PatternConfig& pattern,
                      const controller::PostInterpConfig& post_interp) {
  Scenario s = base;
  const controller::PatternConfig& own = base.controller.pattern;
  s.controller.pattern = pattern;
  s.controller.pattern.mode = own.mode;
  s.controller.pattern.realization = own.realization;
  s.controller.pattern.step_resolution_s = own.step_resolution_s;
  s.controller.post_interp = post_interp;
  return MotionTimesWithAndWithoutPattern(s).shaped_s;
}

// `impulses` as a custom pattern, realised on the period grid for the bands' centres.
controller::PatternConfig CustomPattern(const std::vector<controller::Impulse>& impulses,
                                        const controller::DesignSpec& spec) {
  controller::PatternConfig pattern;
  pattern.method = "custom";
  pattern.impulses = impulses;
  for (const controller::DesignBand& band : spec.bands) {
    pattern.frequencies_hz.push_back(0.5 * (band.frequency_lo_hz + band.frequency_hi_hz));
    pattern.damping_ratios.push_back(0.5 * (band.damping_lo + band.damping_hi));
  }
  return pattern;
}

// The motion time the design and each registry entry add to the scenario's move or
// program, over no shaping at all (pattern none, no post-interpolation filter).
void AddMotionTimes(const Scenario& scenario, DesignReport* report) {
  const controller::PostInterpConfig no_filter;
  const double unshaped = MotionTimeWith(scenario, controller::PatternConfig{}, no_filter);
  if (report->form == DesignForm::kImpulses) {
    report->added_motion_time_s =
        MotionTimeWith(scenario, CustomPattern(DesignImpulses(report->result), report->spec), no_filter) - unshaped;
  } else {
    controller::PostInterpConfig table;
    table.type = controller::PostInterpType::kProfileTable;
    table.table = report->result.coefficients;
    table.max_table_length = std::max<int>(table.max_table_length, static_cast<int>(table.table.size()));
    report->added_motion_time_s = MotionTimeWith(scenario, controller::PatternConfig{}, table) - unshaped;
  }
  for (const controller::ShaperAgainstSpec& s : report->registry) {
    report->registry_added_time_s.push_back(MotionTimeWith(scenario, CustomPattern(s.impulses, report->spec),
                                                           no_filter) - unshaped);
  }
}

}  // namespace

DesignReport PrepareDesign(const DesignRequest& args, Scenario* loaded) {
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


void FinishDesign(const DesignRequest& request, const Scenario& scenario, DesignReport* report) {
  if (request.registry) report->registry = controller::CompareRegistryShapers(report->spec);
  AddMotionTimes(scenario, report);
}

DesignReport ComputeDesign(const DesignRequest& request) {
  Scenario scenario;
  DesignReport report = PrepareDesign(request, &scenario);
  report.result = controller::DesignPattern(report.spec);
  FinishDesign(request, scenario, &report);
  if (request.validate) {
    report.validation = ValidateDesign(scenario, report.spec, report.result, report.form == DesignForm::kImpulses);
  }
  return report;
}

}  // namespace shapebench::bench
