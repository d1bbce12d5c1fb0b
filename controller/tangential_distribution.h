// Seed 000 (EP0089156-type acc/dec device): post-interpolation acc/dec on the tangential
// minute displacement. The interpolator's per-axis minute displacements are queued with
// their tangential length dS; acc/dec filters dS alone into the output SO; each period SO
// releases queued segments in order, a segment longer than what is left of SO split in
// proportion (claim 2: "first output means" when the segment for output is not longer
// than SO, "second output means" otherwise, with the proportional constants KX/KS of the
// segment as first stored). The output stays on the interpolated path, so acc/dec after
// interpolation no longer pulls arcs inward (per-axis filtering does: Fig. 2).
#pragma once

#include <cstddef>
#include <deque>
#include <vector>

#include <Eigen/Dense>

#include "controller/pulse_filter.h"

namespace shapebench::controller {

// One period's output of the interpolating means: per-axis and tangential displacement.
struct MinuteDisplacement {
  Eigen::Vector3d axes_m = Eigen::Vector3d::Zero();
  double tangential_m = 0.0;
};

class TangentialQueue {
 public:
  // Stores the interpolator's minute displacements of one period (minute displacement
  // storage means 3).
  void Push(const MinuteDisplacement& input);
  // Distributes the tangential output SO of one period over the queued segments, in
  // order; returns the per-axis output of the period. Releasing more than is queued
  // releases what there is.
  Eigen::Vector3d Release(double so_m);
  // Everything still queued (at the end of a program, what rounding of SO left behind).
  Eigen::Vector3d Flush();

  std::size_t size() const { return queue_.size(); }
  double queued_tangential_m() const;

 private:
  struct Entry {
    MinuteDisplacement remaining;  // what is left for output
    MinuteDisplacement constants;  // KX, KY, KZ, KS: the segment as first stored
  };
  std::deque<Entry> queue_;
};

// The whole of seed 000's device: `axis_pulses[k]` and `tangential_pulses[k]` are the
// interpolator's output of period k + 1; `filter` is the acc/dec algorithm applied to the
// tangential displacement. Returns the per-axis output pulses (longer by the filter's
// tail); they add up to the input exactly (the last period flushes the queue).
std::vector<Eigen::Vector3d> DistributeTangentially(
    const std::vector<Eigen::Vector3d>& axis_pulses, const std::vector<double>& tangential_pulses,
    const PulseFilter& filter, double period_s);

}  // namespace shapebench::controller
