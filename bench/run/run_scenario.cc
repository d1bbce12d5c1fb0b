#include "bench/run/run_scenario.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "bench/run/closed_form_sampler.h"
#include "bench/run/finish_metrics.h"
#include "bench/scenario/run_memory.h"
#include "bench/run/run_plan.h"
#include "bench/run/run_work.h"
#include "bench/run/plant_sampler.h"
#include "bench/run/sampler.h"
#include "bench/run/unit_slips.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {
namespace {

// The fastest sampler for the plan at or below `fastest` (in the order general < single
// axis < deferred substeps < closed form) that qualifies; a trace only the general sampler
// records. *result receives what the sampler reports beside the tally (which sampler,
// residual modes, stats, substeps, warnings, the trace).
std::unique_ptr<Sampler> MakeSampler(const RunPlan& plan, SamplerKind fastest, RunResult* result) {
  // A plant FMU is stepped (plant_sampler.h), even where its own model has a closed form.
  if (fastest == SamplerKind::kClosedForm && plan.single_mode.mode != nullptr && !plan.scenario.fmu) {
    return MakeClosedFormSampler(plan, result);
  }
  return std::make_unique<PlantSampler>(plan, fastest, result);
}

// What looks like a unit slip (unit_slips.h), after the sampler's own warnings.
void AddUnitSlipWarnings(const RunPlan& plan, RunResult* result) {
  for (std::string& warning : UnitSlipWarnings(plan, result->metrics)) result->warnings.push_back(std::move(warning));
}

// The attribution of a tally whose sampler stepped every tick (metric_sources.h): the cause
// looked for within one damped period of the lowest mode plus one tick.
MetricSources Sources(const RunPlan& plan, const controller::MultiAxisCommand& command,
                      const controller::Program& program, const MetricTally& tally) {
  if (!tally.sources.stepped) return {};
  double lookback_s = plan.dt_s;
  double lowest_hz = std::numeric_limits<double>::infinity();
  for (const model::AxisModes& axis : plan.dynamics.axes) {
    for (const model::ModeInfo& mode : axis.analysis.modes) {
      if (!(mode.frequency_hz > 0.0) || mode.frequency_hz >= lowest_hz) continue;
      lowest_hz = mode.frequency_hz;
      const double zeta = std::min(mode.damping_ratio, 0.99);
      lookback_s = plan.dt_s + 1.0 / (mode.frequency_hz * std::sqrt(1.0 - zeta * zeta));
    }
  }
  return AttributeSources(command, program, tally.sources.peak, tally.sources.contour, tally.sources.cruise,
                          !plan.window.cruise_probe_ticks.empty(), lookback_s);
}

}  // namespace

controller::MultiAxisCommand GenerateScenarioCommand(const Scenario& scenario, const controller::Program& program) {
  controller::ControllerConfig controller = scenario.controller;
  controller.stroke_limits = scenario.machine.stroke_m;  // the CNC's stroke check
  // The memory budget again, on the planned length, before the per-tick command exists.
  controller::CommandLimits limits;
  limits.max_ticks = static_cast<std::size_t>(std::min(MemoryTickLimit(scenario.limits), 1e18));
  limits.key = "limits.max_memory_mb";
  return controller::GenerateProgramCommand(controller, program, limits);
}

RunResult RunScenario(const Scenario& scenario, const RunOptions& options) {
  RunResult result;
  // The program, its path and the command: made here, or shared by a sweep's points.
  const bool shared_program = options.command != nullptr && options.program != nullptr && options.path != nullptr;
  if (!shared_program) result.program = scenario.RunProgram();
  const controller::Program& program = shared_program ? *options.program : result.program;
  if (options.command == nullptr) result.command = GenerateScenarioCommand(scenario, program);
  const controller::MultiAxisCommand& command = options.command != nullptr ? *options.command : result.command;
  std::optional<controller::PathGeometry> own_path;
  const controller::PathGeometry& path = shared_program ? *options.path : own_path.emplace(program);
  // The prepared run: samples, view, modes, window, substeps (constant from here on).
  const CommandSamples* shared = options.command != nullptr ? options.samples : nullptr;
  const RunPlan plan(scenario, command, path, shared, options.record_trace);
  CheckEstimatedWork(plan, 0);  // its samples alone; the exact path adds its extremum grid
  // The sampler, its ticks, the metrics.
  if (!(options.record_trace || options.attribute_sources) || options.fastest_sampler != SamplerKind::kClosedForm ||
      plan.single_mode.mode == nullptr || scenario.fmu) {
    const MetricTally tally = MakeSampler(plan, options.fastest_sampler, &result)->Run();
    result.simulated_s = static_cast<double>(tally.last_tick) * plan.dt_s;
    result.metrics = FinishMetrics(plan, tally);
    result.sources = Sources(plan, command, program, tally);
    AddUnitSlipWarnings(plan, &result);
    return result;
  }
  // A trace (or the attribution) of a closed-form run: the general sampler records it,
  // the metrics stay the closed form's (one answer whatever a run records: run, run --json, a sweep's point,
  // the Python API).
  RunResult closed;
  const Metrics metrics = FinishMetrics(plan, MakeClosedFormSampler(plan, &closed)->Run());
  const MetricTally traced = MakeSampler(plan, SamplerKind::kGeneral, &result)->Run();
  FinishMetrics(plan, traced);  // refuses an overflow as an untraced run would
  result.simulated_s = static_cast<double>(traced.last_tick) * plan.dt_s;
  result.metrics = metrics;
  result.sources = Sources(plan, command, program, traced);
  result.residual_modes = std::move(closed.residual_modes);
  result.sampler = SamplerKind::kClosedForm;
  result.single_mode = true;
  AddUnitSlipWarnings(plan, &result);
  return result;
}

}  // namespace shapebench::bench
