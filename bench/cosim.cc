#include "bench/cosim.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/validation_error.h"
#include "controller/path_geometry.h"
#include "controller/stroke_end.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

// After the motion the run goes on for three periods of the lowest mode (the residual
// window), then further, a lowest-mode period at a time, until a whole period stays
// below the settling band; at most this many periods (an undamped plant never settles).
constexpr int kMaxTailPeriods = 30;
constexpr double kSettlingBand = 0.05;
// A machine without modes (rigid axes) has no natural period: its tail is this long.
constexpr double kRigidTailPeriodS = 0.1;

// The scalar the deflection metrics use (OutputDirection).
struct View {
  bool magnitude = true;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  double Of(const Eigen::Vector3d& v) const { return magnitude ? v.norm() : v.dot(direction); }
};

View MakeView(const OutputConfig& output, const controller::MultiAxisCommand& command) {
  View view;
  int axis = -1;
  switch (output.direction) {
    case OutputDirection::kX: axis = 0; break;
    case OutputDirection::kY: axis = 1; break;
    case OutputDirection::kZ: axis = 2; break;
    case OutputDirection::kMagnitude: break;
    case OutputDirection::kAuto: {
      int moving = 0;
      for (int a = 0; a < controller::kNumAxes; ++a) {
        const auto& v = command.axes[a].velocity_m_s;
        if (std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; })) {
          ++moving;
          axis = a;
        }
      }
      if (moving != 1) axis = -1;
      break;
    }
  }
  if (axis >= 0) {
    view.magnitude = false;
    view.direction(axis) = 1.0;
  }
  return view;
}

// Mean radius over the middle half of one arc (radial_error_m).
struct ArcWindow {
  const controller::PathElement* arc = nullptr;
  double sum_radius_m = 0.0;
  long samples = 0;
};

}  // namespace

int AutoSubsteps(const model::MultiAxisMachineConfig& machine, double period_s) {
  double fastest_hz = 0.0;
  for (const model::AxisModes& axis : model::AnalyzeMachineModes(machine)) {
    for (const model::ModeInfo& mode : axis.analysis.modes) {
      if (std::abs(mode.participation) >= 0.01) fastest_hz = std::max(fastest_hz, mode.frequency_hz);
    }
  }
  // 200 samples per period bound the sampling error of a peak by 1 - cos(pi/200) = 1.2e-4.
  const int substeps = static_cast<int>(std::ceil(period_s * fastest_hz * 200.0));
  return std::clamp(substeps, 1, 64);
}

