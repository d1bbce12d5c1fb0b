// Attribution: which block and line of the program a metric comes from, by time (the block
// executing when the maximum was reached) and by cause (the latest change of the commanded
// acceleration within one damped period of the machine's lowest mode plus one tick before
// it: what most likely rang the structure). run's table, JSON and HTML report them
// (docs/views.md#attribution).
#pragma once

#include <cstddef>
#include <limits>
#include <string>

#include "controller/controller.h"
#include "controller/program.h"

namespace shapebench::bench {

// A time of the run and the program block the interpolator was in then.
struct ProgramSite {
  double time_s = std::numeric_limits<double>::quiet_NaN();
  int block = -1;        // 0-based (trace.csv's `block`); -1 after the program
  std::string file;      // the G-code file; "" for `program:` and `move:`
  int line = 0;          // the block's line in it; 0 without a file
};

struct MetricSource {
  bool present = false;
  ProgramSite at;     // the tick holding the maximum (its end time)
  ProgramSite cause;  // the latest change of commanded acceleration before it, or `at`'s
                      // tick when none lies in the window
};

struct MetricSources {
  MetricSource peak_deflection;
  MetricSource max_contour_error;
  MetricSource cruise_residual;  // present only where the run had cruise probes
  // The first tick holding peak_command_acceleration_m_s2 (present wherever the command
  // accelerates): on a blended path, the blend or the line where the acc/dec peaks.
  MetricSource peak_command_acceleration;
};

// The sites of the ticks `peak_tick`, `contour_tick` and `cruise_tick` (cruise: when
// `has_cruise`), looking back `lookback_s` (the lowest mode's damped period plus a tick)
// for the cause.
MetricSources AttributeSources(const controller::MultiAxisCommand& command, const controller::Program& program,
                               std::size_t peak_tick, std::size_t contour_tick, std::size_t cruise_tick,
                               bool has_cruise, double lookback_s);

// "at 0.512 s in block 3 (prog.nc:5); cause at 0.498 s in block 2 (prog.nc:4)".
std::string SourceText(const MetricSource& source);

}  // namespace shapebench::bench
