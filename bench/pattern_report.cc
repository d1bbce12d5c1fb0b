#include "bench/pattern_report.h"

#include <cstdio>
#include <string>
#include <vector>

#include "controller/grid_realization.h"
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

  // Per unit a, as at the start of an acceleration from rest: nothing before the group,
  // and the steady acceleration is the largest one.
  const std::vector<controller::GridImpulse> table = controller::RealizeOnGrid(
      impulses, controller.period_s, config.frequency_hz, /*accel_before_m_s2=*/0.0,
      /*accel_limit_m_s2=*/1.0);
  out << "\nprofile table on the " << Num(controller.period_s) << " s period grid "
      << "(alpha_n at t = n * period_s; alpha_n not listed are 0)\n"
      << "  each impulse split between its neighbouring ticks, corrected to keep the design\n"
      << "  frequency's vibration phasor (controller::RealizeOnGrid, as the run uses it)\n"
      << "  n      t_s            alpha_n\n";
  std::vector<controller::Impulse> table_impulses;
  for (const auto& entry : table) {
    const double time_s = static_cast<double>(entry.tick) * controller.period_s;
    table_impulses.push_back({time_s, entry.amplitude});
    if (entry.amplitude == 0.0) continue;
    char line[96];
    std::snprintf(line, sizeof line, "  %-5ld  %-13.9g  %.9g\n", entry.tick, time_s,
                  entry.amplitude);
    out << line;
  }

  out << "\nresidual vibration at " << Num(config.frequency_hz)
      << " Hz (undamped; fraction of an unshaped step's)\n"
      << "  jerk impulses   " << Num(controller::ResidualVibration(impulses, config.frequency_hz), "%.3e")
      << "\n  profile table   "
      << Num(controller::ResidualVibration(table_impulses, config.frequency_hz), "%.3e") << "\n";
}

}  // namespace shapebench::bench
