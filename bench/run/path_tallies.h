// What the plant samplers measure along the programmed path besides the deflection: the
// contour error (ContourGauge), an arc's mean radius (radial_error_m), a nonlinear plant's
// free response and quadrant glitches.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "common/math_constants.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {

// Mean radius over the middle half of one arc (radial_error_m).
struct ArcWindow {
  const controller::PathElement* arc = nullptr;
  double sum_radius_m = 0.0;
  long samples = 0;
};

// The deflection of a nonlinear plant after motion end, in the view: its extremes
// (residual_amplitude_m, half their difference) and its last value (dead_band_m).
struct FreeResponse {
  double min = HUGE_VAL;
  double max = -HUGE_VAL;
  double last = 0.0;
  bool any = false;
  void Add(double d) {
    min = std::min(min, d);
    max = std::max(max, d);
    last = d;
    any = true;
  }
};

// quadrant_glitch_m on one arc: the axis reversals (tangent along an axis) at least 5
// degrees inside the arc, the largest and smallest radial deviation (actual radius less
// programmed) within +-5 degrees of each, and the deviations over the arc's middle half
// (by the command's path position, as radial_error_m), whose median is the baseline: robust
// to the spikes themselves, clear of the arc's start and end.
struct ReversalWindows {
  static constexpr double kHalfWidthRad = 5.0 * kPi / 180.0;
  const controller::PathElement* arc = nullptr;
  std::vector<double> angle_rad;  // the reversals' angles on the arc's turn
  std::vector<double> max_radius_m;
  std::vector<double> min_radius_m;
  std::vector<double> middle_m;  // deviations over the middle half

  explicit ReversalWindows(const controller::PathElement& element);
  void Add(double path_s, const Eigen::Vector3d& actual);
  double Glitch() const;  // NaN without a reversal or a baseline
};

// The contour error of a sample: its distance from the programmed path, squared (the
// largest distance is the square root of the largest square, bit for bit: norm() is the
// square root of squaredNorm(), and the square root is monotone). A single straight
// element (a `move:`, a one-block program) is measured on it directly: the whole path's
// search gives the same point there.
//
// Only the run's largest contour error is kept, so a sample that cannot exceed the largest
// so far need not be searched for: the last nearest point found lies on the path, so the
// distance to it bounds the sample's from above. That bound is exact only where the
// search is (lines and plane circular arcs: controller/path_geometry.cc, a helix's or a
// spiral's nearest point is an estimate), and is applied with a margin far above the
// rounding of the points (1e-12 m plus 1e-13 of the coordinates), so the largest error is
// the same bit for bit.
class ContourGauge {
 public:
  explicit ContourGauge(const controller::PathGeometry& path) : path_(path) {
    const auto& elements = path.elements();
    if (elements.size() == 1 && !elements.front().is_arc()) single_ = &elements.front();
    exact_ = true;
    for (const controller::PathElement& e : elements) {
      if (e.is_arc() && (e.rise_m != 0.0 || e.start_radius_m != e.end_radius_m)) exact_ = false;
    }
  }
  // The sample's squared contour error, or 0 when it is provably below `largest_sq`.
  double SquaredDistanceTo(const Eigen::Vector3d& p, double largest_sq) const {
    if (exact_ && has_last_ && largest_sq > 0.0) {
      const double margin = 1e-12 + 1e-13 * p.cwiseAbs().maxCoeff();
      const double bound = (p - last_).norm() + margin;
      if (bound * bound < largest_sq) return 0.0;
    }
    last_ = single_ != nullptr ? single_->NearestPoint(p) : path_.NearestPoint(p);
    has_last_ = true;
    return (p - last_).squaredNorm();
  }
  const controller::PathElement* single() const { return single_; }

 private:
  const controller::PathGeometry& path_;
  const controller::PathElement* single_ = nullptr;
  bool exact_ = false;  // the search is exact on every element (no helix, no spiral)
  mutable Eigen::Vector3d last_;  // the last nearest point found
  mutable bool has_last_ = false;
};

}  // namespace shapebench::bench
