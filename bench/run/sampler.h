// A sampler: the strategy that steps the plant (or its closed form) through the run's
// ticks and turns its outputs into the metric tally. The master (run_scenario.cc) builds the
// RunPlan, chooses a sampler, runs it, and finishes the metrics from the
// tally; every sampler runs the same tick loop (RunTicks), with its own Tick inlined.
#pragma once

#include <cstddef>

#include "bench/run/metric_tally.h"
#include "bench/run/run_window.h"

namespace shapebench::bench {

class Sampler {
 public:
  virtual ~Sampler() = default;
  // Ticks 1.. until the run ends, then what the tally needs from the sampler's own state
  // (its peaks per axis, the residual vibration, ...). Throws model::SolverError.
  virtual MetricTally Run() = 0;
};

// The one tick loop (FMI order inside each Tick: set the input, step, read the outputs).
// S::Tick(k) returns the last tick it advanced through (k, or more for a sampler that
// steps stretches of ticks in one go); S::SettleTail(k) ends the run at the residual
// window's end when the tail is known without simulating it. S::CheckWork(k) throws when
// the run's work through tick k exceeds limits.max_work (run_work.h) and returns how many
// ticks later to look again; the last look is at the end, so the verdict is the whole
// count's, wherever the looks fell.
template <class S>
void RunTicks(S& sampler, const RunWindow& window, MetricTally* tally) {
  std::size_t next_work_check = 1;
  for (std::size_t k = 1; k <= window.max_ticks; ++k) {
    k = sampler.Tick(k);
    tally->last_tick = k;
    if (k >= next_work_check) next_work_check = k + sampler.CheckWork(k);
    if (window.Done(k, tally->quiet_since_tick, &tally->settled)) break;
    if (sampler.SettleTail(k)) break;
  }
  sampler.CheckWork(tally->last_tick);
}

}  // namespace shapebench::bench
