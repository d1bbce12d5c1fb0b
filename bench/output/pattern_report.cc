#include "bench/output/pattern_report.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/profile_table.h"
#include "controller/shaper_registry.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::bench {
namespace {

using controller::PatternMode;

// The key, then what the registry entry says of it (ShaperEntry::summary), e.g.
// "3 (K1 a for t1, (1-K1) a for t1; k1 = 0.675)".
std::string MethodText(const controller::PatternConfig& pattern) {
  const controller::ShaperEntry& entry = controller::FindShaper(pattern.method);
  const std::string summary = entry.summary ? entry.summary(pattern) : entry.description;
  return summary.empty() ? entry.key : entry.key + " (" + summary + ")";
}

std::string FrequencyList(const std::vector<double>& frequencies) {
  std::string text;
  for (const double f : frequencies) text += (text.empty() ? "" : ", ") + FormatNumber(f, 6);
  return text;
}

std::string ModeText(PatternMode mode) {
  switch (mode) {
    case PatternMode::kOff: return "0 (off)";
    case PatternMode::kStart: return "1 (start of acc/dec only)";
    case PatternMode::kEnd: return "2 (end of acc/dec only)";
    case PatternMode::kBoth: return "3 (start and end of acc/dec)";
  }
  return "?";
}

void PrintStep(std::ostream& out, const char* name, const controller::AccelStep& step,
               int index) {
  out << "  ST" << index << " = " << FormatNumber(step.duration_s / 1e-4, 6) << " (0.1 ms units) = "
      << FormatNumber(step.duration_s, 9) << " s   SR" << index << " = " << FormatFixed(step.ratio, 6)
      << "   (" << name << ")\n";
}

// The table's coefficients of at least kShownFraction of the largest |alpha_n|, then a
// count and the sum of the rest: the grid correction (grid_realization.h) spreads
// impulses over many ticks in tiny amounts (a 3-impulse ZVD: 57 coefficients, 53 of
// them +-5e-6), which would bury the few that carry the shaping.
constexpr double kShownFraction = 1e-4;

void PrintProfileTable(std::ostream& out, const std::vector<double>& table, double period_s) {
  double largest = 0.0;
  for (const double alpha : table) largest = std::max(largest, std::abs(alpha));
  out << "  n      t_s            alpha_n   (listed: |alpha_n| >= " << FormatNumber(kShownFraction, 6)
      << " of the largest; alpha_n not listed are below it or 0)\n";
  std::size_t hidden = 0;
  double hidden_sum = 0.0;
  double hidden_largest = 0.0;
  for (std::size_t n = 0; n < table.size(); ++n) {
    const double time_s = static_cast<double>(n) * period_s;
    if (table[n] == 0.0) continue;
    if (std::abs(table[n]) < kShownFraction * largest) {
      ++hidden;
      hidden_sum += table[n];
      hidden_largest = std::max(hidden_largest, std::abs(table[n]));
      continue;
    }
    char line[96];
    std::snprintf(line, sizeof line, "  %-5zu  %-13.9g  %.9g\n", n, time_s, table[n]);
    out << line;
  }
  if (hidden > 0) {
    out << "  ... and " << hidden << " more below " << FormatNumber(kShownFraction, 6)
        << " of the largest (|alpha_n| <= " << FormatNumber(hidden_largest, 2) << ", sum "
        << FormatNumber(hidden_sum, 2) << ")\n";
  }
}

}  // namespace

