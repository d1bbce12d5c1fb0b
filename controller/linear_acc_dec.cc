// Pre-interpolation linear acc/dec with the vibration-suppressing steps (seed 004
// paras. 21-22, 49-50, 52); see the header.
#include "controller/linear_acc_dec.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "controller/grid_realization.h"

namespace shapebench::controller {
namespace {

void Append(IdealProfile& profile, double duration_s, double accel_m_s2) {
  if (duration_s > 0.0) profile.segments.push_back({duration_s, accel_m_s2});
}

double PhaseDuration(double speed_m_s, double accel_m_s2, const StepPattern& pattern) {
  return AccelPhase(speed_m_s, accel_m_s2, pattern).Duration();
}

// The mean time sum A_j t_j of a shaper (amplitudes summing to 1).
double MeanTime(const std::vector<Impulse>& shaper) {
  double mean = 0.0;
  for (const Impulse& i : shaper) mean += i.amplitude * i.time_s;
  return mean;
}

// The steady acceleration convolved with the shaper (the header's general pattern).
IdealProfile ConvolvedPhase(double speed_m_s, double accel_m_s2, const StepPattern& pattern) {
  const std::vector<Impulse>& shaper = pattern.impulses;
  const double a = accel_m_s2;
  const double steady_s = speed_m_s / a;  // the unshaped phase
  const double mean_s = MeanTime(shaper);
  const double duration_s = shaper.back().time_s;
  bool start = pattern.at_start;
  bool end = pattern.at_end;
  // One end unshaped: its single step must not fall inside the shaped end's impulses.
  if (start && !end && steady_s < duration_s - mean_s) end = true;
  if (end && !start && steady_s < mean_s) start = true;
  const double end_s = steady_s + (start ? mean_s : 0.0) - (end ? mean_s : 0.0);
  std::vector<Impulse> first;
  std::vector<Impulse> second;
  if (start) {
    for (const Impulse& i : shaper) first.push_back({i.time_s, a * i.amplitude});
  } else {
    first.push_back({0.0, a});
  }
  if (end) {
    for (const Impulse& i : shaper) second.push_back({end_s + i.time_s, -a * i.amplitude});
  } else {
    second.push_back({end_s, -a});
  }
  IdealProfile phase;
  if (second.front().time_s < first.back().time_s) {
    // A phase shorter than the shaper: the two groups interleave; one group on the grid.
    std::vector<Impulse> merged = first;
    merged.insert(merged.end(), second.begin(), second.end());
    std::stable_sort(merged.begin(), merged.end(),
                     [](const Impulse& x, const Impulse& y) { return x.time_s < y.time_s; });
    std::vector<Impulse> group;
    for (const Impulse& i : merged) {
      if (!group.empty() && group.back().time_s == i.time_s) {
        group.back().amplitude += i.amplitude;
      } else {
        group.push_back(i);
      }
    }
    phase.jerk_groups.push_back(group);
  } else {
    phase.jerk_groups.push_back(first);
    phase.jerk_groups.push_back(second);
  }
  // The piecewise-constant acceleration between the jerk impulses, from t = 0.
  double t = 0.0;
  double accel = 0.0;
  for (const std::vector<Impulse>& group : phase.jerk_groups) {
    for (const Impulse& i : group) {
      Append(phase, i.time_s - t, accel);
      t = std::max(t, i.time_s);
      accel += i.amplitude;
    }
  }
  return phase;
}

}  // namespace

void IdealProfile::AppendPhase(const IdealProfile& phase, double sign) {
  const double start_s = Duration();
  for (const AccelSegment& s : phase.segments) segments.push_back({s.duration_s, sign * s.accel_m_s2});
  for (const std::vector<Impulse>& group : phase.jerk_groups) {
    std::vector<Impulse> shifted;
    for (const Impulse& i : group) shifted.push_back({start_s + i.time_s, sign * i.amplitude});
    jerk_groups.push_back(shifted);
  }
}

void IdealProfile::AppendCruise(double duration_s) { Append(*this, duration_s, 0.0); }

double IdealProfile::Duration() const {
  double total = 0.0;
  for (const AccelSegment& s : segments) total += s.duration_s;
  return total;
}

double IdealProfile::VelocityAt(double t_s) const {
  double t0 = 0.0;
  double v0 = 0.0;
  for (const AccelSegment& s : segments) {
    if (t_s < t0 + s.duration_s) return v0 + s.accel_m_s2 * std::max(0.0, t_s - t0);
    t0 += s.duration_s;
    v0 += s.accel_m_s2 * s.duration_s;
  }
  return 0.0;  // at rest after the move (exactly, whatever the rounding of the sums)
}

double IdealProfile::DistanceAt(double t_s) const {
  double t0 = 0.0;
  double v0 = 0.0;
  double x0 = 0.0;
  for (const AccelSegment& s : segments) {
    const double dt = std::min(std::max(0.0, t_s - t0), s.duration_s);
    if (t_s < t0 + s.duration_s) return x0 + v0 * dt + 0.5 * s.accel_m_s2 * dt * dt;
    x0 += v0 * s.duration_s + 0.5 * s.accel_m_s2 * s.duration_s * s.duration_s;
    v0 += s.accel_m_s2 * s.duration_s;
    t0 += s.duration_s;
  }
  return x0;
}

double IdealProfile::MaxAbsAccel() const {
  double max_accel = 0.0;
  for (const AccelSegment& s : segments) max_accel = std::max(max_accel, std::abs(s.accel_m_s2));
  return max_accel;
}

IdealProfile AccelPhase(double speed_m_s, double accel_m_s2, const StepPattern& pattern) {
  if (pattern.general() && pattern.shapes()) return ConvolvedPhase(speed_m_s, accel_m_s2, pattern);
  const int shaped_ends = (pattern.at_start ? 1 : 0) + (pattern.at_end ? 1 : 0);
  AccelStep step1 = pattern.step1;
  AccelStep step2 = pattern.step2;
  // Para. 50: when the steps alone would overshoot the speed, shorten the steady
  // acceleration first (to zero), then step 2, then step 1.
  double steady_s = speed_m_s / accel_m_s2 - shaped_ends * pattern.velocity_per_accel_s();
  if (steady_s < 0.0) {
    steady_s = 0.0;
    const double per_end = speed_m_s / accel_m_s2 / shaped_ends;  // velocity / a per end
    const double after_step1 = per_end - step1.ratio * step1.duration_s;
    if (after_step1 >= 0.0 && step2.ratio > 0.0) {
      step2.duration_s = std::min(step2.duration_s, after_step1 / step2.ratio);
    } else {
      step2.duration_s = 0.0;  // a zero-acceleration step gains nothing: omitted
      step1.duration_s = std::min(step1.duration_s, per_end / step1.ratio);
    }
  }
  const double a = accel_m_s2;
  IdealProfile phase;
  double t = 0.0;
  if (pattern.at_start) {
    Append(phase, step1.duration_s, step1.ratio * a);
    Append(phase, step2.duration_s, step2.ratio * a);
    phase.jerk_groups.push_back({{0.0, step1.ratio * a},
                                 {step1.duration_s, (step2.ratio - step1.ratio) * a},
                                 {step1.duration_s + step2.duration_s, (1.0 - step2.ratio) * a}});
    t = step1.duration_s + step2.duration_s;
  } else {
    phase.jerk_groups.push_back({{0.0, a}});
  }
  Append(phase, steady_s, a);
  t += steady_s;
  if (pattern.at_end) {  // para. 49: the end of a phase runs the steps in reverse order
    Append(phase, step2.duration_s, step2.ratio * a);
    Append(phase, step1.duration_s, step1.ratio * a);
    phase.jerk_groups.push_back({{t, (step2.ratio - 1.0) * a},
                                 {t + step2.duration_s, (step1.ratio - step2.ratio) * a},
                                 {t + step2.duration_s + step1.duration_s, -step1.ratio * a}});
  } else {
    phase.jerk_groups.push_back({{t, -a}});
  }
  return phase;
}

double LowestShapedSpeed(double accel_m_s2, const StepPattern& pattern) {
  if (pattern.general()) {
    if (pattern.at_start == pattern.at_end) return 0.0;  // both ends (or none): no limit
    const double mean_s = MeanTime(pattern.impulses);
    return accel_m_s2 * (pattern.at_start ? pattern.impulses.back().time_s - mean_s : mean_s);
  }
  const int shaped_ends = (pattern.at_start ? 1 : 0) + (pattern.at_end ? 1 : 0);
  return shaped_ends * accel_m_s2 * pattern.step1.ratio * pattern.step1.duration_s;
}

double ShortestShapedMove(double accel_m_s2, const StepPattern& pattern) {
  const double speed = LowestShapedSpeed(accel_m_s2, pattern);
  return speed * PhaseDuration(speed, accel_m_s2, pattern);
}

IdealProfile PlanRestToRest(double distance_m, double feed_m_s, double accel_m_s2,
                            const StepPattern& pattern) {
  // Whatever the pattern, the dec phase mirrors the acc phase, so a move covers
  // peak speed x (phase duration + cruise duration).
  double speed = feed_m_s;
  double cruise_s = distance_m / feed_m_s - PhaseDuration(feed_m_s, accel_m_s2, pattern);
  if (cruise_s < 0.0) {
    // Short move: the peak speed v solves v * phase_duration(v) = distance (increasing).
    double lo = 0.0;
    double hi = feed_m_s;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * feed_m_s; ++i) {
      const double mid = 0.5 * (lo + hi);
      (mid * PhaseDuration(mid, accel_m_s2, pattern) < distance_m ? lo : hi) = mid;
    }
    speed = 0.5 * (lo + hi);
    cruise_s = 0.0;
  }
  const IdealProfile phase = AccelPhase(speed, accel_m_s2, pattern);
  IdealProfile profile;
  profile.AppendPhase(phase, 1.0);
  profile.AppendCruise(cruise_s);
  profile.AppendPhase(phase, -1.0);
  return profile;
}

