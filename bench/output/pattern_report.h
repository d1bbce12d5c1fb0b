// The `pattern` command's report: the shaping pattern as the patent's para. 49
// parameters, as jerk impulses in continuous time, as the profile table on the
// interpolation-period grid that the controller actually uses, and the residual
// vibration each leaves at the design frequency (every design frequency, with the
// design damping; any method, the shaper library's too). The table lists the coefficients
// of at least 1e-4 of the largest and counts the rest (the grid correction's dust).
#pragma once

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "bench/scenario/scenario.h"
#include "controller/controller.h"

namespace shapebench::bench {

// The residual vibration the pattern leaves at one design frequency (undamped, or with
// the design damping ratio), as a fraction of an unshaped step's.
struct PatternResidual {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double stepped = 0.0;        // the impulses at their continuous times
  double profile_table = 0.0;  // the profile table on the period grid
  double rounded = 0.0;        // each impulse rounded to its nearest tick, uncorrected
};

// What the report shows, as numbers (the report prints them; the Python module returns
// them): the impulses at the start of a shaped phase, the profile table the controller
// builds from them (alpha_n at t = n period_s), the residuals at the design frequencies.
// Method none (or mode off): the unshaped step, impulse {0, 1}, table {1}.
struct PatternData {
  bool shapes = false;
  std::vector<double> design_frequencies_hz;
  std::vector<controller::Impulse> impulses;
  double period_s = 0.0;
  std::vector<double> table;
  std::vector<PatternResidual> residuals;
};
PatternData ComputePattern(const controller::ControllerConfig& controller);

// The residual vibration at one mode of the scenario's machine, with its own damping.
struct ModeResidual {
  int axis = 0;          // model::AxisName
  std::size_t mode = 0;  // 1-based within the axis
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double participation = 0.0;
  double stepped = 0.0;
  double profile_table = 0.0;
};
// Every mode of every modelled axis, in axis order (empty: a machine without modes).
std::vector<ModeResidual> MachineModeResiduals(const Scenario& scenario);

// The motion time of the scenario's move or program with its pattern and without
// (commands generated, as RunScenario's motion_time_s); NaN and `why_not` (the planner's
// "field: message") when the unshaped or shaped command cannot be planned.
struct PatternMotionTimes {
  double shaped_s = NAN;
  double unshaped_s = NAN;
  std::string why_not;
};
PatternMotionTimes MotionTimesWithAndWithoutPattern(const Scenario& scenario);

void PrintPatternReport(std::ostream& out, const controller::ControllerConfig& controller);

// The same, then the residual vibration at every mode of the scenario's machine (each
// axis, each mode with its own damping), then the time penalty in machine terms: the shaper's duration, the motion
// time it adds to the scenario's move or program (commands generated with and without
// the pattern), and the contour error it causes at the feed (profile_table per axis: the
// table's radial error sigma^2 v^2 / (2 r) on a reference arc of 10 mm).
void PrintPatternReport(std::ostream& out, const Scenario& scenario);

}  // namespace shapebench::bench
