// RunOptions of the general exact path (bench/run/run_scenario.cc), not the single-mode closed
// forms (bench/run/closed_form_sampler.h) a run of one mode along one line takes its metrics
// from: for the tests of the general path's own mechanisms (its fast samples, deferred
// substeps, the closed-form tail) and the tests that compare the two.
#pragma once

#include "bench/run/run_scenario.h"

namespace shapebench::bench::testing {

inline RunOptions GeneralPath(bool record_trace) {
  RunOptions options;
  options.record_trace = record_trace;
  options.fastest_sampler = SamplerKind::kDeferredSubsteps;
  return options;
}

}  // namespace shapebench::bench::testing
