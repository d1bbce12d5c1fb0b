// Pre-interpolation linear acc/dec (seed 004 paras. 21-22, 52): the path speed ramps to
// the feed with the steady acceleration feed / accel_time, shaped at the start and/or end
// of each phase by a StepPattern; para. 50's shortening when the feed is low or the move
// short. The ideal profile is continuous-time; it is then realised on the tick grid.
//
// Library shapers (shaper_registry.h) in the stepped realization. A StepPattern with a
// general impulse list (StepPattern::impulses) shapes a phase by convolution: the
// unshaped phase (the steady acceleration a for v / a) convolved with the shaper, i.e.
// the jerk groups {a A_j at t_j} at the phase start and {-a A_j at t_e + t_j} at its end,
// each of which leaves no vibration at the design point on its own. This is what the
// patent's two-step patterns are too (AccelPhase builds those from step1/step2 and keeps
// para. 50's shortening, which is theirs alone). The convolution needs no shortening:
// a phase shorter than the shaper overlaps its two groups (merged into one group for the
// grid) and still cancels. With mode start (end) only, the unshaped end (start) is a
// single step; the phase then needs v >= a (D - mu) (v >= a mu), D the shaper's duration
// and mu = sum A_j t_j its mean time, or the speed would overshoot; below that (a short
// speed change in a program) the phase is shaped at both ends. The planner (PhaseDistance)
// uses AccelPhase, so planning is the same for every shaper.
#pragma once

#include <functional>
#include <vector>

#include "controller/command_trajectory.h"
#include "controller/grid_realization.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

// Piecewise-constant acceleration, continuous velocity, starting at rest at t = 0.
struct AccelSegment {
  double duration_s = 0.0;
  double accel_m_s2 = 0.0;
};

struct IdealProfile {
  std::vector<AccelSegment> segments;
  // The same profile as acceleration steps (jerk impulses, m/s^2 each), grouped: one
  // group per shaped start or end of a phase, one per unshaped corner.
  std::vector<std::vector<Impulse>> jerk_groups;

  double Duration() const;
  double VelocityAt(double t_s) const;
  double DistanceAt(double t_s) const;
  double Distance() const { return DistanceAt(Duration()); }
  double MaxAbsAccel() const;

  // Appends `phase` (a profile from rest, e.g. AccelPhase) at the end, its accelerations
  // and jerks scaled by `sign` (-1: the mirrored dec phase).
  void AppendPhase(const IdealProfile& phase, double sign);
  void AppendCruise(double duration_s);
};

// One acc phase from rest to `speed_m_s` starting at t = 0, shaped by `pattern`, with
// para. 50's order of shortening: the steady acceleration first, then step 2, then
// step 1. A dec phase is the same with the signs flipped (the patent: "deceleration is
// performed in the same pattern"). A general pattern (library shaper): the convolution
// described above.
IdealProfile AccelPhase(double speed_m_s, double accel_m_s2, const StepPattern& pattern);

// Para. 50 shortens the steady acceleration, then step 2, then step 1. Cutting into
// step 1 leaves nothing of the pattern's cancellation, so the bench refuses it: these are
// the lowest peak speed, and the shortest rest-to-rest move, that keep step 1 whole.
// A general pattern: 0 at both ends; a (D - mu) (start only) or a mu (end only).
double LowestShapedSpeed(double accel_m_s2, const StepPattern& pattern);
double ShortestShapedMove(double accel_m_s2, const StepPattern& pattern);

// Rest-to-rest move of `distance_m` (> 0) at up to `feed_m_s`: acc phase, cruise, dec
// phase. A move too short for the feed lowers the peak speed (para. 50: "the same
// concept applies when the travel distance is short").
IdealProfile PlanRestToRest(double distance_m, double feed_m_s, double accel_m_s2,
                            const StepPattern& pattern);

// The profile on the tick grid (grid_realization.h, keeping the vibration at `design`),
// with the cruise (or the peak speed) adjusted so that the ticks cover exactly
// `distance_m`.
CommandTrajectory SampleOnTicks(double distance_m, double feed_m_s, double accel_m_s2,
                                const StepPattern& pattern, double period_s,
                                const GridDesign& design);

// The general form: `plan(nominal_m)` gives a rest-to-rest profile planned for a nominal
// distance (continuous and increasing in it); the result is the grid realization whose
// ticks cover exactly `distance_m` (regula falsi on the nominal distance).
CommandTrajectory RealizeExactDistance(const std::function<IdealProfile(double)>& plan,
                                       double distance_m, double period_s,
                                       const GridDesign& design);

// The profile on the tick grid: the jerk groups realised by RealizeOnGrid, integrated.
CommandTrajectory RealizeOnTicks(const IdealProfile& profile, double period_s,
                                 const GridDesign& design);

}  // namespace shapebench::controller
