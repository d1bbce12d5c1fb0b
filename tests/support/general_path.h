// RunOptions of the general exact path (bench/sim/cosim.cc), not the single-mode closed
// forms (bench/sim/single_mode_run.h) a run of one mode along one line takes its metrics
// from: for the tests of the general path's own mechanisms (its fast samples, deferred
// substeps, the closed-form tail) and the tests that compare the two.
#pragma once

#include "bench/sim/cosim.h"

namespace shapebench::bench::testing {

inline RunOptions GeneralPath(bool record_trace) {
  RunOptions options;
  options.record_trace = record_trace;
  options.single_mode = false;
  return options;
}

}  // namespace shapebench::bench::testing
