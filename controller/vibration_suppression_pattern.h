// JP2551868B2 (seed 004), paras. 36-49: acceleration patterns tied to the natural period
// T that keep the peak deflection at the static one and leave no vibration. Every method
// is expressed as the patent's parameters (para. 49): step 1 (ST1, SR1), step 2 (ST2,
// SR2), then the steady acceleration; at the end of a phase the steps run reversed.
// The shaper library beyond the patent (zv, zvd, zvdd, mzv, ei, um_zv, custom; several
// modes convolved) is controller/input_shaper.h; a StepPattern then carries the general
// impulse sequence instead of two steps.
#pragma once

#include <complex>
#include <vector>

namespace shapebench::controller {

// kMethod1..4: the patent's (this file); the others: the shaper library (input_shaper.h).
enum class PatternMethod {
  kNone, kMethod1, kMethod2, kMethod3, kMethod4,
  kZv, kZvd, kZvdd, kMzv, kEi, kUmZv, kCustom
};
bool IsPatentMethod(PatternMethod method);
// Para. 49 mode 0..3: off, start of acc/dec only, end only, both.
enum class PatternMode { kOff, kStart, kEnd, kBoth };
// How the pattern reaches the command (seed 004): `stepped`, acceleration steps of the
// pre-interpolation linear acc/dec (paras. 36-50); `profile_table`, the pattern's jerk
// impulses as a post-interpolation profile table convolved with the move pulses
// (paras. 52-61). A table shapes every speed change at both ends (mode both).
enum class PatternRealization { kStepped, kProfileTable };

// One impulse of a shaper: `amplitude` (a fraction of the step it shapes) at `time_s`.
struct Impulse {
  double time_s = 0.0;
  double amplitude = 0.0;
};

struct PatternConfig {
  PatternMethod method = PatternMethod::kNone;
  PatternMode mode = PatternMode::kBoth;
  double frequency_hz = 25.0;  // the natural frequency the pattern is designed for
  // Several modes at once: one shaper per frequency, convolved (input_shaper.h). Empty:
  // the single mode `frequency_hz`.
  std::vector<double> frequencies_hz;
  // Library shapers: the damping ratio of the mode(s) they are designed for, in [0, 1).
  double design_damping_ratio = 0.0;
  double vibration_tolerance = 0.05;  // ei: the residual allowed at the design frequency
  std::vector<Impulse> impulses;      // custom: amplitudes summing to 1, times ascending
  double k1 = 0.675;           // method 3: 0.5 <= k1 <= 1
  double t1_s = 0.004;         // method 4: 0 <= t1 <= T/6
  // Resolution of the step times. The patent's ST parameters are set in 0.1 ms units
  // (0.0001 here); 0 keeps the exact design times. Default exact: rounding method 2's
  // T/6 = 6.667 ms to 6.7 ms already leaves about 1% residual vibration per step pair.
  double step_resolution_s = 0.0;
  PatternRealization realization = PatternRealization::kStepped;
  void validate() const;  // throws ValidationError naming the field
  // The frequencies the pattern is designed for: frequencies_hz, else {frequency_hz}.
  std::vector<double> DesignFrequencies() const;
};

// One step of a pattern: the acceleration ratio SR held for ST seconds.
struct AccelStep {
  double duration_s = 0.0;  // ST
  double ratio = 0.0;       // SR, fraction of the steady acceleration
};

struct StepPattern {
  AccelStep step1;
  AccelStep step2;
  // A library shaper (or patent methods convolved for several modes): the phase is the
  // steady acceleration convolved with these impulses (linear_acc_dec.h); step1 and
  // step2 are then unused. Empty for the patent's two-step patterns.
  std::vector<Impulse> impulses;
  bool at_start = false;  // shape the start of each acc/dec phase
  bool at_end = false;    // shape the end of each acc/dec phase (steps reversed)

  bool shapes() const { return at_start || at_end; }
  bool general() const { return !impulses.empty(); }
  // Velocity gained by steps 1 and 2 per unit steady acceleration: SR1*ST1 + SR2*ST2.
  double velocity_per_accel_s() const {
    return step1.ratio * step1.duration_s + step2.ratio * step2.duration_s;
  }
};

// The patent's two steps for methods 1-4 at one frequency; otherwise the general impulse
// sequence of ShaperImpulses (input_shaper.h).
StepPattern MakeStepPattern(const PatternConfig& config);

// Method 3 (para. 44): t1 from cos(2 pi t1 / T) = 1 - 1 / (2 K1).
double Method3StepTime(double k1, double period_s);
// Method 4 (para. 45): a2 / a = 1 - 1 / (2 cos(2 pi t1 / T)).
double Method4SecondRatio(double t1_s, double period_s);

// The jerk impulses of the shaped start of a phase (para. 61): amplitudes (summing to 1)
// at times 0, ST1, ST1 + ST2 — the continuous profile table of the pattern; for a
// library shaper, its impulse sequence (StepPattern::impulses).
std::vector<Impulse> PatternImpulses(const StepPattern& pattern);

// Residual vibration of an impulse sequence at frequency f and damping ratio zeta, as a
// fraction of the vibration an unshaped step leaves: |sum A_j e^{(zeta w + i w_d) t_j}|
// normalised by the last impulse's decay (the standard shaper formula).
double ResidualVibration(const std::vector<Impulse>& impulses, double frequency_hz,
                         double damping_ratio = 0.0);

}  // namespace shapebench::controller
