// Running a loaded scenario as every front end does (the CLI's commands, the Python
// module, python/): RunScenario's ValidationErrors, which are about the scenario, located
// in its sources; and the one text of a solver failure.
#pragma once

#include <string>
#include <vector>

#include "bench/config/config_error.h"
#include "bench/config/override.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario.h"
#include "model/integrator.h"

namespace shapebench::bench {

// RunScenario(scenario, options); a ValidationError it throws is rethrown as the
// ConfigError LocateValidationError gives for scenario.source_file with `overrides` (the
// ones it was loaded with). model::SolverError passes through.
RunResult RunScenarioLocated(const Scenario& scenario, const std::vector<Override>& overrides,
                             const RunOptions& options = {});

// "solver failed: FLAG: what": the CLI's exit-3 line after "error: ", a sweep row's error.
std::string SolverFailureText(const model::SolverError& error);

}  // namespace shapebench::bench
