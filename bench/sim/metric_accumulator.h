// The deflection metrics of a run, accumulated sample by sample. The per-sample kernel
// (TickAccumulator::Add) is written once and specialised per phase of the run; a tick's
// samples go into a TickAccumulator first and then into the run's with one merge, which
// keeps the samples independent of each other (no chain of a dependent max per sample)
// and gives the same values: max is exact, and a non-finite sample ends the run anyway.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace shapebench::bench {

// Where tick k lies: the motion (k < motion_ticks), the residual window (motion_ticks <=
// k <= motion_ticks + residual_ticks; at k == motion_ticks only the tick's last sample,
// the one at motion's end, counts as after the motion) or the settling tail.
enum class RunPhase { kMotion, kWindow, kTail };

// One tick's samples.
struct TickAccumulator {
  double peak = 0.0;        // largest |deflection| (the view's scalar)
  double contour_sq = 0.0;  // largest squared contour error
  double residual = 0.0;    // largest |deflection| in the residual window (residual_peak_m)
  int last_outside = -1;    // the last sample (0-based) outside the settling band
  int first_after_motion = 0;  // samples before this one are still the motion's
  double band = 0.0;

  // Sample j (0-based) of the tick: |deflection| and the squared contour error.
  template <RunPhase P>
  void Add(int j, double magnitude, double square) {
    peak = std::max(peak, magnitude);
    contour_sq = std::max(contour_sq, square);
    if constexpr (P != RunPhase::kMotion) {
      if (j >= first_after_motion) {
        if constexpr (P == RunPhase::kWindow) residual = std::max(residual, magnitude);
        if (magnitude >= band) last_outside = j;
      }
    }
  }
};

// The run's.
struct RunAccumulator {
  double peak = 0.0;
  double contour_sq = 0.0;
  double residual = 0.0;
  long last_outside_band = -1;   // the last sample (count from t = 0) outside the band
  std::size_t quiet_since_tick = 0;
  double band = 0.0;             // kSettlingBand x static displacement

  TickAccumulator StartTick(RunPhase phase, std::size_t k, std::size_t motion_ticks, int substeps) const {
    TickAccumulator tick;
    tick.band = band;
    tick.first_after_motion = phase == RunPhase::kWindow && k == motion_ticks ? substeps - 1 : 0;
    return tick;
  }

  // Tick k's samples into the run's.
  void Merge(const TickAccumulator& tick, std::size_t k, int substeps) {
    peak = std::max(peak, tick.peak);
    contour_sq = std::max(contour_sq, tick.contour_sq);
    residual = std::max(residual, tick.residual);
    if (tick.last_outside >= 0) {
      last_outside_band = static_cast<long>((k - 1) * static_cast<std::size_t>(substeps)) + tick.last_outside + 1;
      quiet_since_tick = k;
    }
  }
};

}  // namespace shapebench::bench
