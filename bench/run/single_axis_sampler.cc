// The single-axis sampler (plant_sampler.h): one axis' scalars while every other output of
// the period stays exactly 0; the general samples' arithmetic, component by component.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/run/plant_sampler.h"
#include "bench/run/single_axis.h"

namespace shapebench::bench {
namespace {

// One tick of single-axis samples (SingleAxis): the general samples' arithmetic, the other
// components left out; the same operations in the same order. A function of its own, kept
// out of line, so that its loop keeps every value in registers (inlined into the master's
// loop it spilled them). Returns whether a value was not finite (or a square overflowed).
template <RunPhase P>
[[gnu::noinline]] bool SampleSingleAxisTick(const SingleAxisSampling& in, double p0, double v0,
                                            double half_a, TickTally* out) {
  TickTally tick = *out;
  // An `or` of comparisons, not a running sum, keeps the samples independent.
  bool not_finite = false;
  for (int j = 0; j < in.substeps; ++j) {
    const double tau = in.taus[j];
    const double p = p0 + v0 * tau + half_a * tau * tau;
    const double actual = p + in.tool_errors[j * in.width];
    const double magnitude = std::abs(in.deflections[j * in.width]);
    const double along = std::clamp((actual - in.single.start_m) * in.single.direction, 0.0, in.single.length_m);
    const double off = actual - (in.single.start_m + along * in.single.direction);
    const double square = off * off;
    not_finite |= !(square + magnitude <= std::numeric_limits<double>::max());
    tick.Add<P>(j, magnitude, square);
  }
  *out = tick;
  return not_finite;
}

}  // namespace

// The single axis and the rows its samples read; every other row must stay exactly 0.
void PlantSampler::SetUpSingleAxis() {
  single_ = FindSingleAxis(samples_, plan_.view, contour_gauge_, plan_.has_stroke);
  if (single_.axis < 0 || rows_ != model::kNumOutputRows) return;
  for (int r = 0; r < rows_; ++r) {
    if (r % 3 != single_.axis && !(integrator_ && integrator_->OutputRowIsZero(r))) watched_rows_.push_back(r);
  }
  deflection_at_ = model::kDeflectionRow + single_.axis;
  tool_error_at_ = model::kToolErrorRow + single_.axis;
  // When every other row is 0 by the integrator's structure, only the axis' deflection
  // and tool error are asked for.
  if (watched_rows_.empty() && integrator_) {
    integrator_->SelectOutputs({deflection_at_, tool_error_at_});
    width_ = 2;
    deflection_at_ = 0;
    tool_error_at_ = 1;
  }
  single_sampling_ = {outputs_.data() + deflection_at_, outputs_.data() + tool_error_at_, plan_.taus_s.data(),
                      width_, substeps_, single_};
}

template <RunPhase P>
void PlantSampler::SampleSingleAxis(std::size_t k, TickTally* tick) {
  const bool commanded = k <= samples_.n;
  const int ax = single_.axis;
  const double p0 = (commanded ? samples_.positions[k - 1] : samples_.positions.back())(ax);
  const double v0 = commanded ? samples_.velocity[k - 1](ax) : 0.0;
  const bool not_finite = SampleSingleAxisTick<P>(single_sampling_, p0, v0, 0.5 * samples_.AccelAt(k)(ax), tick);
  if (integrator_ && not_finite) CheckFinite(k);  // throws for a non-finite output
}

template void PlantSampler::SampleSingleAxis<RunPhase::kMotion>(std::size_t, TickTally*);
template void PlantSampler::SampleSingleAxis<RunPhase::kWindow>(std::size_t, TickTally*);
template void PlantSampler::SampleSingleAxis<RunPhase::kTail>(std::size_t, TickTally*);

}  // namespace shapebench::bench
