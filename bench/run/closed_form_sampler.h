// The closed-form sampler: one structural mode under the kinematic drive along one
// straight line (RunPlan::single_mode), the sweep users run most (the natural-period sweep
// of the patent's SDOF case, JP2551868B2 (seed 004) paras. 11-23) at the cost of the bare
// zero-order hold. docs/samplers.md derives its closed forms; its metrics are the plant
// samplers' to rounding (tests/bench/run/single_mode_run_test.cc: within 1e-11).
#pragma once

#include <memory>

#include "bench/run/run_plan.h"
#include "bench/run/run_result.h"
#include "bench/run/sampler.h"

namespace shapebench::bench {

// For a plan whose single_mode case is set.
std::unique_ptr<Sampler> MakeClosedFormSampler(const RunPlan& plan, RunResult* result);

// While one lives on this thread, the caller reads no max_contour_error_m (a sweep whose
// rows do not list it): the closed form skips the contour error's samples, a third of a
// natural-period sweep's point, and reports it n/a (NaN). Every other metric is the same
// bit for bit. Thread-local like CrossCheckFamilyScope; nests.
class ContourUnreadScope {
 public:
  explicit ContourUnreadScope(bool unread);
  ~ContourUnreadScope();
  ContourUnreadScope(const ContourUnreadScope&) = delete;
  ContourUnreadScope& operator=(const ContourUnreadScope&) = delete;

 private:
  bool previous_;
};

}  // namespace shapebench::bench
