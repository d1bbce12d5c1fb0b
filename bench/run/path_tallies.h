// What the plant samplers measure along the programmed path besides the deflection: the
// contour error (ContourGauge), an arc's mean radius (radial_error_m), a nonlinear plant's
// free response and quadrant glitches.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "common/math_constants.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"
#include "model/drive.h"

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
// The search is a window of blocks around the current one, not the whole path (whose cost
// grew with the program at every sample: a run's cost went with the square of its length).
// The window holds the blocks the interpolator passed from `lag` before the sample's period
// to two periods after it, and two more on each side; `lag` is how long the tool may trail
// the interpolator (ContourLag: the post-interpolation filter's length plus 10 time
// constants of the exponential and of the servo). The window's nearest point is the whole
// path's wherever that lies in the window (PathGeometry::NearestPointIn), and the tool is
// near the path it is cutting; the exception, by design: where another pass of the path
// (an adjacent zig-zag pass, a contour cut again) comes closer to the tool than the pass
// being cut but lies outside the window, the windowed error is measured against the pass
// being cut, the larger (docs/metrics.md). Cost per sample: the blocks in the window, which
// the lag bounds, whatever the program's length.
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
  // `path_position_m`: the interpolator's path position per tick (MultiAxisCommand); it
  // must outlive the gauge.
  ContourGauge(const controller::PathGeometry& path, const std::vector<double>& path_position_m, double period_s,
               double lag_s);
  // Moves the window to period k (the samples between ticks k - 1 and k); k never decreases.
  void MoveTo(std::size_t k);
  // The sample's squared contour error, or 0 when it is provably below `largest_sq`.
  double SquaredDistanceTo(const Eigen::Vector3d& p, double largest_sq) const {
    if (exact_ && has_last_ && largest_sq > 0.0) {
      const double margin = 1e-12 + 1e-13 * p.cwiseAbs().maxCoeff();
      const double bound = (p - last_).norm() + margin;
      if (bound * bound < largest_sq) return 0.0;
    }
    last_ = NearestPoint(p);
    has_last_ = true;
    return (p - last_).squaredNorm();
  }
  // The nearest point of `p` in the current window (plots), and its distance in period
  // k's window (tests).
  Eigen::Vector3d NearestPoint(const Eigen::Vector3d& p) const {
    return single_ != nullptr ? single_->NearestPoint(p) : path_.NearestPointIn(p, first_, last_element_);
  }
  double WindowedDistance(const Eigen::Vector3d& p, std::size_t k) {
    MoveTo(k);
    return (p - NearestPoint(p)).norm();
  }
  const controller::PathElement* single() const { return single_; }
  std::size_t lag_ticks() const { return lag_ticks_; }
  std::size_t first() const { return first_; }  // the window's elements, inclusive
  std::size_t last() const { return last_element_; }

 private:
  const controller::PathGeometry& path_;
  const std::vector<double>& positions_;
  const controller::PathElement* single_ = nullptr;
  bool exact_ = false;  // the search is exact on every element (no helix, no spiral)
  std::size_t lag_ticks_ = 0;
  std::size_t lo_hint_ = 0, hi_hint_ = 0;     // ElementAt's hints (monotone walks)
  std::size_t first_ = 0, last_element_ = 0;  // the window, inclusive
  mutable Eigen::Vector3d last_;  // the last nearest point found
  mutable bool has_last_ = false;
};

// How long the tool may trail the interpolator (ContourGauge's window): the command's
// post-interpolation filter lag plus, for a servo drive, 10 time constants of its position
// loop (1 / Kp) and of its velocity loop.
double ContourLag(const controller::MultiAxisCommand& command, const model::DriveConfig& drive);

}  // namespace shapebench::bench
