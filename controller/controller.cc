#include "controller/controller.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/exponential_acc_dec.h"
#include "controller/linear_acc_dec.h"

namespace shapebench::controller {
namespace {

std::string Num(double v) { return FormatNumber(v); }

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

void PostInterpConfig::validate() const {
  if (type == PostInterpType::kExponential && !(Finite(time_constant_s) && time_constant_s > 0.0)) {
    throw ValidationError("time_constant_s", "must be > 0 for exponential acc/dec (got " +
                                                 Num(time_constant_s) + ")");
  }
}

void ControllerConfig::validate() const {
  if (!(Finite(period_s) && period_s > 0.0 && period_s <= 1.0)) {
    throw ValidationError("period_s", "must be in (0, 1] s (got " + Num(period_s) + ")");
  }
  if (!(Finite(feed_mm_min) && feed_mm_min > 0.0)) {
    throw ValidationError("feed_mm_min", "must be > 0 (got " + Num(feed_mm_min) + ")");
  }
  if (!(Finite(accel_time_s) && accel_time_s >= 0.0)) {
    throw ValidationError("accel_time_s", "must be >= 0 (0 = a feed step; got " + Num(accel_time_s) + ")");
  }
  try {
    pattern.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("pattern");
  }
  if (MakeStepPattern(pattern).shapes() && accel_time_s == 0.0) {
    throw ValidationError("accel_time_s", "must be > 0 when a pattern is active: the steps are "
                                          "fractions of the steady acceleration feed / accel_time_s");
  }
  try {
    post_interp.validate();
  } catch (const ValidationError& e) {
    throw e.Prefixed("post_interp");
  }
}

void MoveConfig::validate() const {
  if (!(Finite(distance_mm) && distance_mm != 0.0)) {
    throw ValidationError("distance_mm", "must be a non-zero number of mm (got " + Num(distance_mm) + ")");
  }
}

CommandTrajectory GenerateCommand(const ControllerConfig& controller, const MoveConfig& move) {
  const double feed_m_s = controller.feed_m_s();
  // accel_time_s = 0 commands a feed step: the fastest the tick grid can carry is a ramp
  // over one interpolation period.
  const double accel_m_s2 = controller.accel_time_s > 0.0 ? feed_m_s / controller.accel_time_s
                                                          : feed_m_s / controller.period_s;
  const StepPattern pattern = MakeStepPattern(controller.pattern);
  const double distance_m = std::abs(move.distance_mm) * 1e-3;
  if (pattern.shapes()) {
    const double lowest_speed = LowestShapedSpeed(accel_m_s2, pattern);
    if (feed_m_s < lowest_speed * (1.0 - 1e-12)) {
      throw ValidationError(
          "controller.feed_mm_min",
          "feed " + Num(controller.feed_mm_min) + " mm/min is too low for the pattern: after para. 50's "
          "shortening (steady acceleration, then step 2) the feed must be at least " +
              Num(lowest_speed * 60000.0) + " mm/min, or step 1 is cut and nothing of the shaping is left; "
              "allowed: a higher feed, a longer accel_time_s, or pattern.mode off");
    }
    const double shortest_m = ShortestShapedMove(accel_m_s2, pattern);
    if (distance_m < shortest_m * (1.0 - 1e-12)) {
      throw ValidationError(
          "move.distance_mm",
          "a move of " + Num(std::abs(move.distance_mm)) + " mm is too short for the pattern: after para. 50's "
          "shortening (steady acceleration, then step 2) it needs at least " + Num(shortest_m * 1e3) +
              " mm, or step 1 is cut and nothing of the shaping is left; allowed: a longer move, a "
              "longer accel_time_s, or pattern.mode off");
    }
  }
  CommandTrajectory command =
      SampleOnTicks(distance_m, feed_m_s, accel_m_s2, pattern, controller.period_s,
                    controller.pattern.frequency_hz);
  if (controller.post_interp.type == PostInterpType::kExponential) {
    command = ApplyExponentialAccDec(command, controller.post_interp.time_constant_s);
  }
  if (move.distance_mm < 0.0) {
    for (double& v : command.velocity_m_s) v = -v;
  }
  return command;
}

}  // namespace shapebench::controller
