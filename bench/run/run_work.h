// limits.max_work (docs/reliability.md#limits): a run's work, counted, never timed, so
// the verdict is the same on every host and at every --jobs. A unit is one of
// - an output sample: ticks x output substeps (bench/run/run_plan.h), whichever sampler,
//   a tail taken in closed form included;
// - an internal step or a right-hand-side evaluation of CVODE (CVodeGetNumSteps plus
//   CVodeGetNumRhsEvals), with or without nonlinear elements;
// - a pass over the poles of the exact path's in-tick extremum search (y, y', y'' or a
//   derivative bound at one time: model/tick_extremum.h).
// A run whose count exceeds the limit stops there (exit 3, WORK_LIMIT); one whose lower
// bound already does (ticks of the motion and the residual window x (substeps + the
// extremum grid's inner points)) is refused before it starts. The samplers look at the
// count every few ticks (stride) and once at the end: the verdict is "the run's whole
// count exceeds max_work", wherever it is seen. limits.max_wall_s (off by default) is
// looked at in the same places, from RunPlan::started: that verdict is the host's.
#pragma once

#include <cstddef>
#include <string_view>

#include "bench/run/run_plan.h"

namespace shapebench::bench {

// Throws model::SolverError("WORK_LIMIT") when `ticks` periods of the plan plus
// `period_work` of the integrator's own work each (PlantIntegrator::PeriodWorkAtLeast)
// exceed the scenario's limits.max_work; nothing has run then.
void CheckEstimatedWork(const RunPlan& plan, long period_work);

// Throws model::SolverError("WORK_LIMIT") when a run through tick `tick` with
// `integrator_work` (PlantIntegrator::Work; `what` names it) has done more than
// limits.max_work, saying what was done and how to raise the limit; ("WALL_LIMIT") when
// limits.max_wall_s is set and has passed.
void CheckWork(const RunPlan& plan, std::size_t tick, long integrator_work, std::string_view what);

// What PlantIntegrator::Work counts, for CheckWork's message.
inline constexpr std::string_view kCvodeWork = "CVODE steps and right-hand-side evaluations";
inline constexpr std::string_view kExtremumWork = "passes of the exact path's in-tick extremum search";

// The work of a run through `tick`: its output samples plus the integrator's own.
double RunWork(const RunPlan& plan, std::size_t tick, long integrator_work);

}  // namespace shapebench::bench
