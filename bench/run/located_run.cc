#include "bench/run/located_run.h"

#include "bench/scenario/scenario_loader.h"
#include "common/validation_error.h"

namespace shapebench::bench {

RunResult RunScenarioLocated(const Scenario& scenario, const std::vector<Override>& overrides,
                             const RunOptions& options) {
  try {
    return RunScenario(scenario, options);
  } catch (const ValidationError& error) {
    throw LocateValidationError(scenario.source_file, overrides, error);
  }
}

std::string SolverFailureText(const model::SolverError& error) {
  return "solver failed: " + error.flag_name() + ": " + error.what();
}

}  // namespace shapebench::bench
