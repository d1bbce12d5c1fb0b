// Post-interpolation exponential acc/dec (seed 004 paras. 26-32, the baseline the patent
// improves on): a first-order lag with time constant 1/K on the commanded velocity.
#pragma once

#include "controller/command_trajectory.h"

namespace shapebench::controller {

// Exact (zero-order-hold) discretisation of the lag on the velocity samples. The tail is
// run until the remaining distance is below `tail_tolerance_m`; the last sample then
// lands on zero, so the filtered move covers the input distance to that tolerance.
CommandTrajectory ApplyExponentialAccDec(const CommandTrajectory& input,
                                         double time_constant_s,
                                         double tail_tolerance_m = 1e-12);

}  // namespace shapebench::controller
