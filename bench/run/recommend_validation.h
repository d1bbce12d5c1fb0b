// `recommend --validate SCENARIO`: the modes an accelerometer log shows
// (bench/measured/psd_peaks.h), put in place of a scenario's machine, run with the
// recommended pattern and without.
#pragma once

#include <string>
#include <vector>

#include "bench/measured/psd_peaks.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/metrics.h"
#include "controller/pattern_config.h"
#include "model/machine.h"

namespace shapebench::bench {

struct ValidationRuns {
  std::string scenario;  // the file, as given
  int axis = 1;          // the driven axis whose model was replaced
  double static_deflection_per_accel_s2 = 0.0;
  model::ModalMachineConfig machine;  // what replaced it
  Metrics none;         // the run without shaping
  Metrics recommended;  // the run with `pattern`
};

// Loads `scenario_path`, replaces its driven axis' model by `modes` (ModesMachine with
// that axis' static deflection) and runs it twice: pattern.method none, then `pattern`
// (the recommendation; its mode and realization as the scenario sets them). Throws
// ConfigError (the scenario; a driven axis without deflection; a run the recommended
// pattern does not fit, naming the key) and model::SolverError.
ValidationRuns RunValidation(const std::string& scenario_path, const std::vector<LogMode>& modes,
                             const controller::PatternConfig& pattern);

}  // namespace shapebench::bench
