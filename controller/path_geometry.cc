#include "controller/path_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/math_constants.h"

namespace shapebench::controller {
namespace {

// End points closer than this in the arc plane make a full circle (the builder's own
// tolerance is far coarser: 1e-6 mm would already be a different program).
constexpr double kFullCircleM = 1e-9;

// Angle in [0, 2 pi).
double Wrap(double angle) {
  double a = std::fmod(angle, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a;
}

PathElement MakeElement(const ProgramBlock& block, int index) {
  PathElement e;
  e.kind = block.kind;
  e.block = index;
  e.start_m = block.start_m;
  e.end_m = block.end_m;
  e.dwell_s = block.dwell_s;
  if (block.kind == MotionKind::kDwell) {
    e.end_m = block.start_m;
    return e;
  }
  if (!e.is_arc()) {
    const Eigen::Vector3d d = block.end_m - block.start_m;
    e.length_m = d.norm();
    if (e.length_m > 0.0) e.direction = d / e.length_m;
    return e;
  }
  const PlaneAxes axes = AxesOf(block.plane);
  e.axis0 = axes.u;
  e.axis1 = axes.v;
  e.normal = axes.n;
  e.center_m = block.center_m;
  const double s0 = block.start_m(e.axis0) - block.center_m(e.axis0);
  const double s1 = block.start_m(e.axis1) - block.center_m(e.axis1);
  const double f0 = block.end_m(e.axis0) - block.center_m(e.axis0);
  const double f1 = block.end_m(e.axis1) - block.center_m(e.axis1);
  e.start_radius_m = std::hypot(s0, s1);
  e.end_radius_m = std::hypot(f0, f1);
  e.start_angle_rad = std::atan2(s1, s0);
  const double end_angle = std::atan2(f1, f0);
  const bool full = std::hypot(f0 - s0, f1 - s1) <= kFullCircleM;
  if (block.kind == MotionKind::kArcCcw) {
    e.sweep_rad = full ? kTwoPi : Wrap(end_angle - e.start_angle_rad);
    if (e.sweep_rad == 0.0) e.sweep_rad = kTwoPi;
  } else {
    e.sweep_rad = full ? -kTwoPi : -Wrap(e.start_angle_rad - end_angle);
    if (e.sweep_rad == 0.0) e.sweep_rad = -kTwoPi;
  }
  e.rise_m = block.end_m(e.normal) - block.start_m(e.normal);
  const double mean_radius = 0.5 * (e.start_radius_m + e.end_radius_m);
  e.length_m = std::hypot(mean_radius * std::abs(e.sweep_rad), e.rise_m);
  return e;
}

}  // namespace

Eigen::Vector3d PathElement::PointAtFraction(double u) const {
  if (u >= 1.0) return end_m;
  if (u <= 0.0) return start_m;
  if (!is_arc()) return start_m + (end_m - start_m) * u;
  if (blend) {
    const double angle = u * sweep_rad;
    return center_m + start_radius_m * (std::cos(angle) * u_dir + std::sin(angle) * v_dir);
  }
  const double angle = start_angle_rad + u * sweep_rad;
  const double radius = start_radius_m + u * (end_radius_m - start_radius_m);
  Eigen::Vector3d p;
  p(axis0) = center_m(axis0) + radius * std::cos(angle);
  p(axis1) = center_m(axis1) + radius * std::sin(angle);
  p(normal) = start_m(normal) + u * rise_m;
  return p;
}

Eigen::Vector3d PathElement::TangentAtFraction(double u) const {
  if (length_m == 0.0) return Eigen::Vector3d::Zero();
  if (!is_arc()) return direction;
  if (blend) return -std::sin(u * sweep_rad) * u_dir + std::cos(u * sweep_rad) * v_dir;
  const double angle = start_angle_rad + u * sweep_rad;
  const double radius = start_radius_m + u * (end_radius_m - start_radius_m);
  const double dr = end_radius_m - start_radius_m;
  Eigen::Vector3d d;
  d(axis0) = -radius * std::sin(angle) * sweep_rad + dr * std::cos(angle);
  d(axis1) = radius * std::cos(angle) * sweep_rad + dr * std::sin(angle);
  d(normal) = rise_m;
  return d.normalized();
}

Eigen::Vector3d PathElement::NearestPoint(const Eigen::Vector3d& p) const {
  if (length_m == 0.0) return start_m;
  if (!is_arc()) {
    const double along = std::clamp((p - start_m).dot(direction), 0.0, length_m);
    return start_m + along * direction;
  }
  // The nearest point of a plane arc lies at p's own angle when that angle is on the arc,
  // else at an end; for a helix this is the usual close estimate.
  const Eigen::Vector3d from_centre = p - center_m;
  const double angle = blend ? std::atan2(from_centre.dot(v_dir), from_centre.dot(u_dir))
                             : std::atan2(from_centre(axis1), from_centre(axis0));
  const double from_start = sweep_rad > 0.0 ? Wrap(angle - start_angle_rad) : Wrap(start_angle_rad - angle);
  Eigen::Vector3d best = (p - start_m).norm() <= (p - end_m).norm() ? start_m : end_m;
  if (from_start <= std::abs(sweep_rad)) {
    const Eigen::Vector3d on_arc = PointAtFraction(from_start / std::abs(sweep_rad));
    if ((p - on_arc).norm() < (p - best).norm()) best = on_arc;
  }
  return best;
}

PathGeometry::PathGeometry(const Program& program) : start_m_(program.start_m) {
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    PathElement e = MakeElement(program.blocks[i], static_cast<int>(i));
    e.source_start_s_m = length_m_;
    e.source_length_m = e.length_m;
    Append(e);
  }
}

PathGeometry::PathGeometry(const Eigen::Vector3d& start_m, std::vector<PathElement> elements) : start_m_(start_m) {
  for (PathElement& e : elements) Append(std::move(e));
}

void PathGeometry::Append(PathElement e) {
  e.start_s_m = length_m_;
  length_m_ += e.length_m;
  Eigen::Vector3d lo = e.start_m.cwiseMin(e.end_m);
  Eigen::Vector3d hi = e.start_m.cwiseMax(e.end_m);
  if (e.blend) {
    // A blend lies in the triangle of its ends and the corner it rounds.
    const Eigen::Vector3d corner = e.start_m + e.v_dir * (e.start_radius_m * std::tan(0.5 * e.sweep_rad));
    lo = lo.cwiseMin(corner);
    hi = hi.cwiseMax(corner);
  } else if (e.is_arc()) {
    const double r = std::max(e.start_radius_m, e.end_radius_m);
    for (int axis : {e.axis0, e.axis1}) {
      lo(axis) = e.center_m(axis) - r;
      hi(axis) = e.center_m(axis) + r;
    }
  }
  box_min_.push_back(lo);
  box_max_.push_back(hi);
  elements_.push_back(std::move(e));
}

std::size_t PathGeometry::ElementAt(double s_m, std::size_t hint) const {
  if (elements_.empty()) return 0;
  std::size_t i = std::min(hint, elements_.size() - 1);
  while (i > 0 && s_m < elements_[i].start_s_m) --i;
  // Forward past elements that end before s, and past zero-length ones (dwells).
  while (i + 1 < elements_.size() &&
         (s_m > elements_[i].end_s_m() || (elements_[i].length_m == 0.0 && s_m >= elements_[i].start_s_m))) {
    ++i;
  }
  return i;
}

Eigen::Vector3d PathGeometry::PointAt(double s_m, std::size_t* hint) const {
  if (elements_.empty()) return start_m_;
  const std::size_t i = ElementAt(s_m, hint ? *hint : 0);
  if (hint) *hint = i;
  const PathElement& e = elements_[i];
  if (e.length_m == 0.0) return e.end_m;
  return e.PointAtFraction((s_m - e.start_s_m) / e.length_m);
}

Eigen::Vector3d PathGeometry::NearestPoint(const Eigen::Vector3d& p) const {
  if (elements_.empty()) return start_m_;
  return NearestPointIn(p, 0, elements_.size() - 1);
}

Eigen::Vector3d PathGeometry::NearestPointIn(const Eigen::Vector3d& p, std::size_t first, std::size_t last) const {
  if (elements_.empty()) return start_m_;
  last = std::min(last, elements_.size() - 1);
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d nearest = start_m_;
  for (std::size_t i = first; i <= last; ++i) {
    const Eigen::Vector3d outside =
        (box_min_[i] - p).cwiseMax(p - box_max_[i]).cwiseMax(Eigen::Vector3d::Zero());
    if (outside.norm() >= best) continue;
    const Eigen::Vector3d candidate = elements_[i].NearestPoint(p);
    const double distance = (p - candidate).norm();
    if (distance < best) {
      best = distance;
      nearest = candidate;
    }
  }
  return nearest;
}

}  // namespace shapebench::controller
