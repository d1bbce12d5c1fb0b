// JP2551868B2 (seed 004) paras. 36-49; see the header.
#include "controller/vibration_suppression_pattern.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"

namespace shapebench::controller {
namespace {

double Quantize(double duration_s, double resolution_s) {
  if (resolution_s <= 0.0) return duration_s;
  return std::round(duration_s / resolution_s) * resolution_s;
}

}  // namespace

double Method3StepTime(double k1, double period_s) {
  return period_s * std::acos(1.0 - 1.0 / (2.0 * k1)) / (2.0 * kPi);
}

double Method4SecondRatio(double t1_s, double period_s) {
  return 1.0 - 1.0 / (2.0 * std::cos(2.0 * kPi * t1_s / period_s));
}

StepPattern Method1Steps(double period_s) {
  StepPattern pattern;
  pattern.step1 = {period_s / 2.0, 0.5};
  return pattern;
}

StepPattern Method2Steps(double period_s) {
  StepPattern pattern;
  pattern.step1 = {period_s / 6.0, 1.0};
  pattern.step2 = {period_s / 6.0, 0.0};
  return pattern;
}

StepPattern Method3Steps(double k1, double period_s) {
  StepPattern pattern;
  const double t1 = Method3StepTime(k1, period_s);
  pattern.step1 = {t1, k1};
  pattern.step2 = {t1, 1.0 - k1};
  return pattern;
}

StepPattern Method4Steps(double t1_s, double period_s) {
  StepPattern pattern;
  pattern.step1 = {t1_s, 1.0};
  pattern.step2 = {period_s / 2.0 - 2.0 * t1_s, Method4SecondRatio(t1_s, period_s)};
  return pattern;
}

StepPattern WithStepResolution(StepPattern pattern, double resolution_s) {
  pattern.step1.duration_s = Quantize(pattern.step1.duration_s, resolution_s);
  pattern.step2.duration_s = Quantize(pattern.step2.duration_s, resolution_s);
  return pattern;
}

void ValidateMethod3(const PatternConfig& config) {
  // Para. 44: cos(2 pi t1/T) = 1 - 1/(2 K1) has a solution only for K1 in [0.5, 1].
  const double k1 = config.k1;
  if (!(k1 >= 0.5 && k1 <= 1.0)) {
    throw ValidationError("k1", "must be in [0.5, 1] for method 3 (0.5 is method 1, 1 is method 2; got " +
                                    FormatNumber(k1) + ")");
  }
}

void ValidateMethod4(const PatternConfig& config) {
  // Para. 45: a2 >= 0 needs cos(2 pi t1/T) >= 1/2, i.e. t1 <= T/6 (at every design
  // frequency when several are given).
  const double t1_s = config.t1_s;
  for (const double f : config.DesignFrequencies()) {
    const double period_s = 1.0 / f;
    if (!(t1_s >= 0.0 && t1_s <= period_s / 6.0 * (1 + 1e-12))) {
      throw ValidationError("t1_s", "must be in [0, T/6] = [0, " + FormatNumber(period_s / 6.0) +
                                        "] s for method 4 at " + FormatNumber(f) + " Hz (got " + FormatNumber(t1_s) + ")");
    }
  }
}

std::vector<Impulse> PatternImpulses(const StepPattern& pattern) {
  if (pattern.general()) return pattern.impulses;
  // The acceleration steps SR1 -> SR2 -> 1 as jerk impulses (para. 61's J_n / A).
  const double times[3] = {0.0, pattern.step1.duration_s,
                           pattern.step1.duration_s + pattern.step2.duration_s};
  const double levels[3] = {pattern.step1.ratio, pattern.step2.ratio, 1.0};
  std::vector<Impulse> impulses;
  double previous_level = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double amplitude = levels[i] - previous_level;
    previous_level = levels[i];
    if (!impulses.empty() && impulses.back().time_s == times[i]) {
      impulses.back().amplitude += amplitude;  // a zero-length step merges with the next
    } else {
      impulses.push_back({times[i], amplitude});
    }
  }
  std::vector<Impulse> nonzero;
  for (const Impulse& impulse : impulses) {
    if (impulse.amplitude != 0.0) nonzero.push_back(impulse);
  }
  return nonzero;
}

}  // namespace shapebench::controller
