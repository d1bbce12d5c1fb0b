// The CNC controller of seeds 004 and 000: feed-rate control and look-ahead block
// planning, pre-interpolation linear acc/dec with the vibration-suppressing pattern,
// interpolation every period, post-interpolation acc/dec (exponential or a profile
// table; per axis or tangential). Its output is the per-axis command the drive follows.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "controller/command_trajectory.h"
#include "controller/program.h"
#include "controller/short_block_clamp.h"
#include "controller/stroke_end.h"
#include "controller/vibration_suppression_pattern.h"
#include "common/field_list.h"

namespace shapebench::controller {

enum class PostInterpType { kNone, kExponential, kProfileTable };
// per_axis: each axis' pulses filtered on their own (the conventional way; pulls arcs
// inward); tangential: seed 000's queue (filtered dS releases the queued segments).
enum class Distribution { kPerAxis, kTangential };

struct PostInterpConfig {
  PostInterpType type = PostInterpType::kNone;
  double time_constant_s = 1.0 / 30.0;  // exponential: 1/K, K = 30 1/s (para. 29)
  // profile_table: the jerk coefficients (one per period, summing to 1), or
  // moving_average_s > 0 for n = moving_average_s / period equal ones (linear acc/dec).
  std::vector<double> table;
  double moving_average_s = 0.0;
  int max_table_length = 64;  // alpha_0 .. alpha_63 (para. 58)
  Distribution distribution = Distribution::kPerAxis;
  void validate() const;

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("type", &type, Choices<PostInterpType>{{"none", PostInterpType::kNone},
                                                    {"exponential", PostInterpType::kExponential},
                                                    {"profile_table", PostInterpType::kProfileTable}});
    a->Visit("time_constant_s", &time_constant_s);
    a->Visit("table", &table);
    a->Visit("moving_average_s", &moving_average_s);
    a->Visit("max_table_length", &max_table_length);
    a->Visit("distribution", &distribution,
             Choices<Distribution>{{"per_axis", Distribution::kPerAxis}, {"tangential", Distribution::kTangential}});
  }
};

struct ControllerConfig {
  double period_s = 0.001;       // interpolation period
  double feed_mm_min = 6000.0;   // commanded feed (mm/min at the YAML boundary); programs:
                                 // until the first F word, and the acc/dec reference
  double accel_time_s = 0.05;    // linear acc/dec: time to reach feed_mm_min; 0 = a step
  double rapid_feed_mm_min = 30000.0;  // G0
  // Corner rule: the largest velocity change per axis at a block junction (taken within
  // one period). 0 stops wherever the direction changes; collinear blocks never stop.
  double corner_velocity_change_mm_min = 0.0;
  // grbl's junction deviation (its setting $11, default 0.01 mm): the junction speed of a
  // grbl program (program_dialect: grbl) instead of the corner rule; 0 stops at every corner.
  double junction_deviation_mm = 0.01;
  PatternConfig pattern;
  PostInterpConfig post_interp;
  ShortBlockConfig short_block;  // seed 002
  StrokeEndConfig stroke_end;    // seed 001
  // The machine's stroke per axis (machine.stroke; the bench copies it here): the CNC's
  // stroke check stops the tool where the path leaves it.
  StrokeLimits stroke_limits;
  void validate() const;  // throws ValidationError naming the field
  double feed_m_s() const { return feed_mm_min / 60000.0; }
  // The steady acceleration of linear acc/dec: feed / accel_time (a one-period ramp for
  // accel_time_s = 0, the fastest the tick grid carries).
  double accel_m_s2() const;

  // The sections (pattern, ...) are read by their own readers (bench/config/field_reader.h).
  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("period_s", &period_s);
    a->Visit("feed_mm_min", &feed_mm_min);
    a->Visit("accel_time_s", &accel_time_s);
    a->Visit("rapid_feed_mm_min", &rapid_feed_mm_min);
    a->Visit("corner_velocity_change_mm_min", &corner_velocity_change_mm_min);
    a->Visit("junction_deviation_mm", &junction_deviation_mm);
    a->Visit("pattern", &pattern);
    a->Visit("post_interp", &post_interp);
    a->Visit("short_block", &short_block);
    a->Visit("stroke_end", &stroke_end);
  }
};

