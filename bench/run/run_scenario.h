// The co-simulation master: the command, the prepared run (run_plan.h), a sampler
// (sampler.h) through the ticks t_k = k * period, the metrics (finish_metrics.h).
#pragma once

#include "bench/run/command_samples.h"
#include "bench/scenario/metrics.h"
#include "bench/run/run_result.h"
#include "bench/scenario/scenario.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {

struct RunOptions {
  // Record the Trace (every output substep: run --out's trace.csv and plots). Sweeps and
  // checks need only the metrics, which are the same bit for bit either way.
  bool record_trace = true;
  // The command of this scenario's controller and program, generated before (a sweep's
  // points that differ only in keys the controller does not read share it): used as it is,
  // and RunResult::command is then left empty. Null: generated here.
  const controller::MultiAxisCommand* command = nullptr;
  // SampleCommand(*command), computed before with it (a sweep shares both, read-only,
  // between its points and threads). Null: computed here. Ignored without `command`.
  const CommandSamples* samples = nullptr;
  // The program `command` was generated from and its path geometry (a sweep shares them
  // with the command): used as they are, and RunResult::program is then left empty.
  // Null: made here. Ignored without `command`; both or neither.
  const controller::Program* program = nullptr;
  const controller::PathGeometry* path = nullptr;
  // The fastest sampler the run may take (sampler.h): the closed form of one mode along
  // one line by default (with a trace, the general sampler records it and the metrics stay
  // the closed form's); kDeferredSubsteps: the plant is stepped (the same to rounding).
  // A run takes the fastest that qualifies at or below this one (RunResult::sampler).
  SamplerKind fastest_sampler = SamplerKind::kClosedForm;
  // Attribute the peak, the contour error and the cruise vibration to program lines
  // (RunResult::sources) also when the closed form takes the run and no trace is recorded:
  // the general sampler then steps the plant once more, untraced, for them (`run` does; a
  // sweep's points and Python's run() without trace=True do not: their sources are empty).
  bool attribute_sources = false;
};

// The command RunScenario generates for the scenario's controller and program (the CNC's
// stroke check and the memory budget included): what a sweep generates once and shares.
controller::MultiAxisCommand GenerateScenarioCommand(const Scenario& scenario, const controller::Program& program);

// Throws ValidationError (bad scenario), model::SolverError (CVODE failure).
RunResult RunScenario(const Scenario& scenario, const RunOptions& options = {});

}  // namespace shapebench::bench
