#include "bench/run/path_tallies.h"

#include <algorithm>
#include <cmath>

namespace shapebench::bench {

ReversalWindows::ReversalWindows(const controller::PathElement& element) : arc(&element) {
  const double quarter = 0.5 * kPi;
  const double a0 = element.start_angle_rad;
  const double a1 = a0 + element.sweep_rad;
  const double lo = std::min(a0, a1) + kHalfWidthRad;
  const double hi = std::max(a0, a1) - kHalfWidthRad;
  for (double k = std::ceil(lo / quarter); k * quarter <= hi; k += 1.0) angle_rad.push_back(k * quarter);
  max_radius_m.assign(angle_rad.size(), -HUGE_VAL);
  min_radius_m.assign(angle_rad.size(), HUGE_VAL);
}

void ReversalWindows::Add(double path_s, const Eigen::Vector3d& actual) {
  const controller::PathElement& e = *arc;
  if (path_s < e.start_s_m || path_s > e.end_s_m() || !(e.length_m > 0.0)) return;
  const double u = (path_s - e.start_s_m) / e.length_m;
  const double commanded = e.start_angle_rad + u * e.sweep_rad;
  const double dx = actual(e.axis0) - e.center_m(e.axis0);
  const double dy = actual(e.axis1) - e.center_m(e.axis1);
  // The sample's angle on the commanded angle's turn (the command and the tool are close).
  const double angle = commanded + std::remainder(std::atan2(dy, dx) - commanded, 2.0 * kPi);
  const double fraction = e.sweep_rad != 0.0 ? std::clamp((angle - e.start_angle_rad) / e.sweep_rad, 0.0, 1.0) : 0.0;
  const double programmed = e.start_radius_m + (e.end_radius_m - e.start_radius_m) * fraction;
  const double deviation = std::hypot(dx, dy) - programmed;
  if (u >= 0.25 && u <= 0.75) middle_m.push_back(deviation);
  for (std::size_t i = 0; i < angle_rad.size(); ++i) {
    if (std::abs(angle - angle_rad[i]) <= kHalfWidthRad) {
      max_radius_m[i] = std::max(max_radius_m[i], deviation);
      min_radius_m[i] = std::min(min_radius_m[i], deviation);
    }
  }
}

double ReversalWindows::Glitch() const {
  double glitch = NAN;
  if (middle_m.empty()) return glitch;
  std::vector<double> sorted = middle_m;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double baseline = *mid;
  for (std::size_t i = 0; i < angle_rad.size(); ++i) {
    if (max_radius_m[i] < min_radius_m[i]) continue;  // no sample in this window
    const double spike = std::max(max_radius_m[i] - baseline, baseline - min_radius_m[i]);
    if (std::isnan(glitch) || spike > glitch) glitch = spike;
  }
  return glitch;
}

}  // namespace shapebench::bench
