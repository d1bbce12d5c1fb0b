#include "bench/sim/cosim.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "common/validation_error.h"
#include "controller/path_geometry.h"
#include "controller/stroke_end.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

// After the motion the run goes on for three periods of the lowest mode (the residual
// window), then further, a lowest-mode period at a time, until a whole period stays
// below the settling band; at most this many periods. An undamped structure under the
// kinematic drive stops at the window's end: nothing will ever damp what the window shows.
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

int AutoSubstepsOf(const std::vector<model::AxisModes>& modes, double period_s) {
  double fastest_hz = 0.0;
  for (const model::AxisModes& axis : modes) {
    for (const model::ModeInfo& mode : axis.analysis.modes) {
      if (std::abs(mode.participation) >= 0.01) fastest_hz = std::max(fastest_hz, mode.frequency_hz);
    }
  }
  // 200 samples per period bound the sampling error of a peak by 1 - cos(pi/200) = 1.2e-4.
  const int substeps = static_cast<int>(std::ceil(period_s * fastest_hz * 200.0));
  return std::clamp(substeps, 1, 64);
}

// The contour error of a sample: its distance from the programmed path, squared (the
// largest distance is the square root of the largest square, bit for bit: norm() is the
// square root of squaredNorm(), and the square root is monotone). A single straight
// element (a `move:`, a one-block program) is measured on it directly: the whole path's
// search gives the same point there.
class ContourGauge {
 public:
  explicit ContourGauge(const controller::PathGeometry& path) : path_(path) {
    const auto& elements = path.elements();
    if (elements.size() == 1 && !elements.front().is_arc()) single_ = &elements.front();
  }
  double SquaredDistanceTo(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d nearest = single_ != nullptr ? single_->NearestPoint(p) : path_.NearestPoint(p);
    return (p - nearest).squaredNorm();
  }
  const controller::PathElement* single() const { return single_; }

 private:
  const controller::PathGeometry& path_;
  const controller::PathElement* single_ = nullptr;
};

// A run whose command moves one axis only, along a single straight element of that axis,
// with the metrics' view on that axis: every other component of command, deflection and
// tool error stays exactly 0 (checked per period on the outputs), so the samples need only
// that axis' scalars. The arithmetic is the general loop's, component by component
// (tests/bench/cosim_fast_path_test.cc compares the two bit for bit).
struct SingleAxis {
  int axis = -1;
  double start_m = 0.0;      // the element's start on the axis
  double direction = 0.0;    // +1 or -1
  double length_m = 0.0;
};

SingleAxis FindSingleAxis(const controller::MultiAxisCommand& command,
                          const std::vector<Eigen::Vector3d>& positions, const View& view,
                          const ContourGauge& gauge, bool has_stroke) {
  SingleAxis none;
  const controller::PathElement* e = gauge.single();
  if (e == nullptr || view.magnitude || has_stroke) return none;
  int axis = -1;
  for (int a = 0; a < controller::kNumAxes; ++a) {
    if (view.direction(a) == 1.0) axis = a;
  }
  if (axis < 0 || std::abs(e->direction(axis)) != 1.0) return none;
  for (int a = 0; a < controller::kNumAxes; ++a) {
    if (a == axis) continue;
    if (e->direction(a) != 0.0) return none;
    for (double v : command.axes[a].velocity_m_s) {
      if (v != 0.0) return none;
    }
    // Its velocities all (+ or -) 0, the axis' positions are its start plus sums of
    // zeros: each equals (==) the first.
    if (positions.front()(a) != e->start_m(a)) return none;
  }
  return {axis, e->start_m(axis), e->direction(axis), e->length_m};
}

}  // namespace

int AutoSubsteps(const model::MultiAxisMachineConfig& machine, double period_s) {
  return AutoSubstepsOf(model::AnalyzeMachineModes(machine), period_s);
}