PatternData ComputePattern(const controller::ControllerConfig& controller) {
  const controller::PatternConfig& config = controller.pattern;
  const controller::StepPattern pattern = controller::MakeStepPattern(config);
  const controller::GridDesign design = controller::ShaperGridDesign(config);
  PatternData data;
  data.shapes = pattern.shapes();
  data.design_frequencies_hz = config.DesignFrequencies();
  data.impulses = pattern.shapes() ? controller::ShaperImpulses(config) : controller::PatternImpulses(pattern);
  data.period_s = controller.period_s;
  // The profile_table realization: the same impulses as jerk coefficients on the period
  // grid (paras. 52-61), exactly as the controller builds the table.
  data.table = pattern.shapes() ? controller::ProfileTableFromImpulses(data.impulses, controller.period_s, design)
                                : std::vector<double>{1.0};
  const std::vector<controller::Impulse> table_impulses = controller::TableImpulses(data.table, data.period_s);
  // Each impulse rounded to its nearest tick, without the correction: what the grid
  // would leave without grid_realization.h.
  std::vector<controller::Impulse> rounded;
  for (const controller::Impulse& impulse : data.impulses) {
    rounded.push_back({std::round(impulse.time_s / controller.period_s) * controller.period_s,
                       impulse.amplitude});
  }
  for (const double f : data.design_frequencies_hz) {
    const double zeta = design.damping_ratio;
    data.residuals.push_back({f, zeta, controller::ResidualVibration(data.impulses, f, zeta),
                              controller::ResidualVibration(table_impulses, f, zeta),
                              controller::ResidualVibration(rounded, f, zeta)});
  }
  return data;
}

