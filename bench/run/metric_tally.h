// The metric tally: what every sampler accumulates sample by sample and hands to the one
// FinishMetrics (finish_metrics.h). A tick's samples go into a TickTally first and then into
// the run's MetricTally with one merge, which keeps the samples independent of each other
// (no chain of a dependent max per sample) and gives the same values: max is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>

namespace shapebench::bench {

// Where tick k lies: the motion (k < motion_ticks), the residual window (motion_ticks <=
// k <= motion_ticks + residual_ticks; at k == motion_ticks only the tick's last sample,
// the one at motion's end, counts as after the motion) or the settling tail.
enum class RunPhase { kMotion, kWindow, kTail };

// One tick's samples.
struct TickTally {
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

// The ticks where the run's maxima were first reached (bench/run/metric_sources.h turns them
// into blocks and lines): kept beside the maxima, by the samplers that step every tick
// (the closed form skips ticks; a traced run's general sampler gives them).
struct SourceTicks {
  std::size_t peak = 0;     // the tick holding peak
  std::size_t contour = 0;  // contour_sq
  std::size_t cruise = 0;   // the cruise probe holding cruise_m
  bool stepped = false;     // set by a sampler that keeps them
};

// The run's: the per-sample maxima, then what the sampler concludes at the end. Every
// field FinishMetrics reads is here, so a sampler cannot leave a metric out.
struct MetricTally {
  // The static reference of the ratios: the deflection under the largest held commanded
  // acceleration, and that deflection per axis (StaticDisplacement, finish_metrics.h).
  double static_m = 0.0;
  Eigen::Vector3d static_vector = Eigen::Vector3d::Zero();
  double band = 0.0;  // RunWindow::kSettlingBand x static_m
  // No static solve (a plant FMU without static_compliance outputs): static_displacement_m,
  // its ratios and settling_time_s are n/a.
  bool static_unknown = false;

  double peak = 0.0;
  double contour_sq = 0.0;
  double residual = 0.0;
  long last_outside_band = -1;   // the last sample (count from t = 0) outside the band
  std::size_t quiet_since_tick = 0;

  double residual_m = 0.0;  // the free vibration at motion end (at rest, rigid: none)
  double cruise_m = NAN;    // the largest at the cruise probes; NaN without one
  Eigen::Vector3d peak_axes = Eigen::Vector3d::Zero();  // per axis, |deflection|
  double overshoot_m = 0.0;                              // beyond the stroke
  double radial_error_m = NAN;                           // arcs only
  // A plant with nonlinear elements: its free response's half peak-to-peak (NaN: none
  // sampled), where it came to rest, its largest quadrant glitch.
  bool nonlinear = false;
  double free_half_range_m = NAN;
  double dead_band_m = NAN;
  double quadrant_glitch_m = NAN;

  std::size_t last_tick = 0;  // the run's end
  bool settled = false;
  SourceTicks sources;

  void SetStatic(double static_displacement_m, const Eigen::Vector3d& vector, double settling_band) {
    static_m = static_displacement_m;
    static_vector = vector;
    band = settling_band * static_displacement_m;
  }

  TickTally StartTick(RunPhase phase, std::size_t k, std::size_t motion_ticks, int substeps) const {
    TickTally tick;
    tick.band = band;
    tick.first_after_motion = phase == RunPhase::kWindow && k == motion_ticks ? substeps - 1 : 0;
    return tick;
  }

  // Tick k's samples into the run's.
  void Merge(const TickTally& tick, std::size_t k, int substeps) {
    if (tick.peak > peak) sources.peak = k;
    if (tick.contour_sq > contour_sq) sources.contour = k;
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
