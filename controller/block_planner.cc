#include "controller/block_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "controller/linear_acc_dec.h"

namespace shapebench::controller {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A stretch of path run at one feed: merged blocks with no speed limit between them.
struct Segment {
  double length_m = 0.0;
  double feed_m_s = 0.0;
  bool hold = false;  // a corner blend: run at one speed, entry = exit
};

// Distance covered by one acc/dec phase from speed u to speed w (shaped as AccelPhase):
// a dec phase mirrors the acc phase, so it covers u * T - (distance of the phase from rest).
double PhaseDistance(double u, double w, const PlannerSettings& s) {
  if (u == w) return 0.0;
  const IdealProfile phase = AccelPhase(std::abs(w - u), s.accel_m_s2, s.pattern);
  const double duration = phase.Duration();
  return w > u ? u * duration + phase.Distance() : u * duration - phase.Distance();
}

// The largest x in [lo, hi] with f(x) <= target, f increasing; lo must satisfy it.
template <typename F>
double LargestWithin(double lo, double hi, double target, F f) {
  if (f(hi) <= target) return hi;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) <= target ? lo : hi) = mid;
  }
  return lo;
}

// Junction speeds (limits in, feasible speeds out; junction[0] = junction[n] = 0), then
// one profile: per segment an acc phase to its peak, a cruise, a dec phase to its exit.
IdealProfile PlanMotion(const std::vector<Segment>& segments, std::vector<double> junction,
                        const PlannerSettings& s) {
  const std::size_t n = segments.size();
  // Backward: each entry speed must allow slowing to the exit within the segment (a
  // blend: equal the exit, the look-ahead that slows the blends ahead of later corners).
  for (std::size_t i = n; i-- > 0;) {
    const double w = junction[i + 1];
    const double cap = junction[i];
    if (segments[i].hold) {
      junction[i] = std::min(cap, w);
    } else if (cap > w && PhaseDistance(cap, w, s) > segments[i].length_m) {
      junction[i] = LargestWithin(w, cap, segments[i].length_m,
                                  [&](double u) { return PhaseDistance(u, w, s); });
    }
  }
  // Forward: each exit speed must be reachable from the entry within the segment.
  for (std::size_t i = 0; i < n; ++i) {
    const double u = junction[i];
    const double cap = junction[i + 1];
    if (segments[i].hold) {
      junction[i + 1] = std::min(cap, u);
    } else if (cap > u && PhaseDistance(u, cap, s) > segments[i].length_m) {
      junction[i + 1] = LargestWithin(u, cap, segments[i].length_m,
                                      [&](double w) { return PhaseDistance(u, w, s); });
    }
  }
  IdealProfile profile;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = junction[i];
    const double w = junction[i + 1];
    const double length = segments[i].length_m;
    if (segments[i].hold && u > 0.0) {
      profile.AppendCruise(length / u);  // u = w: the passes made them equal
      continue;
    }
    auto covered = [&](double peak) { return PhaseDistance(u, peak, s) + PhaseDistance(peak, w, s); };
    const double peak = LargestWithin(std::max(u, w), segments[i].feed_m_s, length, covered);
    const double cruise_s = peak > 0.0 ? std::max(0.0, (length - covered(peak)) / peak) : 0.0;
    if (peak > u) profile.AppendPhase(AccelPhase(peak - u, s.accel_m_s2, s.pattern), 1.0);
    profile.AppendCruise(cruise_s);
    if (peak > w) profile.AppendPhase(AccelPhase(peak - w, s.accel_m_s2, s.pattern), -1.0);
  }
  return profile;
}

// One motion (rest to rest) on the tick grid, covering exactly its length.
CommandTrajectory RealizeMotion(const std::vector<Segment>& segments,
                                const std::vector<double>& junction, const PlannerSettings& s) {
  double total = 0.0;
  std::size_t longest = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    total += segments[i].length_m;
    if (segments[i].length_m > segments[longest].length_m) longest = i;
  }
  if (segments.size() == 1) {
    // The single move of the foundation: the same computation, bit for bit.
    return SampleOnTicks(total, segments[0].feed_m_s, s.accel_m_s2, s.pattern, s.period_s,
                         s.grid_design);
  }
  // The nominal distance goes to the longest segment; the grid's few-ppb excess or
  // shortfall is absorbed there.
  return RealizeExactDistance(
      [&](double nominal_m) {
        std::vector<Segment> adjusted = segments;
        adjusted[longest].length_m = std::max(0.0, adjusted[longest].length_m + nominal_m - total);
        return PlanMotion(adjusted, junction, s);
      },
      total, s.period_s, s.grid_design);
}

}  // namespace

