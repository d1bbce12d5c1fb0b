// The controller part: the scenario's command, one interpolation period a step, the values
// at each period's end computed as run's trace.csv computes its period-boundary rows
// (bench/run/general_sampler.cc), so that the two agree bit for bit.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/fmu/slave.h"
#include "bench/run/command_samples.h"
#include "bench/run/run_scenario.h"
#include "common/format.h"

namespace shapebench::bench::fmu {
namespace {

class ControllerSlave final : public Slave {
 public:
  ControllerSlave(const Scenario& scenario, const Layout& layout)
      : layout_(layout),
        command_(GenerateScenarioCommand(scenario, scenario.RunProgram())),
        samples_(SampleCommand(command_)),
        dt_(command_.period_s) {}

  void WriteInitialOutputs(std::vector<double>* values) override {
    Publish(samples_.positions.front(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), values);
  }

  void DoStep(double t, double h, std::vector<double>* values) override {
    if (std::abs(h - dt_) > 1e-9 * dt_) {
      throw std::runtime_error("the controller steps one interpolation period at a time: the communication step must be " +
                               FormatNumber(dt_, 12) + " s (got " + FormatNumber(h, 12) + " s)");
    }
    const double ticks = (t + h) / dt_;
    const long k = std::lround(ticks);
    if (k < 1 || std::abs(ticks - static_cast<double>(k)) > 1e-6) {
      throw std::runtime_error("the step must end on an interpolation period (t = k * " + FormatNumber(dt_, 12) +
                               " s, k >= 1; got t = " + FormatNumber(t + h, 12) + " s)");
    }
    const auto tick = static_cast<std::size_t>(k);
    const bool commanded = tick <= samples_.n;
    const Eigen::Vector3d& a = samples_.AccelAt(tick);
    const Eigen::Vector3d& v0 = commanded ? samples_.velocity[tick - 1] : samples_.accel[0];
    const Eigen::Vector3d& p0 = commanded ? samples_.positions[tick - 1] : samples_.positions.back();
    const double tau = dt_;
    const Eigen::Vector3d p = p0 + v0 * tau + 0.5 * a * tau * tau;
    const Eigen::Vector3d v = v0 + a * tau;
    Publish(p, v, a, values);
  }

 private:
  void Publish(const Eigen::Vector3d& p, const Eigen::Vector3d& v, const Eigen::Vector3d& a,
               std::vector<double>* values) const {
    for (int axis = 0; axis < 3; ++axis) {
      (*values)[static_cast<std::size_t>(layout_.position[axis])] = p(axis);
      (*values)[static_cast<std::size_t>(layout_.velocity[axis])] = v(axis);
      (*values)[static_cast<std::size_t>(layout_.accel[axis])] = a(axis);
    }
  }

  const Layout layout_;
  const controller::MultiAxisCommand command_;
  const CommandSamples samples_;
  const double dt_;
};

}  // namespace

std::unique_ptr<Slave> MakeControllerSlave(const Scenario& scenario, const Layout& layout) {
  return std::make_unique<ControllerSlave>(scenario, layout);
}

}  // namespace shapebench::bench::fmu
