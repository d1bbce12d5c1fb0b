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

ContourGauge::ContourGauge(const controller::PathGeometry& path, const std::vector<double>& path_position_m,
                           double period_s, double lag_s)
    : path_(path), positions_(path_position_m) {
  const auto& elements = path.elements();
  if (elements.size() == 1 && !elements.front().is_arc()) single_ = &elements.front();
  exact_ = true;
  for (const controller::PathElement& e : elements) {
    if (e.is_arc() && (e.rise_m != 0.0 || e.start_radius_m != e.end_radius_m)) exact_ = false;
  }
  lag_ticks_ = static_cast<std::size_t>(std::ceil(std::max(lag_s, 0.0) / period_s)) + 1;
  last_element_ = elements.empty() ? 0 : elements.size() - 1;
}

void ContourGauge::MoveTo(std::size_t k) {
  const std::size_t n = path_.elements().size();
  if (single_ != nullptr || n == 0 || positions_.empty()) return;
  // The interpolator's ticks lag_ticks_ before the period's start and two after its end.
  constexpr std::size_t kAheadTicks = 2;
  constexpr std::size_t kSpareElements = 2;
  const std::size_t m = positions_.size() - 1;
  const std::size_t lo_k = std::min(k > lag_ticks_ + 1 ? k - lag_ticks_ - 1 : 0, m);
  const std::size_t hi_k = std::min(k + kAheadTicks, m);
  lo_hint_ = path_.ElementAt(positions_[lo_k], lo_hint_);
  hi_hint_ = path_.ElementAt(positions_[hi_k], std::max(hi_hint_, lo_hint_));
  first_ = lo_hint_ > kSpareElements ? lo_hint_ - kSpareElements : 0;
  last_element_ = std::min(hi_hint_ + kSpareElements, n - 1);
}

double ContourLag(const controller::MultiAxisCommand& command, const model::DriveConfig& drive) {
  double lag_s = command.filter_lag_s;
  if (drive.type == model::DriveType::kServo) {
    lag_s += 10.0 / drive.servo.position_gain_1_s;
    if (drive.servo.velocity_loop_hz > 0.0) lag_s += 10.0 / (2.0 * kPi * drive.servo.velocity_loop_hz);
  }
  return lag_s;
}

}  // namespace shapebench::bench