RunResult RunScenario(const Scenario& scenario) {
  RunResult result;
  result.program = scenario.RunProgram();
  controller::ControllerConfig controller = scenario.controller;
  controller.stroke_limits = scenario.machine.stroke_m;  // the CNC's stroke check
  result.command = controller::GenerateProgramCommand(controller, result.program);
  const controller::MultiAxisCommand& command = result.command;
  const double dt = command.period_s;
  const controller::PathGeometry path(result.program);

  const model::MachinePlant machine = model::BuildMachinePlant(scenario.machine, scenario.drive);
  const model::LinearPlant& plant = machine.plant;
  double lowest_hz = std::numeric_limits<double>::infinity();
  for (const model::AxisModes& axis : model::AnalyzeMachineModes(scenario.machine)) {
    for (const model::ModeInfo& mode : axis.analysis.modes) lowest_hz = std::min(lowest_hz, mode.frequency_hz);
  }
  const double lowest_period_s = std::isfinite(lowest_hz) ? 1.0 / lowest_hz : kRigidTailPeriodS;
  const int substeps = scenario.integrator.output_substeps > 0
                           ? scenario.integrator.output_substeps
                           : AutoSubsteps(scenario.machine, dt);
  result.substeps = substeps;
  const View view = MakeView(scenario.output, command);

  // Static displacement: the largest deflection a held commanded acceleration gives.
  const std::size_t n = command.num_ticks();
  double max_accel = 0.0;
  double max_speed = 0.0;
  double static_m = 0.0;
  for (std::size_t k = 1; k <= n; ++k) {
    const Eigen::Vector3d a = command.accel_m_s2(k);
    max_accel = std::max(max_accel, a.norm());
    max_speed = std::max(max_speed, command.velocity_m_s(k).norm());
    static_m = std::max(static_m, std::abs(view.Of(machine.static_gain * a)));
  }
  Metrics& m = result.metrics;
  m.static_displacement_m = static_m;

  // Motion ends at the last tick where a commanded velocity becomes (and stays) zero.
  std::size_t last_moving = 0;
  for (std::size_t k = 0; k <= n; ++k) {
    if (command.velocity_m_s(k) != Eigen::Vector3d::Zero()) last_moving = k;
  }
  const std::size_t motion_ticks = std::min(last_moving + 1, n);
  m.motion_time_s = static_cast<double>(motion_ticks) * dt;
  const auto residual_ticks = static_cast<std::size_t>(std::ceil(3.0 * lowest_period_s / dt));
  const auto period_ticks = static_cast<std::size_t>(std::ceil(lowest_period_s / dt));
  // Guard rail (issue 7): the generated command and its residual window within limits:.
  const double limit_ticks = std::min(scenario.limits.max_simulated_s / dt,
                                      static_cast<double>(scenario.limits.max_ticks));
  if (static_cast<double>(motion_ticks + residual_ticks) > limit_ticks) {
    throw ValidationError("limits.max_simulated_s",
                          "the command and its residual window take " +
                              std::to_string(motion_ticks + residual_ticks) +
                              " periods, more than limits allow (max_simulated_s, max_ticks)");
  }
  const std::size_t max_ticks = static_cast<std::size_t>(
      std::min(static_cast<double>(motion_ticks + kMaxTailPeriods * period_ticks), limit_ticks));

  std::unique_ptr<model::PlantIntegrator> integrator;
  if (plant.num_states() > 0) {
    integrator = model::MakeIntegrator(plant, scenario.integrator, dt, substeps,
                                       std::max(max_accel, 1e-12), max_speed);
    integrator->Reset(Eigen::VectorXd::Zero(plant.num_inputs()));
  }
  Eigen::VectorXd outputs = Eigen::VectorXd::Zero(6);

  const std::vector<Eigen::Vector3d> positions = command.Positions();
  std::vector<ArcWindow> arcs;
  for (const controller::PathElement& e : path.elements()) {
    if (e.is_arc()) arcs.push_back({&e, 0.0, 0});
  }

  Trace& trace = result.trace;
  double travelled_m = 0.0;  // the command's distance along its own path (magnitude view)
  auto record = [&](double t, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                    const Eigen::Vector3d& a, const Eigen::Vector3d& deflection,
                    const Eigen::Vector3d& actual, int block) {
    trace.time_s.push_back(t);
    trace.command_position_m.push_back(view.magnitude ? travelled_m : view.Of(p));
    trace.command_velocity_m_s.push_back(view.Of(v));
    trace.command_accel_m_s2.push_back(view.Of(a));
    trace.deflection_m.push_back(view.Of(deflection));
    trace.command_m.push_back(p);
    trace.actual_m.push_back(actual);
    trace.deflection_axes_m.push_back(deflection);
    trace.block.push_back(block);
    trace.planned_feed_mm_min.push_back(
        block >= 0 ? command.block_feed_m_s[static_cast<std::size_t>(block)] * 60000.0 : 0.0);
  };
  const int first_block = command.block.empty() ? -1 : command.block.front();
  record(0.0, positions.front(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
         Eigen::Vector3d::Zero(), positions.front(), first_block);

  const double band = kSettlingBand * m.static_displacement_m;
  double peak = 0.0;
  Eigen::Vector3d peak_axes = Eigen::Vector3d::Zero();
  double residual = 0.0;
  double cruise = NAN;
  double contour = 0.0;
  double overshoot = 0.0;
  double last_outside_band_s = NAN;  // last sample after the motion outside the band
  std::size_t quiet_since_tick = motion_ticks;
  bool settled = false;
  // Cruise: the commanded feed constant and non-zero, for at least one period of the
  // lowest mode in a row. Shorter constant stretches are steps of a pattern (method 2's
  // zero step, T/6), not the cruise whose vibration the metric reports.
  std::vector<bool> cruise_tick(n + 1, false);
  for (std::size_t k = 1, run_start = 1; k <= n + 1; ++k) {
    const bool steady = k <= n && command.velocity_m_s(k) != Eigen::Vector3d::Zero() &&
                        command.accel_m_s2(k).norm() <= 1e-9 * max_accel;
    if (steady) continue;
    if (k - run_start >= period_ticks) std::fill(cruise_tick.begin() + run_start, cruise_tick.begin() + k, true);
    run_start = k + 1;
  }
  const std::size_t interpolated_ticks = command.path_position_m.size();
  for (std::size_t k = 1; k <= max_ticks; ++k) {
    // FMI order: set the input held over (t_{k-1}, t_k], step, read the outputs.
    const bool commanded = k <= n;
    const Eigen::Vector3d a = commanded ? command.accel_m_s2(k) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d v0 = commanded ? command.velocity_m_s(k - 1) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d p0 = commanded ? positions[k - 1] : positions.back();
    const bool interpolating = k < interpolated_ticks;
    const int block = interpolating ? command.block[k] : -1;
    const double path_s = command.path_position_m.empty()
                              ? 0.0
                              : command.path_position_m[std::min(k, interpolated_ticks - 1)];
    if (integrator) integrator->SetInput(a);
    const bool cruising = commanded && cruise_tick[k];
    for (int j = 1; j <= substeps; ++j) {
      double t = dt * static_cast<double>((k - 1) * substeps + j) / substeps;
      if (integrator) {
        integrator->Step();
        t = integrator->Time();
        outputs = integrator->Output();
        if (!outputs.allFinite()) {  // a degenerate model: never reported as numbers
          throw model::SolverError("NON_FINITE_STATE", "the plant's deflection became non-finite at t = " +
                                                           std::to_string(t) + " s (a degenerate model)");
        }
      }
      const double tau = dt * static_cast<double>(j) / substeps;
      const Eigen::Vector3d p = p0 + v0 * tau + 0.5 * a * tau * tau;
      const Eigen::Vector3d v = v0 + a * tau;
      const Eigen::Vector3d deflection = outputs.segment<3>(model::kDeflectionRow);
      const Eigen::Vector3d actual = p + outputs.segment<3>(model::kToolErrorRow);
      travelled_m += v.norm() * dt / substeps;
      record(t, p, v, a, deflection, actual, block);
      const double magnitude = std::abs(view.Of(deflection));
      peak = std::max(peak, magnitude);
      peak_axes = peak_axes.cwiseMax(deflection.cwiseAbs());
      contour = std::max(contour, path.DistanceTo(actual));
      overshoot = std::max(overshoot, controller::StrokeOvershoot(p, scenario.machine.stroke_m));
      for (ArcWindow& w : arcs) {
        const double from_start = path_s - w.arc->start_s_m;
        if (from_start >= 0.25 * w.arc->length_m && from_start <= 0.75 * w.arc->length_m) {
          w.sum_radius_m += std::hypot(actual(w.arc->axis0) - w.arc->center_m(w.arc->axis0),
                                       actual(w.arc->axis1) - w.arc->center_m(w.arc->axis1));
          ++w.samples;
        }
      }
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
  m.max_contour_error_m = contour;
  for (const ArcWindow& w : arcs) {
    if (w.samples == 0) continue;
    const double programmed = 0.5 * (w.arc->start_radius_m + w.arc->end_radius_m);
    const double error = programmed - w.sum_radius_m / static_cast<double>(w.samples);
    if (std::isnan(m.radial_error_m) || std::abs(error) > std::abs(m.radial_error_m)) m.radial_error_m = error;
  }
  m.peak_deflection_x_m = peak_axes(0);
  m.peak_deflection_y_m = peak_axes(1);
  m.peak_deflection_z_m = peak_axes(2);
  m.short_block_clamps = command.short_block_clamps;
  m.stroke_overshoot_m = overshoot;
  m.stroke_alarm = command.stroke_alarm ? 1.0 : 0.0;
  if (integrator) result.stats = integrator->Stats();
  return result;
}

}  // namespace shapebench::bench