namespace {

// RealizeOnGrid's results for the groups seen so far in one exact-distance search: the
// search changes the nominal distance, which moves the groups after the cruise; the
// groups before it are the same every time, and their (deterministic) realization is
// looked up instead of computed again.
class GridCache {
 public:
  const std::vector<GridImpulse>& Realize(const std::vector<Impulse>& group, double period_s,
                                          const GridDesign& design, double accel_before,
                                          double accel_limit) {
    for (const Entry& e : entries_) {
      if (e.accel_before == accel_before && e.accel_limit == accel_limit && Same(e.group, group)) {
        return e.result;
      }
    }
    entries_.push_back(
        {group, accel_before, accel_limit,
         RealizeOnGrid(group, period_s, design, accel_before, accel_limit)});
    return entries_.back().result;
  }

 private:
  struct Entry {
    std::vector<Impulse> group;
    double accel_before;
    double accel_limit;
    std::vector<GridImpulse> result;
  };
  static bool Same(const std::vector<Impulse>& a, const std::vector<Impulse>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].time_s != b[i].time_s || a[i].amplitude != b[i].amplitude) return false;
    }
    return true;
  }
  std::deque<Entry> entries_;  // stable references
};

CommandTrajectory RealizeOnTicksWith(const IdealProfile& profile, double period_s,
                                     const GridDesign& design, GridCache* cache) {
  std::vector<double> jumps;  // acceleration change at each tick
  const double accel_limit = profile.MaxAbsAccel();
  double accel_before = 0.0;  // groups are in time order; each adds its net change
  for (const std::vector<Impulse>& group : profile.jerk_groups) {
    std::vector<GridImpulse> own;
    const std::vector<GridImpulse>& realized =
        cache != nullptr ? cache->Realize(group, period_s, design, accel_before, accel_limit)
                         : (own = RealizeOnGrid(group, period_s, design, accel_before, accel_limit));
    for (const GridImpulse& g : realized) {
      const auto tick = static_cast<std::size_t>(std::max(0L, g.tick));
      if (jumps.size() <= tick) jumps.resize(tick + 1, 0.0);
      jumps[tick] += g.amplitude;
    }
    for (const Impulse& i : group) accel_before += i.amplitude;
  }
  CommandTrajectory trajectory;
  trajectory.period_s = period_s;
  trajectory.velocity_m_s.assign(std::max<std::size_t>(jumps.size(), 2), 0.0);
  double accel = 0.0;
  for (std::size_t k = 1; k < trajectory.velocity_m_s.size(); ++k) {
    accel += jumps[k - 1];
    trajectory.velocity_m_s[k] = trajectory.velocity_m_s[k - 1] + accel * period_s;
  }
  // The last jump brings the acceleration back to zero at rest; rounding of the sums
  // would leave ~1e-17 m/s there.
  trajectory.velocity_m_s.back() = 0.0;
  return trajectory;
}

}  // namespace