RunResult RunScenario(const Scenario& scenario, const RunOptions& options) {
  RunResult result;
  result.program = scenario.RunProgram();
  controller::ControllerConfig controller = scenario.controller;
  controller.stroke_limits = scenario.machine.stroke_m;  // the CNC's stroke check
  if (options.command == nullptr) {
    result.command = controller::GenerateProgramCommand(controller, result.program);
  }
  const controller::MultiAxisCommand& command =
      options.command != nullptr ? *options.command : result.command;
  const double dt = command.period_s;
  const controller::PathGeometry path(result.program);
  const ContourGauge contour_gauge(path);

  const model::MachinePlant machine = model::BuildMachinePlant(scenario.machine, scenario.drive);
  const model::LinearPlant& plant = machine.plant;
  const std::vector<model::AxisModes> modes = model::AnalyzeMachineModes(scenario.machine);
  double lowest_hz = std::numeric_limits<double>::infinity();
  for (const model::AxisModes& axis : modes) {
    for (const model::ModeInfo& mode : axis.analysis.modes) lowest_hz = std::min(lowest_hz, mode.frequency_hz);
  }
  const double lowest_period_s = std::isfinite(lowest_hz) ? 1.0 / lowest_hz : kRigidTailPeriodS;
  const int substeps = scenario.integrator.output_substeps > 0
                           ? scenario.integrator.output_substeps
                           : AutoSubstepsOf(modes, dt);
  result.substeps = substeps;
  const View view = MakeView(scenario.output, command);

  // The command per tick, once: velocity v_k (k = 0..n), acceleration a_k held over
  // period k (k = 1..n), position p_k (k = 0..n).
  const std::size_t n = command.num_ticks();
  std::vector<Eigen::Vector3d> velocity(n + 1);
  std::vector<Eigen::Vector3d> accel(n + 1, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> positions(n + 1, command.start_m);
  for (int axis = 0; axis < controller::kNumAxes; ++axis) {
    // As MultiAxisCommand::velocity_m_s, accel_m_s2 and Positions compute them.
    const controller::CommandTrajectory& trajectory = command.axes[axis];
    const std::vector<double>& v = trajectory.velocity_m_s;
    velocity[0](axis) = v[0];
    double position = command.start_m(axis);
    if (std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0 && !std::signbit(x); })) {
      // An axis that does not move: the same sums, of zeros (the first turns -0 into +0).
      position += 0.0;
      for (std::size_t k = 1; k <= n; ++k) {
        velocity[k](axis) = 0.0;
        positions[k](axis) = position;
      }
      continue;
    }
    for (std::size_t k = 1; k <= n; ++k) {
      velocity[k](axis) = v[k];
      accel[k](axis) = trajectory.accel_m_s2(k);
      position += trajectory.increment_m(k);
      positions[k](axis) = position;
    }
  }

  // Static displacement: the largest deflection a held commanded acceleration gives.
  double max_accel = 0.0;
  double max_speed = 0.0;
  double static_m = 0.0;
  for (std::size_t k = 1; k <= n; ++k) {
    const Eigen::Vector3d& a = accel[k];
    // Largest squared norms, their roots below: the root of the largest square is the
    // largest norm (norm() is the root of squaredNorm(), the root is monotone).
    max_accel = std::max(max_accel, a.squaredNorm());
    max_speed = std::max(max_speed, velocity[k].squaredNorm());
    static_m = std::max(static_m, std::abs(view.Of(machine.static_gain * a)));
  }
  max_accel = std::sqrt(max_accel);
  max_speed = std::sqrt(max_speed);
  Metrics& m = result.metrics;
  m.static_displacement_m = static_m;

  // Motion ends at the last tick where a commanded velocity becomes (and stays) zero.
  std::size_t last_moving = 0;
  for (std::size_t k = n + 1; k-- > 0;) {
    const Eigen::Vector3d& v = velocity[k];
    if (v(0) != 0.0 || v(1) != 0.0 || v(2) != 0.0) {
      last_moving = k;
      break;
    }
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
  // Undamped (every mode's energy conserved once the command stops): a run not settled by
  // the end of the residual window never settles, and a longer tail would only repeat the
  // window's oscillation (a sample of it up to 1 - cos(pi/200) higher, Sampling). Off a
  // pattern's design frequency this is most of a sweep's points; the 30-period tail made
  // them 2.5 times as long as the motion they report on.
  const bool never_settles_late =
      scenario.drive.type == model::DriveType::kKinematic && model::IsUndamped(scenario.machine);

  std::unique_ptr<model::PlantIntegrator> integrator;
  if (plant.num_states() > 0) {
    integrator = model::MakeIntegrator(plant, scenario.integrator, dt, substeps,
                                       std::max(max_accel, 1e-12), max_speed);
    integrator->Reset(Eigen::VectorXd::Zero(plant.num_inputs()));
  }
  // The outputs of one period's substeps (AdvancePeriod), rows as in MachinePlant.
  const int rows = plant.num_outputs();
  std::vector<double> outputs(static_cast<std::size_t>(substeps) * std::max(rows, 6), 0.0);

  std::vector<ArcWindow> arcs;
  for (const controller::PathElement& e : path.elements()) {
    if (e.is_arc()) arcs.push_back({&e, 0.0, 0});
  }

  Trace& trace = result.trace;
  const bool record_trace = options.record_trace;
  if (record_trace) {
    // Every run simulates the motion and the residual window; most settle a period later
    // (reserved up to a few million samples; a longer trace grows as it goes).
    const std::size_t expected = std::min<std::size_t>(
        std::min(max_ticks, motion_ticks + residual_ticks + period_ticks) * substeps + 1, 4'000'000);
    trace.time_s.reserve(expected);
    trace.command_position_m.reserve(expected);
    trace.command_velocity_m_s.reserve(expected);
    trace.command_accel_m_s2.reserve(expected);
    trace.deflection_m.reserve(expected);
    trace.command_m.reserve(expected);
    trace.actual_m.reserve(expected);
    trace.deflection_axes_m.reserve(expected);
    trace.block.reserve(expected);
    trace.planned_feed_mm_min.reserve(expected);
  }
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
  if (record_trace) {
    record(0.0, positions.front(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
           Eigen::Vector3d::Zero(), positions.front(), first_block);
  }

  const double band = kSettlingBand * m.static_displacement_m;
  double peak = 0.0;
  Eigen::Vector3d peak_axes = Eigen::Vector3d::Zero();
  double residual = 0.0;
  double cruise = NAN;
  double contour = 0.0;
  double overshoot = 0.0;
  const bool has_stroke = std::any_of(scenario.machine.stroke_m.begin(),
                                      scenario.machine.stroke_m.end(),
                                      [](const auto& limits) { return limits.has_value(); });
  long last_outside_band = -1;  // last sample (substep count) after the motion outside the band
  std::size_t quiet_since_tick = motion_ticks;
  bool settled = false;
  std::size_t last_tick = 0;
  // Cruise: the commanded feed constant and non-zero, for at least one period of the
  // lowest mode in a row. Shorter constant stretches are steps of a pattern (method 2's
  // zero step, T/6), not the cruise whose vibration the metric reports.
  std::vector<char> cruise_tick(n + 1, 0);
  for (std::size_t k = 1, run_start = 1; k <= n + 1; ++k) {
    const bool steady = k <= n &&
                        (velocity[k](0) != 0.0 || velocity[k](1) != 0.0 || velocity[k](2) != 0.0) &&
                        (accel[k].squaredNorm() == 0.0 || accel[k].norm() <= 1e-9 * max_accel);
    if (steady) continue;
    if (k - run_start >= period_ticks) std::fill(cruise_tick.begin() + run_start, cruise_tick.begin() + k, 1);
    run_start = k + 1;
  }
  // For how many periods from tick k on the held acceleration stays a_k (the tail's is
  // zero): an integrator that can (CVODE) integrates across those ticks (AdvancePeriod).
  // Found on the way, for the integrators that use it.
  const bool holds = integrator && integrator->UsesInputHolds();
  auto accel_at = [&](std::size_t k) -> const Eigen::Vector3d& { return k <= n ? accel[k] : accel[0]; };
  std::size_t next_change = 0;  // the first tick after k whose acceleration differs from a_k
  auto same_input = [&](std::size_t k) -> long {
    if (!holds) return 1;
    if (k >= next_change) {
      const Eigen::Vector3d& here = accel_at(k);
      next_change = k + 1;
      while (next_change <= max_ticks) {
        const Eigen::Vector3d& next = accel_at(next_change);
        if (next(0) != here(0) || next(1) != here(1) || next(2) != here(2)) break;
        ++next_change;
      }
    }
    return static_cast<long>(next_change - k);
  };
  const std::size_t interpolated_ticks = command.path_position_m.size();
  const SingleAxis single = record_trace ? SingleAxis{}
                                         : FindSingleAxis(command, positions, view, contour_gauge, has_stroke);
  double contour_sq = 0.0;
  // The other axes' rows the single-axis samples must see at 0 (the rest are 0 by the
  // integrator's structure).
  std::vector<int> watched_rows;
  if (single.axis >= 0 && rows == 6) {
    for (int r = 0; r < rows; ++r) {
      if (r % 3 != single.axis && !(integrator && integrator->OutputRowIsZero(r))) watched_rows.push_back(r);
    }
  }
  // When every other row is 0 by the integrator's structure, only the axis' deflection
  // and tool error are asked for: every period takes the single-axis samples.
  int width = rows;  // outputs per substep in `outputs`
  int deflection_at = model::kDeflectionRow + std::max(single.axis, 0);
  int tool_error_at = model::kToolErrorRow + std::max(single.axis, 0);
  if (single.axis >= 0 && rows == 6 && watched_rows.empty() && integrator) {
    integrator->SelectOutputs({model::kDeflectionRow + single.axis, model::kToolErrorRow + single.axis});
    width = 2;
    deflection_at = 0;
    tool_error_at = 1;
  }
  // Every output of period k finite, else the run fails (a degenerate model: never reported
  // as numbers), at the first substep that is not.
  auto check_finite = [&](std::size_t k) {
    for (int i = 0; i < substeps * width; ++i) {
      if (!std::isfinite(outputs[i])) {
        const long count = static_cast<long>((k - 1) * substeps) + i / width + 1;
        throw model::SolverError("NON_FINITE_STATE",
                                 "the plant's deflection became non-finite at t = " +
                                     std::to_string(dt * static_cast<double>(count) / substeps) +
                                     " s (a degenerate model)");
      }
    }
  };
  double fast_peak = 0.0;  // the single-axis samples' peak (of peak and peak_axes(axis))
  std::vector<double> taus(substeps);  // the substeps' times within a period
  for (int j = 1; j <= substeps; ++j) taus[j - 1] = dt * static_cast<double>(j) / substeps;
  for (std::size_t k = 1; k <= max_ticks; ++k) {
    // FMI order: set the input held over (t_{k-1}, t_k], step, read the outputs.
    const bool commanded = k <= n;
    const Eigen::Vector3d& a = commanded ? accel[k] : accel[0];
    const Eigen::Vector3d& v0 = commanded ? velocity[k - 1] : accel[0];
    const Eigen::Vector3d& p0 = commanded ? positions[k - 1] : positions.back();
    bool others_zero = single.axis >= 0 && rows == 6;  // the other axes' outputs all exactly 0
    if (integrator) {
      integrator->AdvancePeriod(a.data(), same_input(k), outputs.data());
      if (others_zero && !watched_rows.empty()) {
        // Branch-free: the other rows' bits all zero (rows the integrator guarantees 0 are
        // not even looked at). Anything else (-0.0 included) takes the general loop.
        std::uint64_t other_bits = 0;
        for (int j = 0; j < substeps; ++j) {
          const double* out = outputs.data() + static_cast<std::ptrdiff_t>(j) * rows;
          for (int r : watched_rows) {
            std::uint64_t bits;
            std::memcpy(&bits, out + r, sizeof bits);
            other_bits |= bits;
          }
        }
        others_zero = other_bits == 0;
      }
      // The single-axis samples check their own values' finiteness (below).
      if (!others_zero) check_finite(k);
    }
    const bool cruising = commanded && cruise_tick[k];
    const bool after_motion = k >= motion_ticks;
    if (others_zero) {
      // The single-axis samples (SingleAxis): the general loop below, its other components
      // left out; the same operations in the same order.
      const int ax = single.axis;
      const double p0_a = p0(ax);
      const double v0_a = v0(ax);
      const double half_a = 0.5 * a(ax);
      const double* deflections = outputs.data() + deflection_at;
      const double* tool_errors = outputs.data() + tool_error_at;
      // Set when a deflection or tool error was not finite (or a square overflowed): an
      // `or` of comparisons, not a running sum, keeps the samples independent.
      bool not_finite = false;
      // The samples' deflection magnitudes, and the contour error (squared) of each.
      auto sample = [&](int j, double* magnitude) {
        const double tau = taus[j];
        const double p = p0_a + v0_a * tau + half_a * tau * tau;
        const double actual = p + tool_errors[j * width];
        *magnitude = std::abs(deflections[j * width]);
        const double along = std::clamp((actual - single.start_m) * single.direction, 0.0, single.length_m);
        const double off = actual - (single.start_m + along * single.direction);
        const double square = off * off;
        not_finite |= !(square + *magnitude <= std::numeric_limits<double>::max());
        return square;
      };
      double tick_peak = fast_peak;
      double tick_contour = contour_sq;
      if (!after_motion) {
        // The tick's own maxima first, then one max into the run's: the run's maxima are no
        // longer a chain of one dependent max per sample (the same values: max is exact, and
        // a NaN sample throws below whatever it did to them).
        double magnitude_max;
        double square_max = sample(0, &magnitude_max);
        for (int j = 1; j < substeps; ++j) {
          double magnitude;
          const double square = sample(j, &magnitude);
          square_max = std::max(square_max, square);
          magnitude_max = std::max(magnitude_max, magnitude);
        }
        tick_contour = std::max(tick_contour, square_max);
        tick_peak = std::max(tick_peak, magnitude_max);
        if (cruising) cruise = std::isnan(cruise) ? magnitude_max : std::max(cruise, magnitude_max);
      } else if (k > motion_ticks + residual_ticks && !cruising) {
        // The tail after the residual window: only the settling band is watched.
        int last_outside = -1;
        for (int j = 0; j < substeps; ++j) {
          double magnitude;
          const double square = sample(j, &magnitude);
          tick_contour = std::max(tick_contour, square);
          tick_peak = std::max(tick_peak, magnitude);
          if (magnitude >= band) last_outside = j;
        }
        if (last_outside >= 0) {
          last_outside_band = static_cast<long>((k - 1) * substeps) + last_outside + 1;
          quiet_since_tick = k;
        }
      } else {
        for (int j = 0; j < substeps; ++j) {
          double magnitude;
          const double square = sample(j, &magnitude);
          tick_contour = std::max(tick_contour, square);
          tick_peak = std::max(tick_peak, magnitude);
          if (cruising) cruise = std::isnan(cruise) ? magnitude : std::max(cruise, magnitude);
          if (k > motion_ticks || j + 1 == substeps) {
            if (k <= motion_ticks + residual_ticks) residual = std::max(residual, magnitude);
            if (magnitude >= band) {
              last_outside_band = static_cast<long>((k - 1) * substeps) + j + 1;
              quiet_since_tick = k;
            }
          }
        }
      }
      if (integrator && not_finite) check_finite(k);  // throws for a non-finite output
      fast_peak = tick_peak;
      contour_sq = tick_contour;
    } else {
      const bool interpolating = k < interpolated_ticks;
      const int block = interpolating ? command.block[k] : -1;
      const double path_s = command.path_position_m.empty()
                                ? 0.0
                                : command.path_position_m[std::min(k, interpolated_ticks - 1)];
      for (int j = 1; j <= substeps; ++j) {
        const long count = static_cast<long>((k - 1) * substeps) + j;  // this sample's
        const double* out = outputs.data() + static_cast<std::ptrdiff_t>(j - 1) * rows;
        const double tau = taus[j - 1];
        const Eigen::Vector3d p = p0 + v0 * tau + 0.5 * a * tau * tau;
        const Eigen::Vector3d deflection(out[model::kDeflectionRow], out[model::kDeflectionRow + 1],
                                         out[model::kDeflectionRow + 2]);
        const Eigen::Vector3d actual =
            p + Eigen::Vector3d(out[model::kToolErrorRow], out[model::kToolErrorRow + 1],
                                out[model::kToolErrorRow + 2]);
        if (record_trace) {
          const Eigen::Vector3d v = v0 + a * tau;
          travelled_m += v.norm() * dt / substeps;
          record(dt * static_cast<double>(count) / substeps, p, v, a, deflection, actual, block);
        }
        const double magnitude = std::abs(view.Of(deflection));
        peak = std::max(peak, magnitude);
        peak_axes = peak_axes.cwiseMax(deflection.cwiseAbs());
        contour_sq = std::max(contour_sq, contour_gauge.SquaredDistanceTo(actual));
        if (has_stroke) overshoot = std::max(overshoot, controller::StrokeOvershoot(p, scenario.machine.stroke_m));
        for (ArcWindow& w : arcs) {
          const double from_start = path_s - w.arc->start_s_m;
          if (from_start >= 0.25 * w.arc->length_m && from_start <= 0.75 * w.arc->length_m) {
            w.sum_radius_m += std::hypot(actual(w.arc->axis0) - w.arc->center_m(w.arc->axis0),
                                         actual(w.arc->axis1) - w.arc->center_m(w.arc->axis1));
            ++w.samples;
          }
        }
        if (cruising) cruise = std::isnan(cruise) ? magnitude : std::max(cruise, magnitude);
        if (after_motion && (k > motion_ticks || j == substeps)) {
          if (k <= motion_ticks + residual_ticks) residual = std::max(residual, magnitude);
          if (magnitude >= band) {
            last_outside_band = count;
            quiet_since_tick = k;
          }
        }
      }
    }
    last_tick = k;
    if (k >= motion_ticks + residual_ticks) {
      if (k >= quiet_since_tick + period_ticks) {
        settled = true;
        break;
      }
      if (never_settles_late) break;
    }
  }
  contour = std::sqrt(contour_sq);
  if (single.axis >= 0) {
    peak = std::max(peak, fast_peak);
    peak_axes(single.axis) = std::max(peak_axes(single.axis), fast_peak);
  }
  result.simulated_s = static_cast<double>(last_tick) * dt;
  m.peak_deflection_m = peak;
  m.peak_ratio = peak / m.static_displacement_m;
  m.residual_amplitude_m = residual;
  m.residual_ratio = residual / m.static_displacement_m;
  m.cruise_residual_ratio = cruise / m.static_displacement_m;
  if (settled) {
    // The sample's time as the loop has it: dt * count / substeps.
    m.settling_time_s =
        last_outside_band < 0
            ? 0.0
            : dt * static_cast<double>(last_outside_band) / substeps + dt / substeps - m.motion_time_s;
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
  bool any_infinite = false;  // (Named() builds strings: only when there is one to name)
  for (double value : {m.static_displacement_m, m.peak_deflection_m, m.peak_ratio,
                       m.residual_amplitude_m, m.residual_ratio, m.cruise_residual_ratio,
                       m.motion_time_s, m.settling_time_s, m.max_contour_error_m,
                       m.radial_error_m, m.peak_deflection_x_m, m.peak_deflection_y_m,
                       m.peak_deflection_z_m, m.short_block_clamps, m.stroke_overshoot_m,
                       m.stroke_alarm}) {
    any_infinite = any_infinite || std::isinf(value);
  }
  for (const auto& [name, value] : any_infinite ? m.Named() : decltype(m.Named()){}) {
    // NaN is "undefined"; infinity never true
    if (std::isinf(value)) {
      throw model::SolverError("NON_FINITE_STATE", name + " overflowed to infinity (a degenerate model)");
    }
  }
  return result;
}

}  // namespace shapebench::bench
