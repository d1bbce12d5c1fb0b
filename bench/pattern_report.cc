#include "bench/pattern_report.h"

#include <cstdio>
#include <string>
#include <vector>

#include "controller/profile_table.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::bench {
namespace {

using controller::PatternMethod;
using controller::PatternMode;

std::string Num(double value, const char* format = "%.6g") {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string MethodText(const controller::PatternConfig& pattern) {
  switch (pattern.method) {
    case PatternMethod::kNone: return "none";
    case PatternMethod::kMethod1: return "1 (a/2 for T/2, then a)";
    case PatternMethod::kMethod2: return "2 (a for T/6, 0 for T/6, then a)";
    case PatternMethod::kMethod3: return "3 (K1 a for t1, (1-K1) a for t1; k1 = " + Num(pattern.k1) + ")";
    case PatternMethod::kMethod4: return "4 (a for t1, a2 for T/2 - 2 t1; t1 = " + Num(pattern.t1_s) + " s)";
  }
  return "?";
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
  out << "  ST" << index << " = " << Num(step.duration_s / 1e-4) << " (0.1 ms units) = "
      << Num(step.duration_s, "%.9g") << " s   SR" << index << " = " << Num(step.ratio, "%.6f")
      << "   (" << name << ")\n";
}

}  // namespace

void PrintPatternReport(std::ostream& out, const controller::ControllerConfig& controller) {
  const controller::PatternConfig& config = controller.pattern;
  const controller::StepPattern pattern = controller::MakeStepPattern(config);
  const double natural_period_s = 1.0 / config.frequency_hz;
  const double steady_accel_m_s2 =
      controller.accel_time_s > 0.0 ? controller.feed_m_s() / controller.accel_time_s : 0.0;

  out << "pattern\n"
      << "  method " << MethodText(config) << "\n"
      << "  design frequency " << Num(config.frequency_hz) << " Hz (T = "
      << Num(natural_period_s) << " s)\n"
      << "  steady acceleration a = " << Num(steady_accel_m_s2) << " m/s^2 (feed "
      << Num(controller.feed_mm_min) << " mm/min / accel_time_s " << Num(controller.accel_time_s)
      << ")\n";
  if (config.step_resolution_s > 0.0) {
    out << "  step times rounded to " << Num(config.step_resolution_s) << " s\n";
  }

  out << "\npara. 49 parameters\n";
  if (!pattern.shapes()) {
    // Method none acts as mode 0 whatever pattern.mode says.
    out << "  mode = " << ModeText(PatternMode::kOff)
        << (config.method == PatternMethod::kNone ? " (pattern.method none)" : "") << "\n"
        << "  no shaping: the acceleration steps straight to a\n";
  } else {
    out << "  mode = " << ModeText(config.mode) << "\n";
    PrintStep(out, "step 1", pattern.step1, 1);
    PrintStep(out, "step 2", pattern.step2, 2);
    out << "  then the steady acceleration (ratio 1); at the end of a phase the steps run in "
           "reverse order\n";
  }

  const std::vector<controller::Impulse> impulses = controller::PatternImpulses(pattern);
  out << "\njerk impulses at the start of a phase (continuous time, per unit a)\n"
      << "  t_s            amplitude\n";
  for (const auto& impulse : impulses) {
    char line[96];
    std::snprintf(line, sizeof line, "  %-13.9g  %.9g\n", impulse.time_s, impulse.amplitude);
    out << line;
  }

  // The profile_table realization: the same impulses as jerk coefficients on the period
  // grid (paras. 52-61), exactly as the controller builds the table.
  const std::vector<double> table =
      pattern.shapes() ? controller::ProfileTableFromPattern(pattern, controller.period_s, config.frequency_hz)
                       : std::vector<double>{1.0};
  const bool table_in_use = config.realization == controller::PatternRealization::kProfileTable;
  out << "\nrealizations (in use: " << (table_in_use ? "profile_table" : "stepped") << ")\n"
      << "  stepped: the steps above in the pre-interpolation linear acc/dec (paras. 36-50),\n"
      << "    each shaped start and end put on the tick grid keeping its vibration phasor\n"
      << "  profile_table: the impulses as jerk coefficients convolved with the move pulses\n"
      << "    after interpolation (paras. 52-61); it shapes every start and end (mode both)\n"
      << "\nprofile table on the " << Num(controller.period_s) << " s period grid "
      << "(alpha_n at t = n * period_s; alpha_n not listed are 0; " << table.size()
      << " coefficients, at most post_interp.max_table_length = " << controller.post_interp.max_table_length
      << ")\n"
      << "  n      t_s            alpha_n\n";
  std::vector<controller::Impulse> table_impulses;
  for (std::size_t n = 0; n < table.size(); ++n) {
    const double time_s = static_cast<double>(n) * controller.period_s;
    table_impulses.push_back({time_s, table[n]});
    if (table[n] == 0.0) continue;
    char line[96];
    std::snprintf(line, sizeof line, "  %-5zu  %-13.9g  %.9g\n", n, time_s, table[n]);
    out << line;
  }

  out << "\nresidual vibration at " << Num(config.frequency_hz)
      << " Hz (undamped; fraction of an unshaped step's)\n"
      << "  stepped (the step times as set)   "
      << Num(controller::ResidualVibration(impulses, config.frequency_hz), "%.3e")
      << "\n  profile_table (on the grid)      "
      << Num(controller::ResidualVibration(table_impulses, config.frequency_hz), "%.3e") << "\n";
}

}  // namespace shapebench::bench
