#include "controller/interpolator.h"

#include <algorithm>

namespace shapebench::controller {
namespace {

// PathGeometry::PointAt(s, &hint), in its two parts: the element (the hint walked on),
// then the point on it. Within one line the pulse needs no point (it is ds times the
// direction), so the point is computed only where it is used, from the element the
// tick found: the same numbers, once per element change instead of once per tick.
Eigen::Vector3d PointOn(const PathGeometry& path, std::size_t element, double s_m) {
  const std::vector<PathElement>& elements = path.elements();
  if (elements.empty()) return path.start_m();
  const PathElement& e = elements[element];
  if (e.length_m == 0.0) return e.end_m;
  return e.PointAtFraction((s_m - e.start_s_m) / e.length_m);
}

int BlockAt(const std::vector<PathElement>& elements, std::size_t element) {
  return elements.empty() ? -1 : elements[element].block;
}

// The common run of ticks inside one line of positive length, ticks k..last at most: the
// general tick of Interpolate with its answers known (the hint stays, the pulse is ds
// times the direction, no stop), in a loop with no calls, so the position stays in a
// register. The first tick it left to the general one.
std::size_t AlongLine(const PathElement& line, const double* speed, double period_s, std::size_t k,
                      std::size_t last, double* s_m, InterpolatedPulses* out) {
  double s = *s_m;
  const double start_s = line.start_s_m;
  const double end_s = line.end_s_m();
  const Eigen::Vector3d direction = line.direction;
  const int block = line.block;
  for (; k <= last; ++k) {
    const double ds = speed[k] * period_s;
    const double s_next = s + ds;
    if (!(s_next >= start_s && s_next <= end_s)) break;
    out->axis_pulses_m[k - 1] = ds * direction;
    out->tangential_pulses_m[k - 1] = ds;
    out->path_position_m[k] = s_next;
    out->block[k] = block;
    s = s_next;
  }
  *s_m = s;
  return k;
}

}  // namespace

InterpolatedPulses Interpolate(const PathGeometry& path, const SpeedPlan& plan, double period_s) {
  InterpolatedPulses out;
  const std::size_t n = plan.speed_m_s.size() - 1;
  out.axis_pulses_m.reserve(n + 1);  // GenerateProgramCommand may append the rest pulse
  out.axis_pulses_m.resize(n);
  out.tangential_pulses_m.resize(n);
  out.path_position_m.resize(n + 1);
  out.block.resize(n + 1);
  std::size_t next_stop = 0;
  double s = 0.0;
  const std::vector<PathElement>& elements = path.elements();
  std::size_t hint = elements.empty() ? 0 : path.ElementAt(0.0, 0);
  std::size_t point_element = hint;  // where `s` was found (the previous tick's point)
  out.path_position_m[0] = 0.0;
  out.block[0] = BlockAt(elements, hint);
  const PathElement none;
  const double* speed = plan.speed_m_s.data();
  for (std::size_t k = 1; k <= n; ++k) {
    if (!elements.empty() && hint == point_element) {
      const PathElement& line = elements[hint];
      if (!line.is_arc() && line.length_m > 0.0) {
        // Up to the next motion end.
        while (next_stop < plan.stops.size() && plan.stops[next_stop].first < k) ++next_stop;
        const std::size_t stop_k = next_stop < plan.stops.size() ? plan.stops[next_stop].first : n + 1;
        k = AlongLine(line, speed, period_s, k, std::min(n, stop_k - 1), &s, &out);
        if (k > n) break;
      }
    }
    const double ds = speed[k] * period_s;
    double s_next = s + ds;
    // Land exactly on each motion's end, so rounding never carries over.
    while (next_stop < plan.stops.size() && plan.stops[next_stop].first < k) ++next_stop;
    if (next_stop < plan.stops.size() && plan.stops[next_stop].first == k) {
      // The pulse keeps v_k * period (the acceleration the acc/dec planned, exactly);
      // the ~1e-14 m the summed pulses differ from the motion's length is not carried on.
      s_next = plan.stops[next_stop].second;
    }
    const std::size_t element_before = hint;
    if (!elements.empty()) {
      // ElementAt(s_next, hint), whose answer is the hint itself while s_next stays inside
      // a line of positive length (the common case, checked first).
      const PathElement& current = elements[hint];
      const bool inside = s_next >= current.start_s_m && s_next <= current.end_s_m() &&
                          current.length_m > 0.0;
      if (!inside) hint = path.ElementAt(s_next, hint);
    }
    const PathElement& e = elements.empty() ? none : elements[hint];
    Eigen::Vector3d& pulse = out.axis_pulses_m[k - 1];
    if (hint == element_before && !e.is_arc() && e.length_m > 0.0) {
      pulse = ds * e.direction;  // within one line: exact, no differencing
    } else {
      pulse = PointOn(path, hint, s_next) - PointOn(path, point_element, s);
    }
    out.tangential_pulses_m[k - 1] = ds;
    out.path_position_m[k] = s_next;
    out.block[k] = BlockAt(elements, hint);
    s = s_next;
    point_element = hint;
  }
  return out;
}

}  // namespace shapebench::controller
