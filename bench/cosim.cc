#include "bench/cosim.h"

#include <algorithm>
#include <cmath>

#include "controller/controller.h"
#include "model/machine.h"

namespace shapebench::bench {
namespace {

// After the motion the run goes on for three periods of the lowest mode (the residual
// window), then further, a lowest-mode period at a time, until a whole period stays
// below the settling band; at most this many periods (an undamped plant never settles).
constexpr int kMaxTailPeriods = 30;
constexpr double kSettlingBand = 0.05;

}  // namespace

int AutoSubsteps(const model::MachineConfig& machine, double period_s) {
  const model::ModalAnalysis analysis = model::AnalyzeModes(machine);
  double fastest_hz = 0.0;
  for (const model::ModeInfo& mode : analysis.modes) {
    if (std::abs(mode.participation) >= 0.01) fastest_hz = std::max(fastest_hz, mode.frequency_hz);
  }
  // 200 samples per period bound the sampling error of a peak by 1 - cos(pi/200) = 1.2e-4.
  const int substeps = static_cast<int>(std::ceil(period_s * fastest_hz * 200.0));
  return std::clamp(substeps, 1, 64);
}

RunResult RunScenario(const Scenario& scenario) {
  RunResult result;
  result.command = controller::GenerateCommand(scenario.controller, scenario.move);
  const controller::CommandTrajectory& command = result.command;
  const double dt = command.period_s;

  const model::LinearPlant plant = model::BuildPlant(scenario.machine);
  const model::ModalAnalysis analysis = model::AnalyzeModes(scenario.machine);
  const double lowest_period_s = 1.0 / analysis.modes.front().frequency_hz;
  const int substeps = scenario.integrator.output_substeps > 0
                           ? scenario.integrator.output_substeps
                           : AutoSubsteps(scenario.machine, dt);
  result.substeps = substeps;

  const double max_accel = command.MaxAbsAccel();
  Metrics& m = result.metrics;
  m.static_displacement_m = max_accel * analysis.static_deflection_per_accel_s2;

  // Motion ends at the last tick where the commanded velocity becomes (and stays) zero.
  std::size_t last_moving = 0;
  for (std::size_t k = 0; k < command.velocity_m_s.size(); ++k) {
    if (command.velocity_m_s[k] != 0.0) last_moving = k;
  }
  const std::size_t motion_ticks = std::min(last_moving + 1, command.num_ticks());
  m.motion_time_s = static_cast<double>(motion_ticks) * dt;
  const auto residual_ticks = static_cast<std::size_t>(std::ceil(3.0 * lowest_period_s / dt));
  const auto period_ticks = static_cast<std::size_t>(std::ceil(lowest_period_s / dt));
  const std::size_t max_ticks = motion_ticks + kMaxTailPeriods * period_ticks;

  auto integrator = model::MakeIntegrator(plant, scenario.integrator, dt, substeps,
                                          std::max(max_accel, 1e-12));
  Eigen::VectorXd input = Eigen::VectorXd::Zero(plant.num_inputs());
  integrator->Reset(input);

  const std::vector<double> positions = command.Positions();
  Trace& trace = result.trace;
  auto record = [&](double t, double p, double v, double a, double deflection) {
    trace.time_s.push_back(t);
    trace.command_position_m.push_back(p);
    trace.command_velocity_m_s.push_back(v);
    trace.command_accel_m_s2.push_back(a);
    trace.deflection_m.push_back(deflection);
  };
  record(0.0, 0.0, 0.0, 0.0, 0.0);

  const double band = kSettlingBand * m.static_displacement_m;
  double peak = 0.0;
  double residual = 0.0;
  double cruise = NAN;
  double last_outside_band_s = NAN;  // last sample after the motion outside the band
  std::size_t quiet_since_tick = motion_ticks;
  bool settled = false;
  for (std::size_t k = 1; k <= max_ticks; ++k) {
    // FMI order: set the input held over (t_{k-1}, t_k], step, read the outputs.
    const bool commanded = k <= command.num_ticks();
    const double a = commanded ? command.accel_m_s2(k) : 0.0;
    const double v0 = commanded ? command.velocity_m_s[k - 1] : 0.0;
    const double p0 = commanded ? positions[k - 1] : positions.back();
    input(0) = a;
    integrator->SetInput(input);
    // Cruise: the commanded feed constant and non-zero over the whole period.
    const bool cruising = commanded && command.velocity_m_s[k] != 0.0 &&
                          std::abs(a) <= 1e-9 * max_accel;
    for (int j = 1; j <= substeps; ++j) {
      integrator->Step();
      const double tau = dt * static_cast<double>(j) / substeps;
      const double t = integrator->Time();
      const double deflection = integrator->Output()(0);
      const double magnitude = std::abs(deflection);
      record(t, p0 + v0 * tau + 0.5 * a * tau * tau, v0 + a * tau, a, deflection);
      peak = std::max(peak, magnitude);
      if (cruising) cruise = std::isnan(cruise) ? magnitude : std::max(cruise, magnitude);
      if (k > motion_ticks || (k == motion_ticks && j == substeps)) {
        if (k <= motion_ticks + residual_ticks) residual = std::max(residual, magnitude);
        if (magnitude >= band) {
          last_outside_band_s = t;
          quiet_since_tick = k;
        }
      }
    }
    if (k >= motion_ticks + residual_ticks && k >= quiet_since_tick + period_ticks) {
      settled = true;
      break;
    }
  }
  m.peak_deflection_m = peak;
  m.peak_ratio = peak / m.static_displacement_m;
  m.residual_amplitude_m = residual;
  m.residual_ratio = residual / m.static_displacement_m;
  m.cruise_residual_ratio = cruise / m.static_displacement_m;
  if (settled) {
    m.settling_time_s = std::isnan(last_outside_band_s)
                            ? 0.0
                            : last_outside_band_s + dt / substeps - m.motion_time_s;
  }
  result.stats = integrator->Stats();
  return result;
}

}  // namespace shapebench::bench
