// JP2551868B2 (seed 004), paras. 36-49: acceleration patterns tied to the natural period
// T that keep the peak deflection at the static one and leave no vibration. Every method
// is expressed as the patent's parameters (para. 49): step 1 (ST1, SR1), step 2 (ST2,
// SR2), then the steady acceleration; at the end of a phase the steps run reversed.
// Methods 1-4 are entries of the shaper registry (controller/shapers/patent_methods.cc,
// kind kPatentStep); a config becomes a StepPattern by MakeStepPattern
// (controller/shaper_registry.h). The shaper library beyond the patent is
// controller/shapers/; a StepPattern then carries the general impulse sequence instead
// of two steps.
#pragma once

#include <vector>

#include "controller/impulse.h"
#include "controller/pattern_config.h"

namespace shapebench::controller {

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

// The two steps of each method for one mode of period T, at the exact design times
// (at_start and at_end unset).
StepPattern Method1Steps(double period_s);             // para. 38: a/2 for T/2, then a
StepPattern Method2Steps(double period_s);             // para. 40: a for T/6, 0 for T/6
StepPattern Method3Steps(double k1, double period_s);  // paras. 43-44: K1 a, (1 - K1) a for t1
StepPattern Method4Steps(double t1_s, double period_s);  // para. 45: a for t1, a2 for T/2 - 2 t1

// ST1 and ST2 rounded to multiples of `resolution_s` (the patent sets them in 0.1 ms
// units); 0 keeps them exact.
StepPattern WithStepResolution(StepPattern pattern, double resolution_s);

// Method 3 (para. 44): t1 from cos(2 pi t1 / T) = 1 - 1 / (2 K1).
double Method3StepTime(double k1, double period_s);
// Method 4 (para. 45): a2 / a = 1 - 1 / (2 cos(2 pi t1 / T)).
double Method4SecondRatio(double t1_s, double period_s);

// The keys methods 3 and 4 read, checked against paras. 44 and 45; throw ValidationError
// naming "k1" or "t1_s".
void ValidateMethod3(const PatternConfig& config);
void ValidateMethod4(const PatternConfig& config);

// The jerk impulses of the shaped start of a phase (para. 61): amplitudes (summing to 1)
// at times 0, ST1, ST1 + ST2 — the continuous profile table of the pattern; for a
// library shaper, its impulse sequence (StepPattern::impulses).
std::vector<Impulse> PatternImpulses(const StepPattern& pattern);

}  // namespace shapebench::controller
