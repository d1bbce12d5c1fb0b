// Pre-interpolation linear acc/dec (seed 004 paras. 21-22, 52): the path speed ramps to
// the feed with the steady acceleration feed / accel_time, shaped at the start and/or end
// of each phase by a StepPattern; para. 50's shortening when the feed is low or the move
// short. The ideal profile is continuous-time; it is then sampled on the tick grid.
#pragma once

#include <vector>

#include "controller/command_trajectory.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

// Piecewise-constant acceleration, continuous velocity, starting at rest at t = 0.
struct AccelSegment {
  double duration_s = 0.0;
  double accel_m_s2 = 0.0;
};

struct IdealProfile {
  std::vector<AccelSegment> segments;
  double Duration() const;
  double VelocityAt(double t_s) const;
  double DistanceAt(double t_s) const;
  double Distance() const { return DistanceAt(Duration()); }
  double MaxAbsAccel() const;
};

// One acc (or dec) phase from 0 to `speed_m_s`, shaped by `pattern`, with para. 50's
// order of shortening: the steady acceleration first, then step 2, then step 1.
// Accelerations are positive; a deceleration phase is the same with the sign flipped.
std::vector<AccelSegment> AccelPhase(double speed_m_s, double accel_m_s2,
                                     const StepPattern& pattern);

// Rest-to-rest move of `distance_m` (> 0) at up to `feed_m_s`: acc phase, cruise, dec
// phase (the mirror of the acc phase). A move too short for the feed lowers the peak
// speed (para. 50: "the same concept applies when the travel distance is short").
IdealProfile PlanRestToRest(double distance_m, double feed_m_s, double accel_m_s2,
                            const StepPattern& pattern);

// Samples the profile's velocity at the ticks, with the cruise (or the peak speed)
// adjusted so that the sampled trajectory covers exactly `distance_m`. Steps that fall
// between ticks are realised as the period's mean acceleration (velocity exact at ticks).
CommandTrajectory SampleOnTicks(double distance_m, double feed_m_s, double accel_m_s2,
                                const StepPattern& pattern, double period_s);

}  // namespace shapebench::controller