namespace {

// What the pattern is designed for: method, frequencies, damping, the steady acceleration.
void PrintPatternDesign(std::ostream& out, const controller::ControllerConfig& controller) {
  const controller::PatternConfig& config = controller.pattern;
  const double steady_accel_m_s2 =
      controller.accel_time_s > 0.0 ? controller.feed_m_s() / controller.accel_time_s : 0.0;

  const std::vector<double> frequencies = config.DesignFrequencies();
  const controller::GridDesign design = controller::ShaperGridDesign(config);
  out << "pattern\n"
      << "  method " << MethodText(config) << "\n";
  const bool from_machine = frequencies.size() == 1 ? config.frequency_from_machine : config.frequencies_from_machine;
  const char* machine_note = from_machine ? ", the machine's participating mode" : "";
  if (frequencies.size() == 1) {
    out << "  design frequency " << FormatNumber(frequencies.front(), 6) << " Hz (T = "
        << FormatNumber(1.0 / frequencies.front(), 6) << " s" << machine_note << ")\n";
  } else {
    out << "  design frequencies " << FrequencyList(frequencies)
        << " Hz (one shaper per frequency, convolved" << (from_machine ? "; the machine's participating modes" : "")
        << ")\n";
  }
  if (!design.damping_ratios.empty()) {
    out << "  design damping ratios " << FrequencyList(design.damping_ratios) << " (one per frequency"
        << (config.damping_from_machine ? ", the modes' own" : "") << ")\n";
  } else if (design.damping_ratio > 0.0) {
    out << "  design damping ratio " << FormatNumber(design.damping_ratio, 6)
        << (config.damping_from_machine ? " (the mode's own)" : "") << "\n";
  }
  out
      << "  steady acceleration a = " << FormatNumber(steady_accel_m_s2, 6) << " m/s^2 (feed "
      << FormatNumber(controller.feed_mm_min, 6) << " mm/min / accel_time_s "
      << FormatNumber(controller.accel_time_s, 6)
      << ")\n";
  if (config.step_resolution_s > 0.0) {
    out << "  step times rounded to " << FormatNumber(config.step_resolution_s, 6) << " s\n";
  }

}

// The shaper's steps (para. 49) or the library shaper's mode.
void PrintPatternSteps(std::ostream& out, const controller::PatternConfig& config,
                       const controller::StepPattern& pattern) {
  if (pattern.general()) {
    const bool patent = controller::FindShaper(config.method).kind == controller::ShaperKind::kPatentStep;
    out << "\nshaper ("
        << (patent ? "the patent's method, convolved per mode" : "library, controller/shaper_registry.h")
        << ")\n  mode = " << ModeText(config.mode) << "\n"
        << "  the steady acceleration of each acc/dec phase is convolved with the impulses below\n";
  } else {
    out << "\npara. 49 parameters\n";
    if (!pattern.shapes()) {
      // Method none acts as mode 0 whatever pattern.mode says.
      out << "  mode = " << ModeText(PatternMode::kOff)
          << (controller::FindShaper(config.method).kind == controller::ShaperKind::kNone
                  ? " (pattern.method " + config.method + ")"
                  : std::string()) << "\n"
          << "  no shaping: the acceleration steps straight to a\n";
    } else {
      out << "  mode = " << ModeText(config.mode) << "\n";
      PrintStep(out, "step 1", pattern.step1, 1);
      PrintStep(out, "step 2", pattern.step2, 2);
      out << "  then the steady acceleration (ratio 1); at the end of a phase the steps run in "
             "reverse order\n";
    }
  }

}

// The jerk impulses, the two realizations and the profile table.
void PrintImpulsesAndTable(std::ostream& out, const controller::ControllerConfig& controller,
                           const PatternData& data) {
  const controller::PatternConfig& config = controller.pattern;
  out << "\njerk impulses at the start of a phase (continuous time, per unit a)\n"
      << "  t_s            amplitude\n";
  for (const auto& impulse : data.impulses) {
    char line[96];
    std::snprintf(line, sizeof line, "  %-13.9g  %.9g\n", impulse.time_s, impulse.amplitude);
    out << line;
  }

  const std::vector<double>& table = data.table;
  const bool table_in_use = config.realization == controller::PatternRealization::kProfileTable;
  out << "\nrealizations (in use: " << (table_in_use ? "profile_table" : "stepped") << ")\n"
      << "  stepped: the steps above in the pre-interpolation linear acc/dec (paras. 36-50),\n"
      << "    each shaped start and end put on the tick grid keeping its vibration phasor\n"
      << "  profile_table: the impulses as jerk coefficients convolved with the move pulses\n"
      << "    after interpolation (paras. 52-61); it shapes every start and end (mode both)\n"
      << "\nprofile table on the " << FormatNumber(controller.period_s, 6) << " s period grid "
      << "(alpha_n at t = n * period_s; " << table.size()
      << " coefficients, at most post_interp.max_table_length = " << controller.post_interp.max_table_length
      << ")\n";
  PrintProfileTable(out, table, controller.period_s);

}

void PrintDesignResiduals(std::ostream& out, const PatternData& data) {
  for (const PatternResidual& residual : data.residuals) {
    const double zeta = residual.damping_ratio;
    out << "\nresidual vibration at " << FormatNumber(residual.frequency_hz, 6) << " Hz ("
        << (zeta > 0.0 ? "damping ratio " + FormatNumber(zeta, 6) : std::string("undamped"))
        << "; fraction of an unshaped step's)\n"
        << "  stepped (the step times as set)   " << FormatScientific(residual.stepped, 3)
        << "\n  profile_table (on the grid)      " << FormatScientific(residual.profile_table, 3) << "\n"
        << "  rounded to the nearest tick      " << FormatScientific(residual.rounded, 3)
        << "   (for comparison: no correction)\n";
  }
}

}  // namespace

void PrintPatternReport(std::ostream& out, const controller::ControllerConfig& controller) {
  const controller::PatternConfig& config = controller.pattern;
  const controller::StepPattern pattern = controller::MakeStepPattern(config);  // may throw: before any line
  PrintPatternDesign(out, controller);
  PrintPatternSteps(out, config, pattern);
  const PatternData data = ComputePattern(controller);
  PrintImpulsesAndTable(out, controller, data);
  PrintDesignResiduals(out, data);
}

