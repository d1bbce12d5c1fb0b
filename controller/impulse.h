// Impulse sequences: what every shaper is (controller/shaper_registry.h). The helpers
// here know nothing of any particular shaper: convolution, the residual vibration a
// sequence leaves, its moments.
#pragma once

#include <vector>

namespace shapebench::controller {

// One impulse of a shaper: `amplitude` (a fraction of the step it shapes) at `time_s`.
struct Impulse {
  double time_s = 0.0;
  double amplitude = 0.0;
};

// The convolution of two impulse sequences (impulses closer than 1e-12 s merged).
std::vector<Impulse> ConvolveImpulses(const std::vector<Impulse>& a, const std::vector<Impulse>& b);

// The sequence with its amplitudes divided by their sum (so they sum to 1).
std::vector<Impulse> NormalisedImpulses(std::vector<Impulse> impulses);

// Residual vibration of an impulse sequence at frequency f and damping ratio zeta, as a
// fraction of the vibration an unshaped step leaves: |sum A_j e^{(zeta w + i w_d) t_j}|
// normalised by the last impulse's decay (the standard shaper formula).
double ResidualVibration(const std::vector<Impulse>& impulses, double frequency_hz,
                         double damping_ratio = 0.0);

// The impulses of a profile table (alpha_n at t = n period_s).
std::vector<Impulse> TableImpulses(const std::vector<double>& table, double period_s);

// Duration (last impulse time), mean time sum A_j t_j and variance sum A_j (t_j - mean)^2
// of an impulse sequence with amplitudes summing to 1.
double ShaperDuration(const std::vector<Impulse>& impulses);
double ShaperMeanTime(const std::vector<Impulse>& impulses);
double ShaperVariance(const std::vector<Impulse>& impulses);

}  // namespace shapebench::controller
