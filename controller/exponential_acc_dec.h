// Post-interpolation exponential acc/dec (seed 004 paras. 26-32, the baseline the patent
// improves on): a first-order lag with time constant 1/K on the commanded velocity.
#pragma once

#include <vector>

#include "controller/command_trajectory.h"

namespace shapebench::controller {

// The lag on a sequence of per-period move pulses (pulses[k] is period k + 1), the pulse
// rate taken linear between ticks (the drive's view): an exact discretisation at the
// ticks. The tail runs until less than 1e-12 m is left, which goes into the last pulse:
// the output adds up to the input exactly.
std::vector<double> ExponentialAccDecPulses(const std::vector<double>& pulses,
                                            double time_constant_s, double period_s);

// The same on velocity samples (v_k = pulse of period k / period); ends at rest.
CommandTrajectory ApplyExponentialAccDec(const CommandTrajectory& input, double time_constant_s);

}  // namespace shapebench::controller
