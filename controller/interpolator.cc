#include "controller/interpolator.h"

#include <algorithm>

namespace shapebench::controller {

InterpolatedPulses Interpolate(const PathGeometry& path, const SpeedPlan& plan, double period_s) {
  InterpolatedPulses out;
  const std::size_t n = plan.speed_m_s.size() - 1;
  out.axis_pulses_m.reserve(n);
  out.tangential_pulses_m.reserve(n);
  out.path_position_m.reserve(n + 1);
  out.block.reserve(n + 1);
  std::size_t hint = 0;
  std::size_t next_stop = 0;
  double s = 0.0;
  Eigen::Vector3d point = path.PointAt(0.0, &hint);
  auto block_at = [&](std::size_t element) {
    return path.elements().empty() ? -1 : path.elements()[element].block;
  };
  out.path_position_m.push_back(0.0);
  out.block.push_back(block_at(hint));
  for (std::size_t k = 1; k <= n; ++k) {
    double ds = plan.speed_m_s[k] * period_s;
    double s_next = s + ds;
    // Land exactly on each motion's end, so rounding never carries over.
    while (next_stop < plan.stops.size() && plan.stops[next_stop].first < k) ++next_stop;
    if (next_stop < plan.stops.size() && plan.stops[next_stop].first == k) {
      // The pulse keeps v_k * period (the acceleration the acc/dec planned, exactly);
      // the ~1e-14 m the summed pulses differ from the motion's length is not carried on.
      s_next = plan.stops[next_stop].second;
    }
    const std::size_t element_before = hint;
    const Eigen::Vector3d next = path.PointAt(s_next, &hint);
    const PathElement& e = path.elements().empty() ? PathElement{} : path.elements()[hint];
    Eigen::Vector3d pulse;
    if (hint == element_before && !e.is_arc() && e.length_m > 0.0) {
      pulse = ds * e.direction;  // within one line: exact, no differencing
    } else {
      pulse = next - point;
    }
    out.axis_pulses_m.push_back(pulse);
    out.tangential_pulses_m.push_back(ds);
    out.path_position_m.push_back(s_next);
    out.block.push_back(block_at(hint));
    s = s_next;
    point = next;
  }
  return out;
}

}  // namespace shapebench::controller