double CornerSpeedLimit(const Eigen::Vector3d& before, const Eigen::Vector3d& after,
                        double corner_velocity_change_m_s) {
  const double change = (after - before).cwiseAbs().maxCoeff();
  if (change <= 1e-9) return kInf;
  return corner_velocity_change_m_s / change;
}

double JunctionDeviationLimit(const Eigen::Vector3d& before, const Eigen::Vector3d& after, double accel_m_s2,
                              double deviation_m) {
  const double cos_interior = -before.dot(after);
  if (cos_interior > 0.999999) return 0.0;   // a reversal: stop
  if (cos_interior < -0.999999) return kInf;  // straight on
  const Eigen::Vector3d junction = (after - before).normalized();
  const double accel = accel_m_s2 / junction.cwiseAbs().maxCoeff();
  const double sin_half = std::sqrt(0.5 * (1.0 - cos_interior));
  return std::sqrt(accel * deviation_m * sin_half / (1.0 - sin_half));
}

namespace {

// The stroke check at run time: at the first tick whose interpolated position has
// reached the stroke end, the alarm stops the tool with the normal (shaped) deceleration
// from the speed it has; the rest of the program is dropped.
void RaiseStrokeAlarm(SpeedPlan& plan, double crossing_s, const PlannerSettings& settings) {
  const double dt = settings.period_s;
  double s = 0.0;
  std::size_t next_stop = 0;
  for (std::size_t k = 1; k < plan.speed_m_s.size(); ++k) {
    s += plan.speed_m_s[k] * dt;
    while (next_stop < plan.stops.size() && plan.stops[next_stop].first < k) ++next_stop;
    if (next_stop < plan.stops.size() && plan.stops[next_stop].first == k) s = plan.stops[next_stop].second;
    if (s < crossing_s) continue;
    plan.stroke_alarm = true;
    plan.alarm_tick = k;
    const double v = plan.speed_m_s[k];
    plan.speed_m_s.resize(k + 1);
    while (!plan.stops.empty() && plan.stops.back().first >= k) plan.stops.pop_back();
    if (v > 0.0) {
      const IdealProfile phase = AccelPhase(v, settings.accel_m_s2, settings.pattern);
      const auto ticks = static_cast<std::size_t>(std::ceil(phase.Duration() / dt - 1e-9));
      for (std::size_t j = 1; j <= ticks; ++j) {
        const double speed = j == ticks ? 0.0 : std::max(0.0, v - phase.VelocityAt(static_cast<double>(j) * dt));
        plan.speed_m_s.push_back(speed);
        s += speed * dt;
      }
    }
    plan.stops.emplace_back(plan.speed_m_s.size() - 1, s);
    return;
  }
}

// Each block's feed: programmed (or the default, or rapid), clamped by the arc radius and
// for short blocks.
void PlanBlockFeeds(const Program& program, const PathGeometry& path,
                    const PlannerSettings& settings, SpeedPlan* plan) {
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    const ProgramBlock& block = program.blocks[i];
    double feed = block.kind == MotionKind::kRapid ? settings.rapid_feed_m_s
                  : std::isnan(block.feed_m_s)     ? settings.default_feed_m_s
                                                   : block.feed_m_s;
    const PathElement& element = path.elements()[i];
    if (element.is_arc()) {
      // Arc feed clamp (as Fanuc's clamp by arc radius): the centripetal acceleration
      // v^2 / r stays within the acc/dec's acceleration.
      const double radius = std::min(element.start_radius_m, element.end_radius_m);
      feed = std::min(feed, std::sqrt(settings.accel_m_s2 * radius));
    }
    bool clamped = false;
    if (element.length_m > 0.0) {
      const ShortBlockFeed short_block = ClampShortBlock(settings.short_block, element.is_arc(),
                                                         element.length_m, feed, settings.period_s);
      feed = short_block.feed_m_s;
      clamped = short_block.clamped;
    }
    plan->block_feed_m_s.push_back(feed);
    plan->block_clamped.push_back(clamped);
    plan->short_block_clamps += clamped ? 1 : 0;
  }
}

