// The `pattern` command's report: the shaping pattern as the patent's para. 49
// parameters, as jerk impulses in continuous time, as the profile table on the
// interpolation-period grid that the controller actually uses, and the residual
// vibration each leaves at the design frequency (every design frequency, with the
// design damping; any method, the shaper library's too). The table lists the coefficients
// of at least 1e-4 of the largest and counts the rest (the grid correction's dust).
#pragma once

#include <ostream>

#include "bench/sim/scenario.h"
#include "controller/controller.h"

namespace shapebench::bench {

void PrintPatternReport(std::ostream& out, const controller::ControllerConfig& controller);

// The same, then the residual vibration at every mode of the scenario's machine (each
// axis, each mode with its own damping), then the time penalty in machine terms: the shaper's duration, the motion
// time it adds to the scenario's move or program (commands generated with and without
// the pattern), and the contour error it causes at the feed (profile_table per axis: the
// table's radial error sigma^2 v^2 / (2 r) on a reference arc of 10 mm).
void PrintPatternReport(std::ostream& out, const Scenario& scenario);

}  // namespace shapebench::bench