CommandTrajectory RealizeOnTicks(const IdealProfile& profile, double period_s,
                                 const GridDesign& design) {
  return RealizeOnTicksWith(profile, period_s, design, nullptr);
}

namespace {

double RealizedDistance(const CommandTrajectory& trajectory) {
  double sum = 0.0;
  for (std::size_t k = 1; k <= trajectory.num_ticks(); ++k) sum += trajectory.increment_m(k);
  return sum;
}

}  // namespace

CommandTrajectory SampleOnTicks(double distance_m, double feed_m_s, double accel_m_s2,
                                const StepPattern& pattern, double period_s,
                                const GridDesign& design) {
  return RealizeExactDistance(
      [&](double nominal_m) { return PlanRestToRest(nominal_m, feed_m_s, accel_m_s2, pattern); },
      distance_m, period_s, design);
}

CommandTrajectory RealizeExactDistance(const std::function<IdealProfile(double)>& plan,
                                       double distance_m, double period_s,
                                       const GridDesign& design) {
  // The grid trajectory covers slightly more or less than the ideal one when steps fall
  // between ticks. Plan for a nominal distance X whose realised distance S(X) is the
  // requested one: S is continuous and increasing with S(X) ~ X, so regula falsi with a
  // bisection fallback converges in a few evaluations. Below that S is a staircase of
  // rounding (and of RealizeOnGrid's snapping of near-grid steps): the search stops once
  // two evaluations in a row bring no closer, or the bracket holds no double between its
  // ends, and returns the closest trajectory found (kept, not realised again).
  GridCache cache;
  CommandTrajectory best_trajectory;
  double best = 0.0;
  double best_f = std::numeric_limits<double>::infinity();
  constexpr int kMaxStalled = 2;
  int stalled = 0;  // evaluations in a row that did not improve on best_f
  auto error = [&](double nominal_m) {
    CommandTrajectory trajectory = RealizeOnTicksWith(plan(nominal_m), period_s, design, &cache);
    const double f = RealizedDistance(trajectory) - distance_m;
    if (std::abs(f) < best_f) {
      best = nominal_m;
      best_f = std::abs(f);
      best_trajectory = std::move(trajectory);
      stalled = 0;
    } else if (std::abs(f) == best_f && trajectory.velocity_m_s == best_trajectory.velocity_m_s) {
      stalled = kMaxStalled;  // another nominal distance, the same ticks: a plateau
    } else {
      ++stalled;
    }
    return f;
  };
  const double x0 = distance_m;
  const double f0 = error(x0);
  if (f0 == 0.0) return best_trajectory;
  double step = std::abs(f0) * 2.0 + 1e-15 * distance_m;
  double x1 = x0 - (f0 > 0 ? step : -step);
  double f1 = error(x1);
  for (int i = 0; i < 60 && (f0 > 0) == (f1 > 0) && stalled < kMaxStalled; ++i) {
    step *= 2.0;
    x1 = std::max(0.5 * x0 * 1e-3, x0 - (f0 > 0 ? step : -step));
    f1 = error(x1);
  }
  if ((f0 > 0) == (f1 > 0)) return best_trajectory;  // no bracket: the closest found
  double lo = f0 < 0 ? x0 : x1;
  double hi = f0 < 0 ? x1 : x0;
  double f_lo = f0 < 0 ? f0 : f1;
  double f_hi = f0 < 0 ? f1 : f0;
  for (int i = 0; i < 100 && best_f > 1e-15 * distance_m && stalled < kMaxStalled; ++i) {
    if (std::nextafter(lo, hi) >= hi) break;  // no double strictly between: nothing new
    double x = lo - f_lo * (hi - lo) / (f_hi - f_lo);
    if (!(x > lo && x < hi) || i % 3 == 2) x = 0.5 * (lo + hi);
    const double f = error(x);
    if (f == 0.0) break;
    (f < 0 ? lo : hi) = x;
    (f < 0 ? f_lo : f_hi) = f;
    if (hi - lo <= 1e-16 * distance_m) break;
  }
  (void)best;
  return best_trajectory;
}

}  // namespace shapebench::controller
