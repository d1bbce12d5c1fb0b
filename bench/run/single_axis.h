// What the single-axis sampler (single_axis_sampler.cc) needs of a run whose command moves
// one axis only, along one straight element of that axis, with the view on that axis.
#pragma once

#include "bench/run/command_samples.h"
#include "bench/run/output_view.h"
#include "bench/run/path_tallies.h"

namespace shapebench::bench {

// A run whose command moves one axis only, along a single straight element of that axis,
// with the metrics' view on that axis: every other component of command, deflection and
// tool error stays exactly 0 (checked per period on the outputs), so the samples need only
// that axis' scalars. The arithmetic is the general samples', component by component
// (tests/bench/cosim_fast_path_test.cc compares the two bit for bit).
struct SingleAxis {
  int axis = -1;
  double start_m = 0.0;      // the element's start on the axis
  double direction = 0.0;    // +1 or -1
  double length_m = 0.0;
};

// That axis, or axis -1 when the run is not such a run: `element` the path's only
// element (null when it has more), or the gauge's.
SingleAxis FindSingleAxis(const controller::PathElement* element, const CommandSamples& samples,
                          const OutputView& view, bool has_stroke);
SingleAxis FindSingleAxis(const CommandSamples& samples, const OutputView& view, const ContourGauge& gauge,
                          bool has_stroke);

// What stays the same from tick to tick of the single-axis samples.
struct SingleAxisSampling {
  const double* deflections;
  const double* tool_errors;
  const double* taus;
  int width;
  int substeps;
  SingleAxis single;
};

}  // namespace shapebench::bench
