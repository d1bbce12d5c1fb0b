#include "controller/controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "common/format.h"
#include "common/key_rule_error.h"
#include "common/validation_error.h"
#include "controller/block_planner.h"
#include "controller/corner_blend.h"
#include "controller/interpolator.h"
#include "controller/linear_acc_dec.h"
#include "controller/path_geometry.h"
#include "controller/profile_table.h"
#include "controller/pulse_filter.h"
#include "controller/shaper_registry.h"
#include "controller/tangential_distribution.h"

namespace shapebench::controller {
namespace {


bool TableRealization(const ControllerConfig& c) {
  return c.pattern.realization == PatternRealization::kProfileTable &&
         FindShaper(c.pattern.method).kind != ShaperKind::kNone && c.pattern.mode != PatternMode::kOff;
}

StepPattern PreInterpolationPattern(const ControllerConfig& c) {
  if (c.pattern.realization != PatternRealization::kStepped) return StepPattern{};
  return MakeStepPattern(c.pattern);
}

// The pattern's table (profile_table realization), cascaded with post_interp's filter.
PulseFilter PostInterpFilter(const ControllerConfig& c) {
  PulseFilter filter;
  if (TableRealization(c)) {
    // The shaper's impulses (methods 1-4: their two steps' jerks) on the period grid.
    filter.table = ProfileTableFromImpulses(ShaperImpulses(c.pattern), c.period_s,
                                            ShaperGridDesign(c.pattern));
  }
  const PostInterpConfig& post = c.post_interp;
  if (post.type == PostInterpType::kProfileTable) {
    const std::vector<double> table =
        post.table.empty() ? MovingAverageTable(post.moving_average_s, c.period_s) : post.table;
    filter.table = ConvolveTables(filter.table, table);
  } else if (post.type == PostInterpType::kExponential) {
    filter.time_constant_s = post.time_constant_s;
  }
  return filter;
}

}  // namespace

void PostInterpConfig::validate() const {
  if (type == PostInterpType::kExponential && !(std::isfinite(time_constant_s) && time_constant_s > 0.0)) {
    throw ValidationError("time_constant_s", "must be > 0 for exponential acc/dec (got " +
                                                 FormatNumber(time_constant_s) + ")");
  }
  if (max_table_length < 1) {
    throw ValidationError("max_table_length", "must be >= 1 (got " + std::to_string(max_table_length) + ")");
  }
  if (type == PostInterpType::kProfileTable) {
    if (table.empty() == (moving_average_s == 0.0)) {
      throw ValidationError(table.empty() ? "type" : "moving_average_s",
                            "profile_table needs exactly one of `table` (the jerk coefficients) "
                            "and `moving_average_s` (> 0); to build the table from the pattern, "
                            "set controller.pattern.realization: profile_table");
    }
    if (!table.empty()) ValidateProfileTable(table, max_table_length);
    if (!(std::isfinite(moving_average_s) && moving_average_s >= 0.0)) {
      throw ValidationError("moving_average_s", "must be > 0 s (got " + FormatNumber(moving_average_s) + ")");
    }
  }
}

double ControllerConfig::accel_m_s2() const {
  return accel_time_s > 0.0 ? feed_m_s() / accel_time_s : feed_m_s() / period_s;
}

namespace {

// A pattern tuned above the period's Nyquist frequency 1 / (2 period) cannot be realized
// on the interpolation grid (5000 Hz at a 1 ms period was accepted silently); below it the
// steps between ticks are handled as docs/design-decisions.md describes.
void RequireBelowNyquist(const PatternConfig& pattern, double period_s) {
  const std::vector<double> frequencies = pattern.DesignFrequencies();
  const double nyquist_hz = 0.5 / period_s;
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    if (frequencies[i] > nyquist_hz) {
      const std::string key =
          pattern.frequencies_hz.empty() ? "pattern.frequency_hz" : "pattern.frequencies_hz[" + std::to_string(i) + "]";
      throw ValidationError(key, FormatNumber(frequencies[i]) + " Hz is above the Nyquist frequency of period_s " +
                                     FormatNumber(period_s) + " s (" + FormatNumber(nyquist_hz) +
                                     " Hz): no pattern at that frequency can be realized at this period");
    }
  }
}

// The stroke end's minute feed against the feed. Either key may be the slip (a feed in
// m/min, a minute feed too high): the loader blames the one the user gave.
void RequireMinuteFeedWithinFeed(const StrokeEndConfig& stroke_end, double feed_mm_min) {
  if (stroke_end.minute_feed_mm_min <= feed_mm_min) return;
  const std::string feed = FormatNumber(feed_mm_min) + " mm/min";
  const std::string minute = FormatNumber(stroke_end.minute_feed_mm_min) + " mm/min";
  throw KeyRuleError({{"stroke_end.minute_feed_mm_min", minute, "is above"}, {"feed_mm_min", feed, "is below"}},
                     "the feed must be at least the stroke end's minute feed (the speed near the stroke "
                     "end; both in mm/min); allowed: a feed of at least " + minute +
                         ", or a minute_feed_mm_min of at most " + feed);
}

}  // namespace