namespace {

// When commanded motion ends: the tick after the last non-zero velocity (RunScenario's
// motion_time_s).
double MotionEndS(const controller::MultiAxisCommand& command) {
  std::size_t last_moving = 0;
  for (std::size_t k = 0; k <= command.num_ticks(); ++k) {
    if (command.velocity_m_s(k) != Eigen::Vector3d::Zero()) last_moving = k;
  }
  return static_cast<double>(std::min(last_moving + 1, command.num_ticks())) * command.period_s;
}

double MotionTimeS(const Scenario& scenario, const controller::ControllerConfig& controller) {
  controller::ControllerConfig c = controller;
  c.stroke_limits = scenario.machine.stroke_m;  // as RunScenario
  if (!scenario.program) controller::CheckShapedMove(c, std::abs(scenario.move.distance_mm) * 1e-3);
  return MotionEndS(controller::GenerateProgramCommand(c, scenario.RunProgram()));
}

// The residual vibration at every mode of every modelled axis of the scenario's machine,
// each with its own damping: the design frequency is one guess of them, a band of them
// or a second mode is what the machine actually has.
void PrintMachineModeResiduals(std::ostream& out, const Scenario& scenario) {
  out << "\nresidual vibration at the machine's modes (each with its own damping; fraction of an "
         "unshaped step's)\n";
  const std::vector<ModeResidual> modes = MachineModeResiduals(scenario);
  if (modes.empty()) {
    out << "  none: the machine model has no modes\n";
    return;
  }
  out << "  axis  mode  frequency_hz  damping_ratio  participation  stepped     profile_table\n";
  for (const ModeResidual& mode : modes) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-4s  %-4zu  %-12.6g  %-13.6g  %-13.6g  %-10.3e  %.3e\n",
                  model::AxisName(mode.axis), mode.mode, mode.frequency_hz, mode.damping_ratio,
                  mode.participation, mode.stepped, mode.profile_table);
    out << line;
  }
}

}  // namespace

std::vector<ModeResidual> MachineModeResiduals(const Scenario& scenario) {
  const PatternData data = ComputePattern(scenario.controller);
  const std::vector<controller::Impulse> table_impulses = controller::TableImpulses(data.table, data.period_s);
  std::vector<ModeResidual> residuals;
  for (const model::AxisModes& axis : model::AnalyzeMachineModes(scenario.machine)) {
    for (std::size_t m = 0; m < axis.analysis.modes.size(); ++m) {
      const model::ModeInfo& mode = axis.analysis.modes[m];
      residuals.push_back({axis.axis, m + 1, mode.frequency_hz, mode.damping_ratio, mode.participation,
                           controller::ResidualVibration(data.impulses, mode.frequency_hz, mode.damping_ratio),
                           controller::ResidualVibration(table_impulses, mode.frequency_hz, mode.damping_ratio)});
    }
  }
  return residuals;
}

PatternMotionTimes MotionTimesWithAndWithoutPattern(const Scenario& scenario) {
  const controller::ControllerConfig& controller = scenario.controller;
  PatternMotionTimes times;
  try {
    controller::ControllerConfig unshaped = controller;
    unshaped.pattern.method = controller::kNoShaping;
    unshaped.pattern.frequencies_hz.clear();
    unshaped.pattern.impulses.clear();
    unshaped.pattern.design_damping_ratio = 0.0;
    unshaped.pattern.damping_ratios.clear();
    const double shaped_s = MotionTimeS(scenario, controller);
    const double unshaped_s = MotionTimeS(scenario, unshaped);
    times.shaped_s = shaped_s;
    times.unshaped_s = unshaped_s;
  } catch (const ValidationError& error) {
    times.why_not = error.field() + ": " + error.message();
  }
  return times;
}

