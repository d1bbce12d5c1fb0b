// When a period's inner output substeps can be left unstepped (a single-axis run on the
// exact path without a trace, deferred_substeps_sampler.cc): its metrics are maxima and a last sample outside
// a band, and the deflection's largest |value| over the whole period is known exactly
// from its ends and its in-tick extremum (model/tick_extremum.h). An inner sample can
// change a metric only if that bound reaches the run's value so far (or the settling
// band); otherwise only the period's end sample is taken, which is computed with the same
// arithmetic either way (ExactIntegrator::AdvancePeriodToEnd). Where a bound reaches a
// metric, the master writes the inner substeps after all (WriteDeferredSubsteps) and
// samples them as before, so every metric is the same bit for bit as with every substep.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace shapebench::bench {

// The samples' own rounding against the closed forms: the substeps' outputs are products
// of the discretisation (its exponential good to ~1e-15 of the state's scale), the
// extremum a modal closed form. 1e-9 of the run's scale is far above both.
constexpr double kDeferredMargin = 1e-9;

// No sample strictly inside the period has a |deflection| above this: the largest of
// |y| at its ends and inside it, plus the margin of the run's scale (static displacement).
// NaN when any of them is (the caller then samples every substep, which checks them).
inline double InnerSampleBound(double start, double end, double inside, double scale) {
  if (std::isnan(start + end + inside)) return NAN;
  const double largest = std::max(std::max(std::abs(start), std::abs(end)), inside);
  return largest + kDeferredMargin * (largest + scale);
}

// The range of p0 + v0 t + half_a t^2 over t in [0, h] (the command on the axis).
inline void QuadraticRange(double p0, double v0, double half_a, double h, double* lo, double* hi) {
  const double end = p0 + v0 * h + half_a * h * h;
  *lo = std::min(p0, end);
  *hi = std::max(p0, end);
  if (half_a != 0.0) {
    const double t = -v0 / (2.0 * half_a);
    if (t > 0.0 && t < h) {
      const double vertex = p0 + v0 * t + half_a * t * t;
      *lo = std::min(*lo, vertex);
      *hi = std::max(*hi, vertex);
    }
  }
}

// The distance from the line (start, direction +-1, length, along one axis) of a sample
// whose tool position lies in [lo, hi] on the axis, as SampleSingleAxisTick computes it
// (the tool clamped onto the line): a bound of its magnitude, or 0 when it is exactly 0
// for every such sample (a line from 0 and the tool strictly within it: the clamp is not
// taken and 0 + (x - 0) is x exactly). The rounding term covers the samples' own
// arithmetic (a few ulps of the coordinates).
inline double OffLineBound(double start, double direction, double length, double lo, double hi) {
  const double along_lo = direction > 0.0 ? lo - start : start - hi;
  const double along_hi = direction > 0.0 ? hi - start : start - lo;
  const double rounding =
      8.0 * std::numeric_limits<double>::epsilon() * (std::abs(start) + std::max(std::abs(lo), std::abs(hi)) + length);
  if (start == 0.0 && along_lo > rounding && along_hi < length - rounding) return 0.0;
  return std::max(0.0, std::max(-along_lo, along_hi - length)) + rounding;
}

}  // namespace shapebench::bench
