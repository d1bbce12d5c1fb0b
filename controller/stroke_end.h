// EP0646852 (seed 001): deceleration at the stroke end. Looking ahead over the pre-read
// blocks, the planner finds where the path, arcs followed along their curve, first
// leaves the stroke [min, max] of an axis. With the function on, it slows the tool to a
// minute feed by that point, starting at the deceleration distance the feed, the minute
// feed and the acceleration need (the pattern still shapes it), so that the stroke check
// stops the tool at the stroke end itself and the whole stroke is usable. Off, the
// conventional control runs at full feed until the tool reaches the stroke end and then
// stops at the normal deceleration, overshooting by about F^2 / (2 a).
#pragma once

#include <array>
#include <optional>

#include "controller/path_geometry.h"
#include "common/field_list.h"

namespace shapebench::controller {

struct StrokeEndConfig {
  bool enabled = false;
  int look_ahead_blocks = 15;          // pre-read blocks the check sees
  double minute_feed_mm_min = 100.0;   // the speed near the stroke end
  void validate() const;               // throws ValidationError naming the field

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("enabled", &enabled, Choices<bool>{{"true", true}, {"false", false}});
    a->Visit("look_ahead_blocks", &look_ahead_blocks);
    a->Visit("minute_feed_mm_min", &minute_feed_mm_min);
  }
};

// Per axis, [min, max] in metres; nullopt: no stroke limit on that axis.
using StrokeLimits = std::array<std::optional<std::array<double, 2>>, 3>;

// Arc length of the first point of the path outside the limits (to ~1e-12 m), or
// nullopt when the path stays inside. A path that starts outside gives 0.
std::optional<double> FindStrokeCrossing(const PathGeometry& path, const StrokeLimits& limits);

// How far `p` lies beyond the limits (0 inside).
double StrokeOvershoot(const Eigen::Vector3d& p, const StrokeLimits& limits);

}  // namespace shapebench::controller