void PrintPatternReport(std::ostream& out, const Scenario& scenario) {
  const controller::ControllerConfig& controller = scenario.controller;
  PrintPatternReport(out, controller);
  PrintMachineModeResiduals(out, scenario);
  const controller::PatternConfig& config = controller.pattern;
  const controller::StepPattern pattern = controller::MakeStepPattern(config);
  out << "\ntime penalty (what the shaping costs the machine)\n";
  if (!pattern.shapes()) {
    out << "  none: no shaping\n";
    return;
  }
  const PatternData data = ComputePattern(controller);  // shaped: the shaper's impulses and table
  const std::vector<controller::Impulse>& impulses = data.impulses;
  const std::vector<double>& table = data.table;
  const bool table_in_use = config.realization == controller::PatternRealization::kProfileTable;
  out << "  shaper duration             " << FormatNumber(controller::ShaperDuration(impulses), 6)
      << " s (continuous); " << FormatNumber(static_cast<double>(table.size() - 1) * controller.period_s, 6)
      << " s on the grid (the table's last coefficient)\n";
  const std::string what = scenario.program
                               ? "the scenario's program"
                               : "the scenario's move (" + FormatNumber(scenario.move.distance_mm, 6) + " mm)";
  const PatternMotionTimes times = MotionTimesWithAndWithoutPattern(scenario);
  if (times.why_not.empty()) {
    out << "  motion time added           " << FormatNumber(times.shaped_s - times.unshaped_s, 6) << " s (" << what
        << ": " << FormatNumber(times.shaped_s, 6) << " s shaped, " << FormatNumber(times.unshaped_s, 6)
        << " s unshaped; realization "
        << (table_in_use ? "profile_table" : "stepped") << ", post_interp as set)\n";
  } else {
    out << "  motion time added           n/a (" << times.why_not << ")\n";
  }
  // Contour error at the programmed feed. The table filters each axis' pulses: on an arc
  // of radius r at speed v a filter of variance sigma^2 (of its coefficients as a
  // distribution in time) shrinks the radius by sigma^2 v^2 / (2 r) (small v / r;
  // 1 - |H(i v / r)|). Stepped shaping acts on the path speed before interpolation: the
  // tool stays on the programmed path.
  constexpr double kReferenceRadiusM = 0.010;
  // The programmed feed: the highest F of the program's cutting blocks (a `move:` and
  // blocks before the first F run at controller.feed_mm_min).
  double v = 0.0;
  for (const controller::ProgramBlock& block : scenario.RunProgram().blocks) {
    if (block.kind == controller::MotionKind::kRapid || block.kind == controller::MotionKind::kDwell) continue;
    v = std::max(v, std::isnan(block.feed_m_s) ? controller.feed_m_s() : block.feed_m_s);
  }
  if (v == 0.0) v = controller.feed_m_s();
  const double variance = controller::ShaperVariance(controller::TableImpulses(table, controller.period_s));
  const double radial_m = variance * v * v / (2.0 * kReferenceRadiusM);
  // Not small v / r: the steady state of the table on the circle, r (1 - |H(e^{i W T})|),
  // W = v / r (the chord's own sag left out).
  std::complex<double> response = 0.0;
  for (std::size_t n = 0; n < table.size(); ++n) {
    response += table[n] * std::polar(1.0, -v / kReferenceRadiusM * static_cast<double>(n) * controller.period_s);
  }
  const double steady_m = kReferenceRadiusM * (1.0 - std::abs(response));
  out << "  contour error at the feed   (the programmed feed " << FormatNumber(v * 60000.0, 6)
      << " mm/min, the highest of the program's, on an arc of reference radius 10 mm)\n";
  const bool per_axis = controller.post_interp.distribution == controller::Distribution::kPerAxis;
  auto row = [&](const std::string& name, bool in_use) {
    char text[64];
    std::snprintf(text, sizeof text, "    %-36s", (name + (in_use ? " (in use)" : "")).c_str());
    return std::string(text);
  };
  out << row("stepped", !table_in_use)
      << "0: the shaper acts on the path speed before interpolation; the tool stays on the path\n"
      << row("profile_table, per_axis", table_in_use && per_axis) << FormatNumber(radial_m * 1e6, 6)
      << " um radial (inward) = sigma^2 v^2 / (2 r), sigma = " << FormatNumber(std::sqrt(variance), 6)
      << " s the table's standard deviation\n"
      << row("", false) << "(steady state on that circle, r (1 - |H(v/r)|): " << FormatNumber(steady_m * 1e6, 6)
      << " um)\n"
      << row("profile_table, tangential", table_in_use && !per_axis)
      << "0 radial: seed 000's distribution keeps the tool on the interpolated path\n"
      << "    (post_interp's own filter adds its error in either case)\n";
}

}  // namespace shapebench::bench
