// Block planning with look-ahead (seed 004 paras. 21-22: feed-rate control, then
// pre-interpolation linear acc/dec of the path speed). The pre-read blocks are grouped
// into motions between stops (program start and end, dwells, corners that need a stop);
// within a motion, the path speed may stay up across block boundaries: collinear blocks
// join without a stop, and where the direction changes the junction speed is limited so
// that no axis changes velocity by more than the corner allowance in one period (the
// corner rule). Backward and forward passes make every speed change fit its block; each
// change is one acc/dec phase shaped by the vibration-suppressing pattern (seed 004), so
// the shaping holds across blocks as it does for a single move. On arcs the feed is
// clamped so that the centripetal acceleration v^2 / r stays within the acc/dec's.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "controller/grid_realization.h"
#include "controller/path_geometry.h"
#include "controller/program.h"
#include "controller/short_block_clamp.h"
#include "controller/stroke_end.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

struct PlannerSettings {
  double period_s = 0.001;
  double accel_m_s2 = 1.0;          // steady acceleration of linear acc/dec
  StepPattern pattern;              // the stepped realization (none: plain linear acc/dec)
  GridDesign grid_design{25.0};     // the design point(s) the grid realization keeps
  double default_feed_m_s = 0.1;    // blocks before the first F word
  double rapid_feed_m_s = 0.5;      // G0
  double corner_velocity_change_m_s = 0.0;  // per axis, per junction; 0: stop at corners
  // >= 0: grbl's junction rule with this junction deviation (m) instead of the corner rule.
  double junction_deviation_m = -1.0;
  ShortBlockConfig short_block;
  StrokeEndConfig stroke_end;
  StrokeLimits stroke_limits;
};

struct SpeedPlan {
  // Path speed samples at the ticks t_k = k * period (k = 0..N), the pre-interpolation
  // acc/dec output: the speed is linear between ticks, v_0 = v_N = 0.
  std::vector<double> speed_m_s;
  // Where each motion ends: the tick and the exact arc length there (the interpolator
  // lands on it so rounding never accumulates across motions).
  std::vector<std::pair<std::size_t, double>> stops;
  // The feed each block runs at (m/s), for traces, and whether the short-block clamp
  // lowered it.
  std::vector<double> block_feed_m_s;
  std::vector<bool> block_clamped;
  int short_block_clamps = 0;
  // The stroke check: where the path first leaves the stroke, and whether (and at which
  // tick) the interpolated position reached it, raising the alarm that stopped the tool.
  std::optional<double> stroke_crossing_s_m;
  bool stroke_alarm = false;
  std::size_t alarm_tick = 0;
};

SpeedPlan PlanPathSpeed(const Program& program, const PathGeometry& path,
                        const PlannerSettings& settings);
// The same on `path`, a blended path (controller/corner_blend.h): the blocks' feeds from
// `programmed`, the speeds along `path`; a blend runs at one speed, the lower feed of its
// two blocks and sqrt(a r) at most, its entry and exit junctions equal.
SpeedPlan PlanPathSpeed(const Program& program, const PathGeometry& programmed, const PathGeometry& path,
                        const PlannerSettings& settings);

// The junction speed limit between two directions (unit tangents) under the corner rule:
// infinite when they agree (within 1e-9), else allowance / max_axis |t2 - t1|.
double CornerSpeedLimit(const Eigen::Vector3d& before, const Eigen::Vector3d& after,
                        double corner_velocity_change_m_s);

// grbl's junction rule (planner.c): the speed at which a circle tangent to both directions
// whose closest point lies `deviation_m` from the junction is run with the centripetal
// acceleration a_j: v^2 = a_j delta sin(phi/2) / (1 - sin(phi/2)), phi the junction's
// interior angle (180 deg for a straight continuation: infinite; 0 for a reversal: 0, a
// stop). a_j is the largest acceleration along the junction vector t2 - t1 that keeps every
// axis within `accel_m_s2` (a / max_axis |j|, j its unit vector), as grbl limits each axis
// to its own maximum. Straight and reversal within grbl's 1e-6 of cos(phi).
double JunctionDeviationLimit(const Eigen::Vector3d& before, const Eigen::Vector3d& after, double accel_m_s2,
                              double deviation_m);

}  // namespace shapebench::controller
