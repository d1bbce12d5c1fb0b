// Interpolation every period (seed 004 para. 52, seed 000 Fig. 1 "interpolating means"):
// the pre-interpolation acc/dec gives the path speed at each tick; the tangential minute
// displacement of period k is dS_k = v_k * period (the speed the acc/dec reached at the
// end of the period: with the pulse rate as the drive's velocity sample, the drive then
// sees exactly the acceleration the acc/dec planned), and the per-axis minute
// displacements dX, dY, dZ are the chords between consecutive points of the path.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "controller/block_planner.h"
#include "controller/path_geometry.h"

namespace shapebench::controller {

struct InterpolatedPulses {
  // Index k - 1 holds period k (k = 1..N).
  std::vector<Eigen::Vector3d> axis_pulses_m;
  std::vector<double> tangential_pulses_m;
  // Per tick k = 0..N: the path position S_k and the block it lies in.
  std::vector<double> path_position_m;
  std::vector<int> block;
};

InterpolatedPulses Interpolate(const PathGeometry& path, const SpeedPlan& plan, double period_s);

}  // namespace shapebench::controller
