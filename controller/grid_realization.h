// Putting acceleration steps that fall between ticks onto the tick grid without losing
// the pattern's zero of vibration (the patent's para. 61 faces the same problem: method
// 2's jerks at 6.67 and 13.33 ms in a 1 ms profile table).
#pragma once

#include <vector>

#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

struct GridImpulse {
  long tick = 0;  // at t = tick * period_s
  double amplitude = 0.0;
};

// Realises one group of jerk impulses (acceleration steps) on the grid. Each impulse is
// first split between its two neighbouring ticks in proportion to its distance from them
// (which keeps the acceleration after the group and the velocity after the group exact:
// the zeroth and first moments). For a group of two or more impulses (a shaped phase
// start or end) the split weights are then corrected by the smallest change that also
// makes the group's vibration phasor at `design_frequency_hz` equal the ideal group's,
// so a pattern that cancels vibration at that frequency still cancels it exactly on the
// grid (the plain split leaves ~1% for method 2 at 25 Hz and 1 ms). The correction is
// the least-squares change of the acceleration over the group's span, made where the
// acceleration is below `accel_limit_m_s2` when that suffices, so that the run's largest
// acceleration is not raised. `accel_before_m_s2`: the acceleration before the group.
std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       double design_frequency_hz, double accel_before_m_s2,
                                       double accel_limit_m_s2);

}  // namespace shapebench::controller
