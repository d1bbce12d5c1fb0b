#include "bench/run/run_plan.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "bench/run/single_axis.h"
#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

// The mode of the run's one modelled axis, or null.
const model::ModalMode* OnlyMode(const model::MultiAxisMachineConfig& machine, int axis) {
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (a != axis && machine.axes[a].has_value()) return nullptr;
  }
  if (!machine.axes[axis].has_value()) return nullptr;
  const auto* modal = std::get_if<model::ModalMachineConfig>(&machine.axes[axis]->form);
  if (modal == nullptr || modal->modes.size() != 1 || modal->coupled()) return nullptr;
  return &modal->modes.front();
}

// The closed form's case (closed_form_sampler.cc): the kinematic drive, no stroke limit, one
// straight element along the view's axis with the others still at its start, one mode of
// that axis (gain not 0, under-damped), at most one stationary point a period
// (model/tick_extremum.h's grid of one) in the command's period.
SingleModeCase FindSingleModeCase(const Scenario& scenario, const controller::PathGeometry& path,
                                  const CommandSamples& samples, const OutputView& view, double dt_s,
                                  bool has_stroke) {
  const SingleModeCase none;
  if (scenario.drive.type != model::DriveType::kKinematic ||
      scenario.integrator.method == model::IntegratorMethod::kCvode) {
    return none;
  }
  const controller::PathElement* only = path.elements().size() == 1 ? &path.elements().front() : nullptr;
  const int axis = FindSingleAxis(only, samples, view, has_stroke).axis;
  if (axis < 0) return none;
  const model::ModalMode* mode = OnlyMode(scenario.machine, axis);
  if (mode == nullptr || !(mode->gain != 0.0) || !(mode->damping_ratio < 1.0) || !(mode->frequency_hz > 0.0)) {
    return none;
  }
  const double wd = 2.0 * kPi * mode->frequency_hz * std::sqrt(1.0 - mode->damping_ratio * mode->damping_ratio);
  if (!(wd * dt_s <= 0.5 * kPi)) return none;
  return {mode, only, axis};
}

std::vector<double> SubstepTimes(double dt_s, int substeps) {
  std::vector<double> taus(static_cast<std::size_t>(substeps));
  for (int j = 1; j <= substeps; ++j) taus[j - 1] = dt_s * static_cast<double>(j) / substeps;
  return taus;
}

// The machine and drive checked once, before the analysis that needs them valid.
model::MachineDynamics ValidatedDynamics(const Scenario& scenario) {
  scenario.machine.validate();
  scenario.drive.validate();
  return model::AnalyzeMachine(scenario.machine);
}

int OutputSubsteps(const Scenario& scenario, const model::MachineDynamics& dynamics, double dt_s) {
  return scenario.integrator.output_substeps > 0 ? scenario.integrator.output_substeps
                                                 : AutoSubsteps(dynamics, dt_s);
}

}  // namespace

std::string_view SamplerName(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::kGeneral: return "general";
    case SamplerKind::kSingleAxis: return "single-axis";
    case SamplerKind::kDeferredSubsteps: return "deferred substeps";
    case SamplerKind::kClosedForm: return "closed form";
  }
  return "?";
}

RunPlan::RunPlan(const Scenario& scenario_in, const controller::MultiAxisCommand& command_in,
                 const controller::PathGeometry& path_in, const CommandSamples* shared_samples,
                 bool record_trace_in)
    : scenario(scenario_in),
      command(command_in),
      path(path_in),
      own_samples_(shared_samples != nullptr ? CommandSamples{} : SampleCommand(command_in)),
      samples(shared_samples != nullptr ? *shared_samples : own_samples_),
      dt_s(command_in.period_s),
      dynamics(ValidatedDynamics(scenario_in)),
      view(MakeOutputView(scenario_in.output, samples.axis_moves)),
      window(PlanRunWindow(scenario_in, samples, dynamics, dt_s)),
      substeps(OutputSubsteps(scenario_in, dynamics, dt_s)),
      taus_s(SubstepTimes(dt_s, substeps)),
      has_stroke(std::any_of(scenario_in.machine.stroke_m.begin(), scenario_in.machine.stroke_m.end(),
                             [](const auto& limits) { return limits.has_value(); })),
      record_trace(record_trace_in),
      single_mode(FindSingleModeCase(scenario_in, path_in, samples, view, dt_s, has_stroke)) {}

}  // namespace shapebench::bench
