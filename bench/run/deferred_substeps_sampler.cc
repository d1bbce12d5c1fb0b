#include "bench/run/plant_sampler.h"

#include <cmath>

#include "bench/run/deferred_substeps.h"

// The deferred-substeps sampler (deferred_substeps.h): a single-axis run on the exact path
// whose tool error is its deflection steps each period to its end and writes its inner
// substeps only where they can change a metric.
namespace shapebench::bench {

// The tool error bounded by the deflection's bound needs the two rows to be one.
bool PlantSampler::QualifiesForDeferredSubsteps() const {
  const model::LinearPlant& plant = machine_.plant;
  return exact_extrema_ && watched_rows_.empty() && width_ == 2 && substeps_ > 1 &&
         integrator_->Capabilities().deferred_substeps && plan_.view.axis == single_.axis &&
         plant.C.row(model::kDeflectionRow + single_.axis) == plant.C.row(model::kToolErrorRow + single_.axis);
}

// SampleTick of a run with deferred substeps: the period stepped to its end; its inner
// substeps written and sampled only where they can change a metric (InnerSamplesMatter).
template <RunPhase P>
void PlantSampler::DeferredTick(std::size_t k) {
  integrator_->AdvancePeriodToEnd(samples_.AccelAt(k).data(), outputs_.data());
  const double y_end = outputs_[static_cast<std::size_t>((substeps_ - 1) * width_ + deflection_at_)];
  const double inside = integrator_->PeriodExtremum();
  // The motion-end tick's end sample alone opens the residual window: sampled in full.
  const bool inner = k == window_.motion_ticks || InnerSamplesMatter<P>(k, y_end, inside);
  period_start_m_ = y_end;
  if (!inner) {
    // No sample of the period, its end included, reaches a maximum so far; the end sample
    // can still be the last outside the settling band.
    ++result_.deferred_periods;
    if constexpr (P != RunPhase::kMotion) {
      if (std::abs(y_end) >= tally_.band) {
        tally_.last_outside_band = static_cast<long>(k) * substeps_;
        tally_.quiet_since_tick = k;
      }
    }
    return;
  }
  integrator_->WriteDeferredSubsteps(outputs_.data());
  TickTally tick = tally_.StartTick(P, k, window_.motion_ticks, substeps_);
  SampleSingleAxis<P>(k, &tick);
  tick.peak = std::max(tick.peak, inside);
  if constexpr (P == RunPhase::kWindow) {
    if (k != window_.motion_ticks) tick.residual = std::max(tick.residual, inside);
  }
  tally_.Merge(tick, k, substeps_);
}

// Whether a sample of period k (its end included) can change a metric: raise the peak,
// the residual peak or the contour error so far, or be the last outside the settling band
// while the period's end is inside it (the end sample alone, outside, is taken without the
// others). The deflection (= the tool error) of every sample is within InnerSampleBound;
// the tool position within that of the command's range over the period. NaN anywhere:
// they matter (the samples then check finiteness).
template <RunPhase P>
bool PlantSampler::InnerSamplesMatter(std::size_t k, double y_end, double inside) const {
  const double bound = InnerSampleBound(period_start_m_, y_end, inside, tally_.static_m);
  if (!(bound < tally_.peak)) return true;
  if constexpr (P != RunPhase::kMotion) {
    if (P == RunPhase::kWindow && !(bound < tally_.residual)) return true;
    if (!(bound < tally_.band) && !(std::abs(y_end) >= tally_.band)) return true;
  }
  const bool commanded = k <= samples_.n;
  const int ax = single_.axis;
  const double p0 = (commanded ? samples_.positions[k - 1] : samples_.positions.back())(ax);
  const double v0 = commanded ? samples_.velocity[k - 1](ax) : 0.0;
  double lo = 0.0;
  double hi = 0.0;
  QuadraticRange(p0, v0, 0.5 * samples_.AccelAt(k)(ax), dt_, &lo, &hi);
  const double off = OffLineBound(single_.start_m, single_.direction, single_.length_m, lo - bound, hi + bound);
  return off != 0.0 && !(off * off < tally_.contour_sq);
}

template void PlantSampler::DeferredTick<RunPhase::kMotion>(std::size_t);
template void PlantSampler::DeferredTick<RunPhase::kWindow>(std::size_t);
template void PlantSampler::DeferredTick<RunPhase::kTail>(std::size_t);

}  // namespace shapebench::bench