struct MoveConfig {
  double distance_mm = 100.0;  // signed: negative moves the other way
  int axis = -1;               // 0..2; -1: the machine's driven axis (the bench decides)
  void validate() const;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("distance_mm", &distance_mm);
    a->Visit("axis", &axis, Choices<int>{{"x", 0}, {"y", 1}, {"z", 2}});
  }
};

// The one-block program `move:` stands for: a straight move from the origin along `axis`.
Program MoveProgram(const MoveConfig& move, int axis);

// Where a stroke alarm fired (EP0646852, seed 001): the tick's time, the block and its
// G-code line, the axis furthest towards its limit, its position and that limit.
struct StrokeAlarmSite {
  double time_s = std::numeric_limits<double>::quiet_NaN();
  int block = -1;  // 0-based; -1 unknown
  int line = 0;    // the block's G-code line; 0 for `program:` blocks
  int axis = -1;   // -1: no limited axis found
  double position_m = std::numeric_limits<double>::quiet_NaN();
  double limit_m = std::numeric_limits<double>::quiet_NaN();
  // "at 0.42 s, Y = 0.5 m (limit 0.5 m), block 2 (line 2)"
  std::string Text() const;
};

// What the controller hands the drives: per axis, the velocity at every tick (the pulse
// of the period just ended / period), all axes the same length (N + 1 samples).
struct MultiAxisCommand {
  double period_s = 0.001;
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  std::array<CommandTrajectory, kNumAxes> axes;
  // The interpolator's state per tick k = 0..M (M <= N: the post-interpolation tail
  // follows): path position before post-interpolation acc/dec, and its block.
  std::vector<double> path_position_m;
  std::vector<int> block;
  std::vector<double> block_feed_m_s;  // the feed each block was planned at
  // How long the post-interpolation filter's output may trail the interpolator: the
  // table's length, plus 10 time constants of exponential acc/dec (0: no filter). The
  // bench sizes its contour error's window of blocks from it.
  double filter_lag_s = 0.0;
  std::vector<bool> block_clamped;     // lowered by the short-block clamp
  int short_block_clamps = 0;
  bool stroke_alarm = false;
  StrokeAlarmSite stroke_alarm_site;   // where, when stroke_alarm
  std::vector<std::string> warnings;   // e.g. the short-block clamp's ratio above its minimum

  std::size_t num_ticks() const { return axes[0].num_ticks(); }
  Eigen::Vector3d velocity_m_s(std::size_t k) const;
  Eigen::Vector3d accel_m_s2(std::size_t k) const;  // held over period k (k >= 1)
  // Positions p_0 .. p_N (start + trapezoids), summed in tick order.
  std::vector<Eigen::Vector3d> Positions() const;
};

// A bound on the command's length, checked once the speed plan knows it and before the
// per-tick pulses are allocated; `key` names the limit in the ValidationError.
struct CommandLimits {
  std::size_t max_ticks = std::numeric_limits<std::size_t>::max();
  std::string key;
};

// Throws ValidationError with a scenario-root key path when the program cannot be run.
MultiAxisCommand GenerateProgramCommand(const ControllerConfig& controller, const Program& program,
                                        const CommandLimits& limits = {});

// Para. 50 taken to its end cuts step 1 and leaves nothing of the shaping: the bench
// refuses a single move (or feed) too short (low) for its stepped pattern, naming
// `move.distance_mm` or `controller.feed_mm_min`.
void CheckShapedMove(const ControllerConfig& controller, double distance_m);

// The single-axis command of `move:` (the foundation's interface, kept for its tests).
CommandTrajectory GenerateCommand(const ControllerConfig& controller, const MoveConfig& move);

}  // namespace shapebench::controller
