// JP2551868B2 (seed 004) paras. 36-49; see the header.
#include "controller/vibration_suppression_pattern.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/input_shaper.h"

namespace shapebench::controller {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string Num(double v) { return FormatNumber(v); }

double Quantize(double duration_s, double resolution_s) {
  if (resolution_s <= 0.0) return duration_s;
  return std::round(duration_s / resolution_s) * resolution_s;
}

}  // namespace

bool IsPatentMethod(PatternMethod method) {
  return method == PatternMethod::kMethod1 || method == PatternMethod::kMethod2 ||
         method == PatternMethod::kMethod3 || method == PatternMethod::kMethod4;
}

std::vector<double> PatternConfig::DesignFrequencies() const {
  return frequencies_hz.empty() ? std::vector<double>{frequency_hz} : frequencies_hz;
}

void PatternConfig::validate() const {
  if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
    throw ValidationError("frequency_hz", "must be a finite number > 0 (got " + Num(frequency_hz) + ")");
  }
  // The library's keys (frequencies_hz, design_damping_ratio, vibration_tolerance,
  // impulses) and the shapers they design (input_shaper.h).
  ValidateShaperKeys(*this);
  // Para. 44: cos(2 pi t1/T) = 1 - 1/(2 K1) has a solution only for K1 in [0.5, 1].
  if (method == PatternMethod::kMethod3 && !(k1 >= 0.5 && k1 <= 1.0)) {
    throw ValidationError("k1", "must be in [0.5, 1] for method 3 (0.5 is method 1, 1 is method 2; got " +
                                    Num(k1) + ")");
  }
  // Para. 45: a2 >= 0 needs cos(2 pi t1/T) >= 1/2, i.e. t1 <= T/6 (at every design
  // frequency when several are given).
  for (const double f : DesignFrequencies()) {
    const double period_s = 1.0 / f;
    if (method == PatternMethod::kMethod4 && !(t1_s >= 0.0 && t1_s <= period_s / 6.0 * (1 + 1e-12))) {
      throw ValidationError("t1_s", "must be in [0, T/6] = [0, " + Num(period_s / 6.0) +
                                        "] s for method 4 at " + Num(f) + " Hz (got " + Num(t1_s) + ")");
    }
  }
  if (!(std::isfinite(step_resolution_s) && step_resolution_s >= 0.0)) {
    throw ValidationError("step_resolution_s", "must be >= 0 (0 keeps exact step times; got " +
                                                   Num(step_resolution_s) + ")");
  }
}

double Method3StepTime(double k1, double period_s) {
  return period_s * std::acos(1.0 - 1.0 / (2.0 * k1)) / (2.0 * kPi);
}

double Method4SecondRatio(double t1_s, double period_s) {
  return 1.0 - 1.0 / (2.0 * std::cos(2.0 * kPi * t1_s / period_s));
}

StepPattern MakeStepPattern(const PatternConfig& config) {
  StepPattern pattern;
  if (config.method == PatternMethod::kNone || config.mode == PatternMode::kOff) return pattern;
  const std::vector<double> frequencies = config.DesignFrequencies();
  if (!IsPatentMethod(config.method) || frequencies.size() > 1) {
    // The library (or the patent's methods convolved for several modes): the general
    // impulse sequence, applied by convolution (linear_acc_dec.h).
    pattern.impulses = ShaperImpulses(config);
    pattern.at_start = config.mode == PatternMode::kStart || config.mode == PatternMode::kBoth;
    pattern.at_end = config.mode == PatternMode::kEnd || config.mode == PatternMode::kBoth;
    return pattern;
  }
  const double period_s = 1.0 / frequencies.front();
  switch (config.method) {
    case PatternMethod::kMethod1:  // para. 38: a/2 for T/2, then a
      pattern.step1 = {period_s / 2.0, 0.5};
      break;
    case PatternMethod::kMethod2:  // para. 40: a for T/6, 0 for T/6, then a
      pattern.step1 = {period_s / 6.0, 1.0};
      pattern.step2 = {period_s / 6.0, 0.0};
      break;
    case PatternMethod::kMethod3: {  // para. 43-44: K1 a for t1, (1 - K1) a for t1
      const double t1 = Method3StepTime(config.k1, period_s);
      pattern.step1 = {t1, config.k1};
      pattern.step2 = {t1, 1.0 - config.k1};
      break;
    }
    case PatternMethod::kMethod4:  // para. 45: a for t1, a2 for T/2 - 2 t1
      pattern.step1 = {config.t1_s, 1.0};
      pattern.step2 = {period_s / 2.0 - 2.0 * config.t1_s,
                       Method4SecondRatio(config.t1_s, period_s)};
      break;
    default:  // kNone and the library: handled above
      break;
  }
  pattern.step1.duration_s = Quantize(pattern.step1.duration_s, config.step_resolution_s);
  pattern.step2.duration_s = Quantize(pattern.step2.duration_s, config.step_resolution_s);
  pattern.at_start = config.mode == PatternMode::kStart || config.mode == PatternMode::kBoth;
  pattern.at_end = config.mode == PatternMode::kEnd || config.mode == PatternMode::kBoth;
  return pattern;
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

double ResidualVibration(const std::vector<Impulse>& impulses, double frequency_hz,
                         double damping_ratio) {
  if (impulses.empty()) return 0.0;
  const double w = 2.0 * kPi * frequency_hz;
  const double wd = w * std::sqrt(1.0 - damping_ratio * damping_ratio);
  const double t_last = impulses.back().time_s;
  double c = 0.0;
  double s = 0.0;
  double total = 0.0;
  for (const Impulse& impulse : impulses) {
    // Decay measured from the last impulse keeps the exponentials <= 1.
    const double decay = std::exp(-damping_ratio * w * (t_last - impulse.time_s));
    c += impulse.amplitude * decay * std::cos(wd * impulse.time_s);
    s += impulse.amplitude * decay * std::sin(wd * impulse.time_s);
    total += impulse.amplitude;
  }
  return std::hypot(c, s) / std::abs(total);
}

}  // namespace shapebench::controller
