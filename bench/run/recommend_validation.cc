// The validation runs of `recommend --validate` (see the header).
#include "bench/run/recommend_validation.h"

#include "bench/config/config_error.h"
#include "bench/scenario/scenario_loader.h"
#include "common/format.h"
#include "common/validation_error.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

ValidationRuns RunValidation(const std::string& scenario_path, const std::vector<LogMode>& modes,
                             const controller::PatternConfig& pattern) {
  Scenario scenario = LoadScenario(scenario_path, {});
  ValidationRuns runs;
  runs.scenario = scenario_path;
  runs.axis = scenario.machine.driven_axis;
  for (const model::AxisModes& axis : model::AnalyzeMachineModes(scenario.machine)) {
    if (axis.axis == runs.axis) runs.static_deflection_per_accel_s2 = axis.analysis.static_deflection_per_accel_s2;
  }
  const std::string axis_name = model::AxisName(runs.axis);
  if (!(runs.static_deflection_per_accel_s2 > 0.0)) {
    throw ConfigError(scenario_path, 0, 0, "machine",
                      "the driven axis " + axis_name +
                          " has no static deflection to keep (rigid): --validate needs a scenario whose "
                          "machine deflects along its driven axis");
  }
  runs.machine = ModesMachine(modes, runs.static_deflection_per_accel_s2);
  scenario.machine.axes[runs.axis] = model::MachineConfig{runs.machine};
  auto run = [&](const controller::PatternConfig& shaping) {
    Scenario s = scenario;
    const controller::PatternConfig& old = scenario.controller.pattern;
    s.controller.pattern = shaping;
    s.controller.pattern.mode = old.mode;
    s.controller.pattern.realization = old.realization;
    s.controller.pattern.step_resolution_s = old.step_resolution_s;
    // Errors name scenario keys (machine.*, controller.*, as RunScenario's do) and what
    // --validate put in.
    auto located = [&](const ValidationError& error) {
      return ConfigError(scenario_path, 0, 0, error.field(),
                         error.message() + " (--validate: the " + axis_name +
                             " axis modelled by the log's modes, controller.pattern.method " + shaping.method +
                             " at " + FormatNumber(shaping.frequency_hz) + " Hz)");
    };
    try {
      s.machine.validate();
    } catch (const ValidationError& error) {
      throw located(error.Prefixed("machine"));
    }
    try {
      s.controller.validate();
    } catch (const ValidationError& error) {
      throw located(error.Prefixed("controller"));
    }
    try {
      RunOptions options;
      options.record_trace = false;
      return RunScenario(s, options).metrics;
    } catch (const ValidationError& error) {
      throw located(error);
    }
  };
  controller::PatternConfig none;
  none.method = controller::kNoShaping;
  runs.none = run(none);
  runs.recommended = run(pattern);
  return runs;
}

}  // namespace shapebench::bench
