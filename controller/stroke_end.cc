#include "controller/stroke_end.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::controller {

void StrokeEndConfig::validate() const {
  if (look_ahead_blocks < 1) {
    throw ValidationError("look_ahead_blocks", "must be >= 1 (got " + std::to_string(look_ahead_blocks) + ")");
  }
  if (!(std::isfinite(minute_feed_mm_min) && minute_feed_mm_min > 0.0)) {
    throw ValidationError("minute_feed_mm_min", "must be > 0 (got " + FormatNumber(minute_feed_mm_min) + ")");
  }
}

double StrokeOvershoot(const Eigen::Vector3d& p, const StrokeLimits& limits) {
  double beyond = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (!limits[a]) continue;
    beyond = std::max({beyond, (*limits[a])[0] - p(a), p(a) - (*limits[a])[1]});
  }
  return beyond;
}

std::optional<double> FindStrokeCrossing(const PathGeometry& path, const StrokeLimits& limits) {
  auto outside = [&](const Eigen::Vector3d& p) { return StrokeOvershoot(p, limits) > 0.0; };
  if (outside(path.start_m())) return 0.0;
  for (const PathElement& e : path.elements()) {
    if (e.length_m == 0.0) continue;
    // Lines are straight: their end decides. Arcs are walked along the curve in steps
    // of at most 1 degree (a chord then cannot jump over a crossing by more than the
    // sagitta r (1 - cos 0.5 deg) = 4e-5 r), then the crossing is bisected. The short pi
    // is kept, not kPi: with kPi a full circle takes 360 steps instead of 361.
    const int steps = e.is_arc() ? std::max(4, static_cast<int>(std::ceil(std::abs(e.sweep_rad) / (3.14159265358979 / 180.0))))
                                 : 1;
    double u_prev = 0.0;
    for (int i = 1; i <= steps; ++i) {
      const double u = static_cast<double>(i) / steps;
      if (!outside(e.PointAtFraction(u))) {
        u_prev = u;
        continue;
      }
      double lo = u_prev, hi = u;
      for (int k = 0; k < 100 && (hi - lo) * e.length_m > 1e-13; ++k) {
        const double mid = 0.5 * (lo + hi);
        (outside(e.PointAtFraction(mid)) ? hi : lo) = mid;
      }
      return e.start_s_m + hi * e.length_m;
    }
  }
  return std::nullopt;
}

}  // namespace shapebench::controller
