// The programmed path as a function of arc length s: lines, arcs and helices joined end
// to end. The interpolator evaluates it every period; the bench measures contour and
// radial errors against it.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "controller/program.h"

namespace shapebench::controller {

struct PathElement {
  MotionKind kind = MotionKind::kLinear;
  int block = 0;            // index in Program::blocks
  double start_s_m = 0.0;   // arc length at the element's start
  double length_m = 0.0;    // 0 for a dwell
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_m = Eigen::Vector3d::Zero();
  // Lines: the unit direction.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  // Arcs: centre, plane axes (first, second, normal), start angle and signed sweep
  // (CCW > 0), start and end radius (they may differ by the builder's tolerance; the
  // radius then varies linearly with the angle, as a control's spiral interpolation does)
  // and the rise along the normal axis (helix).
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  int axis0 = 0, axis1 = 1, normal = 2;
  double start_angle_rad = 0.0;
  double sweep_rad = 0.0;
  double start_radius_m = 0.0;
  double end_radius_m = 0.0;
  double rise_m = 0.0;
  double dwell_s = 0.0;
  // A corner blend (controller/corner_blend.h): a circular arc (kArcCcw, start angle 0,
  // sweep the turn) in the plane of the two lines it joins, whatever their axes: u_dir
  // from the centre to the start, v_dir the start's tangent. The planner runs it at one
  // speed.
  bool blend = false;
  Eigen::Vector3d u_dir = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_dir = Eigen::Vector3d::Zero();
  // Where the element lies on the programmed path (its arc length there): the element
  // itself unless the path was blended (a blend covers the two trimmed line ends).
  double source_start_s_m = 0.0;
  double source_length_m = 0.0;

  bool is_arc() const { return kind == MotionKind::kArcCw || kind == MotionKind::kArcCcw; }
  double end_s_m() const { return start_s_m + length_m; }
  // The point at `u` in [0, 1] of the element (u = 1 gives end_m exactly).
  Eigen::Vector3d PointAtFraction(double u) const;
  // The unit tangent at `u` in [0, 1] (zero for a dwell).
  Eigen::Vector3d TangentAtFraction(double u) const;
  // The point of the element nearest to `p` (for a helix, the close estimate at p's
  // angle), and the distance to it.
  Eigen::Vector3d NearestPoint(const Eigen::Vector3d& p) const;
  double DistanceTo(const Eigen::Vector3d& p) const { return (p - NearestPoint(p)).norm(); }
};

class PathGeometry {
 public:
  explicit PathGeometry(const Program& program);
  // A path of given elements (a blended one): their start_s_m are set here, in order.
  PathGeometry(const Eigen::Vector3d& start_m, std::vector<PathElement> elements);

  const std::vector<PathElement>& elements() const { return elements_; }
  double length_m() const { return length_m_; }
  const Eigen::Vector3d& start_m() const { return start_m_; }

  // The element containing arc length s (the first of equal ones at a boundary is the
  // one ending there, except at s = 0). `hint`: an index to start the search from
  // (monotone walks are O(1)).
  std::size_t ElementAt(double s_m, std::size_t hint = 0) const;
  Eigen::Vector3d PointAt(double s_m, std::size_t* hint = nullptr) const;

  // The nearest point of the whole path to `p`, and the distance (contour error).
  Eigen::Vector3d NearestPoint(const Eigen::Vector3d& p) const;
  // The nearest point among elements first..last (inclusive; clamped to the path): the
  // same candidates and comparisons as NearestPoint, so the same distance wherever the
  // whole path's nearest point lies on one of them (the bench's windowed contour error).
  Eigen::Vector3d NearestPointIn(const Eigen::Vector3d& p, std::size_t first, std::size_t last) const;
  double DistanceTo(const Eigen::Vector3d& p) const { return (p - NearestPoint(p)).norm(); }

 private:
  Eigen::Vector3d start_m_;
  std::vector<PathElement> elements_;
  double length_m_ = 0.0;
  void Append(PathElement e);
  // Axis-aligned bounds of each element, to skip far ones in DistanceTo.
  std::vector<Eigen::Vector3d> box_min_, box_max_;
};

}  // namespace shapebench::controller