// The stroke end: with the function on, the path from the crossing on runs at the minute
// feed, reached by the crossing (a junction there), so the planner slows down ahead of it.
// The pre-read window: a crossing more than look_ahead_blocks blocks ahead of where the
// slowdown must begin is seen only from block (crossing - window) on. The speed limit at
// the crossing.
double CrossingSpeedLimit(const PathGeometry& path, const PlannerSettings& settings,
                          const SpeedPlan& plan, double crossing_s) {
  const double minute = settings.stroke_end.minute_feed_mm_min / 60000.0;
  const std::size_t crossing_element = path.ElementAt(crossing_s);
  const std::size_t first_seen =
      crossing_element > static_cast<std::size_t>(settings.stroke_end.look_ahead_blocks)
          ? crossing_element - settings.stroke_end.look_ahead_blocks
          : 0;
  const double window_m = crossing_s - path.elements()[first_seen].start_s_m;
  const double feed = plan.block_feed_m_s[path.elements()[crossing_element].block];
  if (feed > minute && PhaseDistance(feed, minute, settings) > window_m) {
    // The speed at the crossing when the slowdown from the feed starts at the window:
    // D(feed, w) = window (D falls as w rises).
    return LargestWithin(minute, feed, -window_m,
                         [&](double w) { return -PhaseDistance(feed, w, settings); });
  }
  return minute;
}

// The stretches of one motion (rest to rest) as they come; each finished motion's speeds
// are appended to the plan, with a stop at its end.
class MotionAppender {
 public:
  MotionAppender(const PlannerSettings& settings, SpeedPlan* plan) : settings_(settings), plan_(plan) {}

  // Appends a stretch of `length` at `feed` whose start is limited to `limit`; `hold`: a
  // blend, run at one speed (never merged with its neighbours).
  void Add(double length, double feed, double limit, bool hold = false) {
    if (segments_.empty()) {
      segments_.push_back({length, feed, hold});
      junction_.assign(1, 0.0);
    } else if (hold == segments_.back().hold && limit >= feed && segments_.back().feed_m_s == feed) {
      segments_.back().length_m += length;  // no limit: one stretch
    } else {
      junction_.push_back(std::min({limit, segments_.back().feed_m_s, feed}));
      segments_.push_back({length, feed, hold});
    }
  }

  void Finish() {
    if (segments_.empty()) return;
    junction_.push_back(0.0);
    const CommandTrajectory motion = RealizeMotion(segments_, junction_, settings_);
    plan_->speed_m_s.insert(plan_->speed_m_s.end(), motion.velocity_m_s.begin() + 1,
                            motion.velocity_m_s.end());
    for (const Segment& segment : segments_) travelled_m_ += segment.length_m;
    plan_->stops.emplace_back(plan_->speed_m_s.size() - 1, travelled_m_);
    segments_.clear();
    junction_.clear();
  }

 private:
  const PlannerSettings& settings_;
  SpeedPlan* plan_;
  std::vector<Segment> segments_;
  std::vector<double> junction_;  // junction_[i]: the speed limit where segment i starts
  double travelled_m_ = 0.0;
};

// A blend's speed cap: the lower feed of the two blocks it joins, and v^2 / r within the
// acc/dec's acceleration.
double BlendFeed(const PathElement& blend, const SpeedPlan& plan, const PlannerSettings& s) {
  return std::min({plan.block_feed_m_s[blend.block], plan.block_feed_m_s[blend.block + 1],
                   std::sqrt(s.accel_m_s2 * blend.start_radius_m)});
}

// The end of a line next to a blend that runs at the blend's speed: what one period covers
// at its cap plus a period's acceleration, (v + a T) T (at most half the line). The ticks
// spread a speed change over the period it ends in, so a change ending at the arc would
// put tangential acceleration (at more than the blend's speed) on it; with the guard the
// arc carries its centripetal acceleration alone.
double BlendGuard(const PathElement* blend, const PathElement& line, const SpeedPlan& plan, const PlannerSettings& s) {
  if (blend == nullptr || !blend->blend || line.blend) return 0.0;
  const double guard = (BlendFeed(*blend, plan, s) + s.accel_m_s2 * s.period_s) * s.period_s;
  return std::min(guard, 0.5 * line.length_m);
}