void ControllerConfig::validate() const {
  if (!(std::isfinite(period_s) && period_s > 0.0 && period_s <= 1.0)) {
    throw ValidationError("period_s", "must be in (0, 1] s (got " + FormatNumber(period_s) + ")");
  }
  if (!(std::isfinite(feed_mm_min) && feed_mm_min > 0.0)) {
    throw ValidationError("feed_mm_min", "must be > 0 (got " + FormatNumber(feed_mm_min) + ")");
  }
  if (!(std::isfinite(accel_time_s) && accel_time_s >= 0.0)) {
    throw ValidationError("accel_time_s", "must be >= 0 (0 = a feed step; got " + FormatNumber(accel_time_s) + ")");
  }
  if (!(std::isfinite(rapid_feed_mm_min) && rapid_feed_mm_min > 0.0)) {
    throw ValidationError("rapid_feed_mm_min", "must be > 0 (got " + FormatNumber(rapid_feed_mm_min) + ")");
  }
  if (!(std::isfinite(corner_velocity_change_mm_min) && corner_velocity_change_mm_min >= 0.0)) {
    throw ValidationError("corner_velocity_change_mm_min",
                          "must be >= 0 (0 stops at every corner; got " +
                              FormatNumber(corner_velocity_change_mm_min) + ")");
  }
  if (!(std::isfinite(junction_deviation_mm) && junction_deviation_mm >= 0.0)) {
    throw ValidationError("junction_deviation_mm",
                          "must be >= 0 (grbl's $11, default 0.01; 0 stops at every corner; got " +
                              FormatNumber(junction_deviation_mm) + ")");
  }
  try {
    pattern.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("pattern");
  }
  const bool shaped = MakeStepPattern(pattern).shapes();
  if (shaped) RequireBelowNyquist(pattern, period_s);
  if (shaped && pattern.realization == PatternRealization::kStepped && accel_time_s == 0.0) {
    throw ValidationError("accel_time_s", "must be > 0 when a pattern is active: the steps are "
                                          "fractions of the steady acceleration feed / accel_time_s");
  }
  try {
    post_interp.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("post_interp");
  }
  try {
    short_block.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("short_block");
  }
  try {
    stroke_end.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("stroke_end");
  }
  RequireMinuteFeedWithinFeed(stroke_end, feed_mm_min);
  if (post_interp.type == PostInterpType::kProfileTable && post_interp.table.empty()) {
    const long n = std::lround(post_interp.moving_average_s / period_s);
    if (n < 1 || n > post_interp.max_table_length) {
      throw ValidationError("post_interp.moving_average_s",
                            "gives " + std::to_string(n) + " coefficients at period_s " +
                                FormatNumber(period_s) + "; allowed: 1 to max_table_length (" +
                                std::to_string(post_interp.max_table_length) + ")");
    }
  }
  if (TableRealization(*this)) {
    if (pattern.mode != PatternMode::kBoth) {
      throw ValidationError("pattern.mode",
                            "the profile_table realization shapes the start and the end of every "
                            "speed change (mode both); modes start and end need realization stepped");
    }
    const std::size_t length =
        ProfileTableFromImpulses(ShaperImpulses(pattern), period_s, ShaperGridDesign(pattern)).size();
    if (static_cast<long>(length) > post_interp.max_table_length) {
      throw ValidationError("pattern.realization",
                            "the pattern's profile table needs " + std::to_string(length) +
                                " coefficients at period_s " + FormatNumber(period_s) +
                                ", more than post_interp.max_table_length (" +
                                std::to_string(post_interp.max_table_length) +
                                "); allowed: a longer period, a larger max_table_length, or "
                                "realization stepped");
    }
  }
}

void MoveConfig::validate() const {
  if (!(std::isfinite(distance_mm) && distance_mm != 0.0)) {
    throw ValidationError("distance_mm", "must be a non-zero number of mm (got " + FormatNumber(distance_mm) + ")");
  }
}

Program MoveProgram(const MoveConfig& move, int axis) {
  Program program;
  ProgramBlock block;
  block.kind = MotionKind::kLinear;
  block.end_m(axis) = move.distance_mm * 1e-3;
  program.blocks.push_back(block);
  return program;
}

