// The CNC controller for one straight move along the driven axis: feed, pre-interpolation
// linear acc/dec with the vibration-suppressing pattern, post-interpolation acc/dec.
#pragma once

#include "controller/command_trajectory.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

enum class PostInterpType { kNone, kExponential };

struct PostInterpConfig {
  PostInterpType type = PostInterpType::kNone;
  double time_constant_s = 1.0 / 30.0;  // exponential: 1/K, K = 30 1/s (para. 29)
  void validate() const;
};

struct ControllerConfig {
  double period_s = 0.001;       // interpolation period
  double feed_mm_min = 6000.0;   // commanded feed (mm/min at the YAML boundary)
  double accel_time_s = 0.05;    // linear acc/dec: time to reach the feed; 0 = a step
  PatternConfig pattern;
  PostInterpConfig post_interp;
  void validate() const;  // throws ValidationError naming the field
  double feed_m_s() const { return feed_mm_min / 60000.0; }
};

struct MoveConfig {
  double distance_mm = 100.0;  // signed: negative moves the other way
  void validate() const;
};

// Throws ValidationError with a scenario-root key path ("move.distance_mm", ...) when the
// move cannot be planned (e.g. too short for its pattern).
CommandTrajectory GenerateCommand(const ControllerConfig& controller, const MoveConfig& move);

}  // namespace shapebench::controller