// Appends one element: a blend as one hold, a line next to blends with its guards, the
// element across the stroke end's crossing in two.
void AddElement(const PathElement& element, const PathElement* before, const PathElement* after, double feed,
                double limit, const SpeedPlan& plan, const PlannerSettings& s, MotionAppender* motion) {
  const double head = BlendGuard(before, element, plan, s);
  const double tail = BlendGuard(after, element, plan, s);
  if (head == 0.0 && tail == 0.0) {
    motion->Add(element.length_m, feed, limit, element.blend);
    return;
  }
  if (head > 0.0) motion->Add(head, BlendFeed(*before, plan, s), limit, true);
  motion->Add(element.length_m - head - tail, feed, head > 0.0 ? kInf : limit);
  if (tail > 0.0) motion->Add(tail, BlendFeed(*after, plan, s), kInf, true);
}

}  // namespace

SpeedPlan PlanPathSpeed(const Program& program, const PathGeometry& path,
                        const PlannerSettings& settings) {
  return PlanPathSpeed(program, path, path, settings);
}

SpeedPlan PlanPathSpeed(const Program& program, const PathGeometry& programmed, const PathGeometry& path,
                        const PlannerSettings& settings) {
  SpeedPlan plan;
  PlanBlockFeeds(program, programmed, settings, &plan);
  plan.stroke_crossing_s_m = FindStrokeCrossing(path, settings.stroke_limits);
  const bool slow_down = plan.stroke_crossing_s_m && settings.stroke_end.enabled;
  const double crossing_s = plan.stroke_crossing_s_m.value_or(0.0);
  const double crossing_limit = slow_down ? CrossingSpeedLimit(path, settings, plan, crossing_s)
                                          : settings.stroke_end.minute_feed_mm_min / 60000.0;

  plan.speed_m_s.push_back(0.0);
  MotionAppender motion(settings, &plan);
  const PathElement* previous = nullptr;
  const std::vector<PathElement>& elements = path.elements();
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const PathElement& element = elements[i];
    if (element.kind == MotionKind::kDwell) {
      motion.Finish();
      // A dwell of any length holds at least until the next tick.
      const auto ticks = static_cast<std::size_t>(std::ceil(element.dwell_s / settings.period_s - 1e-9));
      plan.speed_m_s.insert(plan.speed_m_s.end(), ticks, 0.0);
      previous = nullptr;
      continue;
    }
    if (element.length_m == 0.0) continue;
    double feed = element.blend ? BlendFeed(element, plan, settings) : plan.block_feed_m_s[element.block];
    if (slow_down && element.start_s_m >= crossing_s) feed = std::min(feed, crossing_limit);
    double limit = kInf;
    if (previous != nullptr) {
      const Eigen::Vector3d before = previous->TangentAtFraction(1.0), after = element.TangentAtFraction(0.0);
      limit = settings.junction_deviation_m >= 0.0
                  ? JunctionDeviationLimit(before, after, settings.accel_m_s2, settings.junction_deviation_m)
                  : CornerSpeedLimit(before, after, settings.corner_velocity_change_m_s);
      if (limit <= 0.0) motion.Finish();  // an exact stop at the corner
    }
    if (slow_down && element.start_s_m < crossing_s && crossing_s < element.end_s_m()) {
      motion.Add(crossing_s - element.start_s_m, feed, limit);
      motion.Add(element.end_s_m() - crossing_s, std::min(feed, crossing_limit), crossing_limit);
    } else {
      AddElement(element, previous, i + 1 < elements.size() ? &elements[i + 1] : nullptr, feed, limit, plan,
                 settings, &motion);
    }
    previous = &element;
  }
  motion.Finish();
  if (plan.speed_m_s.size() < 2) plan.speed_m_s.push_back(0.0);
  if (plan.stroke_crossing_s_m) RaiseStrokeAlarm(plan, crossing_s, settings);
  return plan;
}

}  // namespace shapebench::controller
