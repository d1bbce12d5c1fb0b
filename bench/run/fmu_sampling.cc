#include <array>
#include <cmath>
#include <memory>

#include "bench/fmi/fmu_plant.h"
#include "bench/run/finish_metrics.h"
#include "bench/run/plant_sampler.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

// The plant sampler's FMU path (docs/fmi.md#importing-a-plant-fmu): the FMU in place of the
// integrator, stepped by the general sampler; the metrics it cannot give are n/a with the
// reason as a warning.
namespace shapebench::bench {
namespace {

// Under the master's servo the native servo plant (the run's machine_) reads the FMU's
// structure states with the master's e, e', z after each axis' (FmuPlant::PlantState): its
// per-axis blocks, when the machine's axes are separate and the counts add up.
bool LayOutServoStates(const model::MultiAxisMachineConfig& config, int servo_plant_states, FmuPlant* fmu) {
  if (config.CoupledModes() != nullptr) return false;
  std::array<int, 3> structure_states{};
  int total = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (config.axes[axis]) structure_states[static_cast<std::size_t>(axis)] = model::BuildPlant(*config.axes[axis]).num_states();
    total += structure_states[static_cast<std::size_t>(axis)] + 3;  // e, e', z per axis
  }
  return total == servo_plant_states && fmu->LayOutServoStates(structure_states);
}

}  // namespace

void PlantSampler::SetUpFmu() {
  // The FMU's stop time: the longest the run may go (the residual window and the tail).
  const double stop_s = static_cast<double>(window_.max_ticks) * dt_;
  auto fmu = std::make_unique<FmuPlant>(*plan_.scenario.fmu, dt_, substeps_, stop_s);
  fmu_ = fmu.get();
  Eigen::Matrix3d gain;
  const bool has_static = fmu->StaticGain(&gain);
  SetStaticReference(plan_, gain, &tally_);
  const FmuMachine& machine = *plan_.scenario.fmu;
  const std::string file = machine.fmu->fmu_path();
  if (!has_static) {
    tally_.static_unknown = true;
    result_.warnings.push_back("static_displacement_m, the ratios and settling_time_s are n/a: the FMU " + file +
                               " maps no static_compliance output (docs/fmi.md)");
  }
  // shapebench's own machine FMU: its states read as the native run reads its plant's.
  if (machine.model_known && nonlinear_ == false && machine_.plant.num_states() > 0 &&
      (machine.master_servo ? LayOutServoStates(plan_.scenario.machine, machine_.plant.num_states(), fmu.get())
                            : static_cast<std::size_t>(machine_.plant.num_states()) == machine.states.size())) {
    residual_vibration_ = std::make_unique<ResidualVibration>(machine_.plant, plan_.view);
  }
  bool residual = residual_vibration_ != nullptr;
  for (const auto& r : machine.residual_amplitude) residual = residual || r.has_value();
  if (!residual) {
    result_.warnings.push_back("residual_amplitude_m and cruise_residual_ratio are n/a: the FMU " + file +
                               " maps no residual_amplitude output (docs/fmi.md); residual_peak_m stands");
  }
  // The in-step peaks of the view's axis from its deflection_peak output; else only the
  // communication points (and substeps) are seen.
  if (plan_.view.axis >= 0 && fmu->Capabilities().period_extremum) {
    exact_extrema_ = fmu->WatchExtremum(model::kDeflectionRow + plan_.view.axis);
  }
  integrator_ = std::move(fmu);
  rows_ = model::kNumOutputRows;
  width_ = rows_;
  outputs_.assign(static_cast<std::size_t>(substeps_) * rows_, 0.0);
}

double PlantSampler::FmuResidual() const { return fmu_->ResidualAmplitude(plan_.view.axis); }

}  // namespace shapebench::bench
