// Putting acceleration steps that fall between ticks onto the tick grid without losing
// the pattern's zero of vibration (JP2551868B2 (seed 004) para. 61 faces the same problem:
// method 2's jerks at 6.67 and 13.33 ms in a 1 ms profile table).
#pragma once

#include <utility>
#include <vector>

#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

// The design point(s) whose vibration the grid realization keeps: one or several
// natural frequencies of modes with one damping ratio, or one each. A single frequency converts
// implicitly (seed 004's case: one undamped mode).
struct GridDesign {
  GridDesign() = default;
  GridDesign(double frequency_hz) : frequencies_hz{frequency_hz} {}  // NOLINT: implicit
  GridDesign(std::vector<double> frequencies, double damping)
      : frequencies_hz(std::move(frequencies)), damping_ratio(damping) {}
  std::vector<double> frequencies_hz;
  double damping_ratio = 0.0;
  // One damping ratio per frequency (modes of their own damping); empty: damping_ratio.
  std::vector<double> damping_ratios;
  double DampingAt(std::size_t j) const { return damping_ratios.empty() ? damping_ratio : damping_ratios[j]; }
};

struct GridImpulse {
  long tick = 0;  // at t = tick * period_s
  double amplitude = 0.0;
};

// Realises one group of jerk impulses (acceleration steps) on the grid. Each impulse is
// first split between its two neighbouring ticks in proportion to its distance from them
// (which keeps the acceleration after the group and the velocity after the group exact:
// the zeroth and first moments). For a group of two or more impulses (a shaped phase
// start or end) the split weights are then corrected by the smallest change that also
// makes the group's vibration phasor at every design frequency equal the ideal group's,
// so a pattern that cancels vibration there still cancels it exactly on the grid (the
// plain split leaves ~1% for method 2 at 25 Hz and 1 ms). With damping the phasor is the
// damped one, sum A_j e^{(zeta w + i w_d) t_j} (the residual of a mode of that damping
// after the group, up to a common decay), so a damped design keeps its zero too.
// The correction is the least-squares change of the acceleration over the group's span
// (it needs at least 1 + 2 x frequencies periods there), made where the acceleration is
// below `accel_limit_m_s2` when that suffices, so that the run's largest acceleration is
// not raised. `accel_before_m_s2`: the acceleration before the group.
std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       const GridDesign& design, double accel_before_m_s2,
                                       double accel_limit_m_s2);

}  // namespace shapebench::controller