Eigen::Vector3d MultiAxisCommand::velocity_m_s(std::size_t k) const {
  return {axes[0].velocity_m_s[k], axes[1].velocity_m_s[k], axes[2].velocity_m_s[k]};
}

Eigen::Vector3d MultiAxisCommand::accel_m_s2(std::size_t k) const {
  return {axes[0].accel_m_s2(k), axes[1].accel_m_s2(k), axes[2].accel_m_s2(k)};
}

std::vector<Eigen::Vector3d> MultiAxisCommand::Positions() const {
  std::vector<Eigen::Vector3d> positions(num_ticks() + 1, start_m);
  for (std::size_t k = 1; k <= num_ticks(); ++k) {
    positions[k] = positions[k - 1];
    for (int a = 0; a < kNumAxes; ++a) positions[k](a) += axes[a].increment_m(k);
  }
  return positions;
}

namespace {

// The pattern's key that sets how long its acceleration lasts (its step 1, or the shaper),
// with its value as shown.
RuleKey PatternTimeKey(const PatternConfig& pattern) {
  const ShaperKind kind = FindShaper(pattern.method).kind;
  if (kind == ShaperKind::kCustom) return {"controller.pattern.impulses", "(the impulses given)", "last too long for"};
  if (kind == ShaperKind::kPatentStep && pattern.method == "4") {
    return {"controller.pattern.t1_s", FormatNumber(pattern.t1_s) + " s", "is too long for"};
  }
  if (!pattern.frequencies_hz.empty()) {
    std::string shown;
    for (const double f : pattern.frequencies_hz) shown += (shown.empty() ? "[" : ", ") + FormatNumber(f);
    return {"controller.pattern.frequencies_hz", shown + "] Hz", "are too low for"};
  }
  return {"controller.pattern.frequency_hz", FormatNumber(pattern.frequency_hz) + " Hz", "is too low for"};
}

// The acc/dec time against the pattern's length: the feed cancels out of the rule
// (LowestShapedSpeed is a multiple of feed / accel_time_s), so these two are its keys.
KeyRuleError PatternTimeError(const ControllerConfig& controller, const std::string& rule) {
  return KeyRuleError({{"controller.accel_time_s", FormatNumber(controller.accel_time_s) + " s", "is too short for"},
                       PatternTimeKey(controller.pattern)},
                      rule);
}

}  // namespace

void CheckShapedMove(const ControllerConfig& controller, double distance_m) {
  if (controller.pattern.realization != PatternRealization::kStepped) return;
  const StepPattern pattern = MakeStepPattern(controller.pattern);
  if (!pattern.shapes()) return;
  const double accel_m_s2 = controller.accel_m_s2();
  if (pattern.general()) {
    // A library shaper convolved with the acc/dec needs no shortening; with one end
    // unshaped, the phase must outlast the shaped end's impulses.
    const double lowest_speed = LowestShapedSpeed(accel_m_s2, pattern);
    if (controller.feed_m_s() < lowest_speed * (1.0 - 1e-12)) {
      throw PatternTimeError(controller,
                             "the shaper at one end of the phase (pattern.mode start or end) needs an acc/dec "
                             "time of at least " + FormatNumber(lowest_speed / accel_m_s2) +
                                 " s so the unshaped end's step falls outside the shaper (the feed does not "
                                 "matter: the acceleration is feed / accel_time_s); allowed: a longer "
                                 "accel_time_s, a shorter shaper (a higher design frequency), or pattern.mode both");
    }
    const double shortest_m = ShortestShapedMove(accel_m_s2, pattern);
    if (distance_m < shortest_m * (1.0 - 1e-12)) {
      throw ValidationError(
          "move.distance_mm",
          "a move of " + FormatNumber(distance_m * 1e3) + " mm is too short for the shaper at one end of the "
          "phase (pattern.mode start or end): it needs at least " + FormatNumber(shortest_m * 1e3) +
              " mm; allowed: a longer move, a longer accel_time_s, or pattern.mode both");
    }
    return;
  }
  const double lowest_speed = LowestShapedSpeed(accel_m_s2, pattern);
  if (controller.feed_m_s() < lowest_speed * (1.0 - 1e-12)) {
    throw PatternTimeError(controller,
                           "after para. 50's shortening (steady acceleration, then step 2) the acc/dec time "
                           "must be at least the pattern's step 1 at each shaped end, " +
                               FormatNumber(lowest_speed / accel_m_s2) +
                               " s, or step 1 is cut and nothing of the shaping is left (the feed does not "
                               "matter: the acceleration is feed / accel_time_s); allowed: a longer "
                               "accel_time_s, a shorter step 1 (a higher frequency_hz; method 4: a shorter "
                               "t1_s), or pattern.mode off");
  }
  const double shortest_m = ShortestShapedMove(accel_m_s2, pattern);
  if (distance_m < shortest_m * (1.0 - 1e-12)) {
    throw ValidationError(
        "move.distance_mm",
        "a move of " + FormatNumber(distance_m * 1e3) + " mm is too short for the pattern: after para. 50's "
        "shortening (steady acceleration, then step 2) it needs at least " + FormatNumber(shortest_m * 1e3) +
            " mm, or step 1 is cut and nothing of the shaping is left; allowed: a longer move, a "
            "longer accel_time_s, or pattern.mode off");
  }
}

