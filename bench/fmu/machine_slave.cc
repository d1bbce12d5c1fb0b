// The machine part: base accelerations in, deflection and tool error out (docs/fmi.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/fmu/exact_stepper.h"
#include "bench/fmu/slave.h"
#include "bench/run/command_samples.h"
#include "bench/run/run_scenario.h"
#include "bench/run/run_window.h"
#include "common/format.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench::fmu {
namespace {

class MachineSlave final : public Slave {
 public:
  MachineSlave(const Scenario& scenario, const Layout& layout)
      : layout_(layout),
        machine_(model::BuildMachinePlant(scenario.machine, scenario.drive)),
        config_(scenario.integrator),
        accel_(static_cast<std::size_t>(std::max(machine_.plant.num_inputs(), 3)), 0.0),
        outputs_(static_cast<std::size_t>(std::max(machine_.plant.num_outputs(), model::kNumOutputRows)), 0.0),
        peaks_(outputs_.size(), 0.0) {
    if (machine_.nonlinear.empty()) {
      const double period_s = scenario.controller.period_s;
      const int substeps = scenario.integrator.output_substeps > 0
                               ? scenario.integrator.output_substeps
                               : AutoSubsteps(model::AnalyzeMachine(scenario.machine), period_s);
      exact_ = std::make_unique<ExactStepper>(machine_.plant, period_s, substeps);
      return;
    }
    // CVODE's tolerances scale with the run's largest acceleration and speed: the scenario's.
    const controller::MultiAxisCommand command = GenerateScenarioCommand(scenario, scenario.RunProgram());
    const CommandSamples samples = SampleCommand(command);
    scale_accel_ = std::max(samples.max_accel_m_s2, 1e-12);
    scale_speed_ = samples.max_speed_m_s;
    if (config_.method == model::IntegratorMethod::kAuto) config_.method = model::IntegratorMethod::kCvode;
  }

  void WriteInitialOutputs(std::vector<double>* values) override {
    for (int axis = 0; axis < 3; ++axis) {
      Set(values, layout_.static_compliance[axis], machine_.static_gain(axis, axis));
    }
    Publish(values);
  }

  void DoStep(double /*t*/, double h, std::vector<double>* values) override {
    for (int axis = 0; axis < 3; ++axis) {
      const int vr = layout_.input[axis];
      accel_[static_cast<std::size_t>(axis)] = vr == kNoVariable ? 0.0 : (*values)[static_cast<std::size_t>(vr)];
    }
    for (std::size_t axis = 0; axis < 3; ++axis) {
      // The held acceleration integrated exactly (position first: it reads the old velocity).
      drive_position_[axis] += drive_velocity_[axis] * h + 0.5 * accel_[axis] * h * h;
      drive_velocity_[axis] += accel_[axis] * h;
    }
    if (exact_) {
      exact_->Step(accel_.data(), h);
      for (int row = 0; row < exact_->num_outputs(); ++row) {
        outputs_[static_cast<std::size_t>(row)] = exact_->Output(row);
        peaks_[static_cast<std::size_t>(row)] = exact_->Peak(row);
      }
    } else if (machine_.plant.num_states() > 0) {
      StepCvode(h);
    }
    Publish(values);
  }

 private:
  // CVODE with its events (model/nonlinear_integrator.h), one substep a step: the step size
  // is the one of the first step (its integrator is built for one period).
  void StepCvode(double h) {
    if (!cvode_) {
      cvode_h_ = h;
      cvode_ = model::MakePlantIntegrator({machine_.plant, machine_.nonlinear, machine_.following_error_axis},
                                          config_, h, 1, scale_accel_, scale_speed_);
      cvode_->Reset(Eigen::VectorXd::Zero(machine_.plant.num_inputs()));
    } else if (std::abs(h - cvode_h_) > 1e-9 * cvode_h_) {
      throw std::runtime_error("this machine is nonlinear (CVODE): the communication step must stay " +
                               FormatNumber(cvode_h_, 12) + " s, the first step's (got " + FormatNumber(h, 12) + " s)");
    }
    std::vector<double> before(outputs_);
    cvode_->AdvancePeriod(accel_.data(), 1, outputs_.data());
    for (std::size_t row = 0; row < outputs_.size(); ++row) {
      peaks_[row] = std::max(std::abs(before[row]), std::abs(outputs_[row]));
    }
  }

  static void Set(std::vector<double>* values, int vr, double value) {
    if (vr != kNoVariable) (*values)[static_cast<std::size_t>(vr)] = value;
  }

  void Publish(std::vector<double>* values) const {
    for (int axis = 0; axis < 3; ++axis) {
      Set(values, layout_.deflection[axis], outputs_[static_cast<std::size_t>(model::kDeflectionRow + axis)]);
      Set(values, layout_.tool_error[axis], outputs_[static_cast<std::size_t>(model::kToolErrorRow + axis)]);
      Set(values, layout_.deflection_peak[axis], peaks_[static_cast<std::size_t>(model::kDeflectionRow + axis)]);
      Set(values, layout_.tool_error_peak[axis], peaks_[static_cast<std::size_t>(model::kToolErrorRow + axis)]);
      double statik = 0.0;
      for (int b = 0; b < 3; ++b) statik += machine_.static_gain(axis, b) * accel_[static_cast<std::size_t>(b)];
      Set(values, layout_.static_deflection[axis], statik);
      Set(values, layout_.drive_position[axis], drive_position_[static_cast<std::size_t>(axis)]);
      Set(values, layout_.drive_velocity[axis], drive_velocity_[static_cast<std::size_t>(axis)]);
    }
    if (layout_.num_states == 0) return;
    const Eigen::VectorXd x = exact_ ? exact_->State()
                              : cvode_ ? cvode_->PlantState() : Eigen::VectorXd::Zero(layout_.num_states);
    for (int i = 0; i < layout_.num_states && i < x.size(); ++i) Set(values, layout_.first_state + i, x(i));
  }

  const Layout layout_;
  const model::MachinePlant machine_;
  model::IntegratorConfig config_;
  std::vector<double> accel_;
  std::vector<double> outputs_;
  std::vector<double> peaks_;
  std::array<double, 3> drive_position_{}, drive_velocity_{};  // from rest at t = 0
  std::unique_ptr<ExactStepper> exact_;
  std::unique_ptr<model::PlantIntegrator> cvode_;
  double cvode_h_ = 0.0;
  double scale_accel_ = 1.0;
  double scale_speed_ = 0.0;
};

}  // namespace

std::unique_ptr<Slave> MakeMachineSlave(const Scenario& scenario, const Layout& layout) {
  return std::make_unique<MachineSlave>(scenario, layout);
}

}  // namespace shapebench::bench::fmu
