#include "bench/run/single_axis.h"

#include <cmath>

namespace shapebench::bench {

SingleAxis FindSingleAxis(const controller::PathElement* e, const CommandSamples& samples,
                          const OutputView& view, bool has_stroke) {
  SingleAxis none;
  if (e == nullptr || e->is_arc() || view.magnitude || has_stroke) return none;
  const int axis = view.axis;
  if (axis < 0 || std::abs(e->direction(axis)) != 1.0) return none;
  for (int a = 0; a < controller::kNumAxes; ++a) {
    if (a == axis) continue;
    if (e->direction(a) != 0.0 || samples.axis_moves[a]) return none;
    // Its velocities all (+ or -) 0, the axis' positions are its start plus sums of
    // zeros: each equals (==) the first.
    if (samples.positions.front()(a) != e->start_m(a)) return none;
  }
  return {axis, e->start_m(axis), e->direction(axis), e->length_m};
}

SingleAxis FindSingleAxis(const CommandSamples& samples, const OutputView& view,
                          const ContourGauge& gauge, bool has_stroke) {
  return FindSingleAxis(gauge.single(), samples, view, has_stroke);
}

}  // namespace shapebench::bench