namespace {

std::string AxisLetter(int axis) { return std::string(1, static_cast<char>('X' + axis)); }

// Where the stroke alarm fired: the tick, the axis furthest towards its limit there, and
// the block, since the rest of the program is dropped (EP0646852 (seed 001): the
// conventional stroke check stops the tool there).
StrokeAlarmSite FindStrokeAlarmSite(const Program& program, const PathGeometry& path,
                                    const InterpolatedPulses& pulses, const SpeedPlan& plan,
                                    const StrokeLimits& limits, double period_s) {
  StrokeAlarmSite site;
  const std::size_t k = std::min(plan.alarm_tick, pulses.path_position_m.size() - 1);
  site.time_s = static_cast<double>(plan.alarm_tick) * period_s;
  const Eigen::Vector3d p = path.PointAt(pulses.path_position_m[k]);
  double beyond = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (!limits[a]) continue;
    for (int side = 0; side < 2; ++side) {
      const double bound = (*limits[a])[side];
      const double reach = side == 0 ? bound - p(a) : p(a) - bound;
      if (reach > beyond) {
        beyond = reach;
        site.axis = a;
        site.position_m = p(a);
        site.limit_m = bound;
      }
    }
  }
  const int block = k < pulses.block.size() ? pulses.block[k] : -1;
  if (block >= 0 && static_cast<std::size_t>(block) < program.blocks.size()) {
    site.block = block;
    const int line = program.blocks[static_cast<std::size_t>(block)].source_line;
    if (program.gcode_lines && line > 0) site.line = line;
  }
  return site;
}

// The stroke alarm in words: the warning on stderr.
std::string StrokeAlarmWarning(const StrokeAlarmSite& site) {
  std::string text = "stroke alarm";
  if (site.axis >= 0) {
    text += " at " + AxisLetter(site.axis) + " = " + FormatNumber(site.position_m) + " m (limit " +
            FormatNumber(site.limit_m) + " m)";
  }
  if (site.block >= 0) {
    text += " in block " + std::to_string(site.block + 1);
    if (site.line > 0) text += " (line " + std::to_string(site.line) + ")";
  }
  return text + ": the rest of the program was not run";
}

// A blended run's positions as the programmed path's arc length (corner_blend.h), and the
// programmed block there: the contour error's window, the trace and the attribution read
// the programmed path.
void ToProgrammedPath(const PathGeometry& programmed, const PathGeometry& blended, InterpolatedPulses* pulses) {
  std::size_t hint = 0, programmed_hint = 0;
  for (std::size_t k = 0; k < pulses->path_position_m.size(); ++k) {
    const double s = SourcePosition(blended, pulses->path_position_m[k], &hint);
    pulses->path_position_m[k] = s;
    if (programmed.elements().empty()) continue;
    programmed_hint = programmed.ElementAt(s, programmed_hint);
    pulses->block[k] = programmed.elements()[programmed_hint].block;
  }
}

}  // namespace

std::string StrokeAlarmSite::Text() const {
  std::string text = "at " + FormatNumber(time_s) + " s";
  if (axis >= 0) {
    text += ", " + AxisLetter(axis) + " = " + FormatNumber(position_m) + " m (limit " + FormatNumber(limit_m) + " m)";
  }
  if (block >= 0) {
    text += ", block " + std::to_string(block + 1);
    if (line > 0) text += " (line " + std::to_string(line) + ")";
  }
  return text;
}

