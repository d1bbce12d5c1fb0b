// How long a run simulates and when it may stop. After the motion the run goes on for
// the residual window (three periods of the lowest mode), then a lowest-mode period at a
// time until a whole period stays inside the settling band, at most kMaxTailPeriods
// periods. An undamped structure under the kinematic drive stops at the window's end:
// nothing will ever damp what the window shows, and a longer tail would only repeat its
// oscillation (tests/bench/cosim_tail_test.cc).
#pragma once

#include <cstddef>
#include <vector>

#include "bench/run/command_samples.h"
#include "bench/scenario/scenario.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

struct RunWindow {
  static constexpr int kMaxTailPeriods = 30;
  static constexpr double kSettlingBand = 0.05;  // of the static displacement
  // A machine without modes has no natural period: its tail is this long.
  static constexpr double kRigidTailPeriodS = 0.1;

  std::size_t motion_ticks = 0;
  std::size_t residual_ticks = 0;  // three lowest-mode periods
  std::size_t period_ticks = 0;    // one lowest-mode period
  std::size_t max_ticks = 0;       // the tick the run stops at if it never settles
  bool never_settles_late = false;
  // Per cruise stretch, ascending: the tick one lowest-mode period into it, s - 1 +
  // period_ticks (<= e), whose state cruise_residual_ratio reads. Cruise: the commanded
  // feed constant and non-zero for at least one lowest-mode period in a row (ticks s..e).
  // Shorter constant stretches are steps of a pattern (method 2's zero step, T/6), not the
  // cruise whose vibration cruise_residual_ratio reports.
  std::vector<std::size_t> cruise_probe_ticks;

  std::size_t window_end() const { return motion_ticks + residual_ticks; }
  // Whether the run stops after tick k, the deflection last outside the settling band in
  // tick quiet_since_tick; `settled` tells why.
  bool Done(std::size_t k, std::size_t quiet_since_tick, bool* settled) const {
    if (k < window_end()) return false;
    if (k >= quiet_since_tick + period_ticks) {
      *settled = true;
      return true;
    }
    return never_settles_late;
  }
};

// Throws ValidationError("limits.max_simulated_s", "limits.max_ticks" or
// "limits.max_memory_mb") when the motion and its residual window exceed the scenario's
// limits (bench/scenario/run_memory.h for the memory).
RunWindow PlanRunWindow(const Scenario& scenario, const CommandSamples& samples,
                        const model::MachineDynamics& dynamics, double period_s);

// Output substeps per period when integrator.output_substeps is 0: at least 200 samples
// per period of the fastest participating mode (any axis), at most 64; 1 for a rigid
// machine. 200 samples bound a sampled peak's error by 1 - cos(pi/200) = 1.2e-4.
int AutoSubsteps(const model::MachineDynamics& dynamics, double period_s);

}  // namespace shapebench::bench