MultiAxisCommand GenerateProgramCommand(const ControllerConfig& controller, const Program& program,
                                        const CommandLimits& limits) {
  const double dt = controller.period_s;
  const PathGeometry programmed(program);
  const std::optional<PathGeometry> blended =
      BlendCorners(program, programmed, 16.0 * controller.accel_m_s2() * dt * dt);
  const PathGeometry& path = blended ? *blended : programmed;
  PlannerSettings settings;
  settings.period_s = dt;
  settings.accel_m_s2 = controller.accel_m_s2();
  settings.pattern = PreInterpolationPattern(controller);
  settings.grid_design = ShaperGridDesign(controller.pattern);
  settings.default_feed_m_s = controller.feed_m_s();
  settings.rapid_feed_m_s = controller.rapid_feed_mm_min / 60000.0;
  settings.corner_velocity_change_m_s = controller.corner_velocity_change_mm_min / 60000.0;
  if (program.junction_deviation_rule) settings.junction_deviation_m = controller.junction_deviation_mm * 1e-3;
  settings.short_block = controller.short_block;
  settings.stroke_end = controller.stroke_end;
  settings.stroke_limits = controller.stroke_limits;
  SpeedPlan plan = PlanPathSpeed(program, programmed, path, settings);
  if (plan.speed_m_s.size() > limits.max_ticks) {
    throw ValidationError(limits.key, "the command takes " + std::to_string(plan.speed_m_s.size() - 1) +
                                          " periods, more than " + limits.key + " allows (" +
                                          std::to_string(limits.max_ticks) + " periods)");
  }
  InterpolatedPulses pulses = Interpolate(path, plan, dt);
  StrokeAlarmSite alarm_site;
  if (plan.stroke_alarm) alarm_site = FindStrokeAlarmSite(program, path, pulses, plan, controller.stroke_limits, dt);
  if (blended) ToProgrammedPath(programmed, *blended, &pulses);

  const PulseFilter filter = PostInterpFilter(controller);
  std::vector<Eigen::Vector3d> out;
  if (filter.is_identity()) {
    out = std::move(pulses.axis_pulses_m);
  } else if (controller.post_interp.distribution == Distribution::kTangential) {
    out = DistributeTangentially(pulses.axis_pulses_m, pulses.tangential_pulses_m, filter, dt);
  } else {
    for (int a = 0; a < kNumAxes; ++a) {
      std::vector<double> axis(pulses.axis_pulses_m.size());
      for (std::size_t k = 0; k < axis.size(); ++k) axis[k] = pulses.axis_pulses_m[k](a);
      const std::vector<double> filtered = filter.Apply(axis, dt);
      if (out.size() < filtered.size()) out.resize(filtered.size(), Eigen::Vector3d::Zero());
      for (std::size_t k = 0; k < filtered.size(); ++k) out[k](a) = filtered[k];
    }
  }
  // The drive's velocity sample at tick k is the pulse rate of period k; a command ends
  // at rest.
  if (out.empty() || out.back() != Eigen::Vector3d::Zero()) out.push_back(Eigen::Vector3d::Zero());
  MultiAxisCommand command;
  command.period_s = dt;
  command.start_m = program.start_m;
  for (int a = 0; a < kNumAxes; ++a) {
    CommandTrajectory& axis = command.axes[a];
    axis.period_s = dt;
    axis.velocity_m_s.assign(out.size() + 1, 0.0);
    // An axis whose pulses are all +0 stays at the 0.0 assigned (0 / dt, without dividing).
    bool moves = false;
    for (std::size_t k = 0; k < out.size() && !moves; ++k) {
      moves = out[k](a) != 0.0 || std::signbit(out[k](a));
    }
    if (!moves) continue;
    for (std::size_t k = 0; k < out.size(); ++k) axis.velocity_m_s[k + 1] = out[k](a) / dt;
  }
  command.filter_lag_s = static_cast<double>(filter.table.size()) * dt + 10.0 * filter.time_constant_s;
  command.path_position_m = std::move(pulses.path_position_m);
  command.block = std::move(pulses.block);
  command.block_feed_m_s = std::move(plan.block_feed_m_s);
  command.block_clamped = std::move(plan.block_clamped);
  command.short_block_clamps = plan.short_block_clamps;
  command.stroke_alarm = plan.stroke_alarm;
  command.stroke_alarm_site = alarm_site;
  command.warnings = program.warnings;
  for (std::string& warning : ShortBlockWarnings(controller.short_block)) {
    command.warnings.push_back(std::move(warning));
  }
  if (plan.stroke_alarm) command.warnings.push_back(StrokeAlarmWarning(alarm_site));
  return command;
}

CommandTrajectory GenerateCommand(const ControllerConfig& controller, const MoveConfig& move) {
  CheckShapedMove(controller, std::abs(move.distance_mm) * 1e-3);
  return GenerateProgramCommand(controller, MoveProgram(move, 0)).axes[0];
}

}  // namespace shapebench::controller
