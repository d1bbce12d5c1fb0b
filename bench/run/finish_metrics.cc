#include "bench/run/finish_metrics.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/math_constants.h"
#include "controller/shaper_registry.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

// A metric that overflowed is a degenerate model, never a number (NaN is "undefined").
void RefuseInfiniteMetrics(const Metrics& m) {
  for (const MetricInfo& info : MetricTable()) {
    if (std::isinf(m.*info.field)) {
      throw model::SolverError("NON_FINITE_STATE",
                               std::string(info.name) + " overflowed to infinity (a degenerate model)");
    }
  }
}

// A plant with nonlinear elements (docs/nonlinear.md): the residual from its free response
// after motion end (half its peak-to-peak: one undamped mode's amplitude exactly), where it
// comes to rest, and the quadrant glitches of its arcs.
void FinishNonlinearMetrics(const MetricTally& t, Metrics* m) {
  if (!std::isnan(t.free_half_range_m)) {
    m->residual_amplitude_m = t.free_half_range_m;
    m->residual_ratio = m->static_displacement_m > 0.0 ? m->residual_amplitude_m / m->static_displacement_m : NAN;
    m->dead_band_m = t.dead_band_m;
  }
  m->quadrant_glitch_m = t.quadrant_glitch_m;
}

}  // namespace

double StaticDisplacement(const CommandSamples& s, const Eigen::Matrix3d& static_gain, const OutputView& view,
                          Eigen::Vector3d* vector) {
  double static_m = 0.0;
  std::size_t at = 0;
  // Once per held acceleration (the same a, the same value: the first tick reaching the
  // largest is the first of its run).
  for (const std::size_t k : s.accel_changes) {
    const double here = std::abs(view.Of(static_gain * s.accel[k]));
    if (here > static_m) {
      static_m = here;
      at = k;
    }
  }
  *vector = Eigen::Vector3d::Zero();
  if (at == 0) return static_m;
  // The vector's sign follows the machine and the move, never the view (issue 32 item 16):
  // C a (C = -static_gain: the tool lags by -C a) with a taken in the positive sense of the
  // axis it mostly lies along (the first of equal ones), so a Y move and its reverse,
  // viewed along Y, Z or as the magnitude, give the same vector; a mode of negative gain
  // shows as a negative entry.
  const Eigen::Vector3d& a = s.accel[at];
  Eigen::Index dominant = 0;
  a.cwiseAbs().maxCoeff(&dominant);
  const Eigen::Vector3d deflection = -(static_gain * (a(dominant) < 0.0 ? Eigen::Vector3d(-a) : a));
  for (int b = 0; b < 3; ++b) (*vector)(b) = deflection(b) == 0.0 ? 0.0 : deflection(b);  // no -0
  return static_m;
}

namespace {

// A single straight move (a `move:`, a one-line program): the command's own acceleration
// is the acc/dec's, and the reference stays as it always was.
bool SingleStraightMove(const controller::PathGeometry& path) {
  int moving = 0;
  for (const controller::PathElement& e : path.elements()) {
    if (e.length_m == 0.0) continue;
    if (e.is_arc()) return false;
    ++moving;
  }
  return moving <= 1;
}

// The directions the program moves in: each line's, and each arc's tangent at its ends
// and every degree of its sweep between.
template <typename F>
void ForEachDirection(const controller::PathGeometry& path, F f) {
  for (const controller::PathElement& e : path.elements()) {
    if (e.length_m == 0.0) continue;
    if (!e.is_arc()) {
      f(e.direction);
      continue;
    }
    const int steps = std::max(4, static_cast<int>(std::ceil(std::abs(e.sweep_rad) * 180.0 / kPi)));
    for (int j = 0; j <= steps; ++j) {
      // An arc's end tangent along an axis carries ~1e-17 on the other (cos 90 deg): 0.
      Eigen::Vector3d d = e.TangentAtFraction(static_cast<double>(j) / steps);
      for (int b = 0; b < 3; ++b) d(b) = std::abs(d(b)) < 1e-12 ? 0.0 : d(b);
      f(d);
    }
  }
}

}  // namespace

double ProgramStaticDisplacement(const controller::PathGeometry& path, double accel_m_s2,
                                 const Eigen::Matrix3d& static_gain, const OutputView& view,
                                 Eigen::Vector3d* vector) {
  double static_m = 0.0;
  Eigen::Vector3d along = Eigen::Vector3d::Zero();
  ForEachDirection(path, [&](const Eigen::Vector3d& d) {
    const double here = std::abs(view.Of(static_gain * (accel_m_s2 * d)));
    if (here > static_m) {
      static_m = here;
      along = d;
    }
  });
  *vector = Eigen::Vector3d::Zero();
  if (static_m == 0.0) return static_m;
  // The sign convention of StaticDisplacement: the acceleration in the positive sense of
  // the axis it mostly lies along.
  Eigen::Index dominant = 0;
  along.cwiseAbs().maxCoeff(&dominant);
  const Eigen::Vector3d a = accel_m_s2 * (along(dominant) < 0.0 ? Eigen::Vector3d(-along) : along);
  const Eigen::Vector3d deflection = -(static_gain * a);
  for (int b = 0; b < 3; ++b) (*vector)(b) = deflection(b) == 0.0 ? 0.0 : deflection(b);  // no -0
  return static_m;
}

void SetStaticReference(const RunPlan& plan, const Eigen::Matrix3d& static_gain, MetricTally* tally) {
  Eigen::Vector3d vector;
  // Programs: the acc/dec's acceleration, not whatever one period of the command held (a
  // corner's one-period velocity step made the ratios read 0.17-0.37, issue 36).
  const double static_m =
      SingleStraightMove(plan.path)
          ? StaticDisplacement(plan.samples, static_gain, plan.view, &vector)
          : ProgramStaticDisplacement(plan.path, plan.scenario.controller.accel_m_s2(), static_gain, plan.view,
                                      &vector);
  tally->SetStatic(static_m, vector, RunWindow::kSettlingBand);
  tally->quiet_since_tick = plan.window.motion_ticks;
}

void SetPatternMetrics(const controller::PatternConfig& pattern, Metrics* m) {
  const controller::ShaperKind kind = controller::FindShaper(pattern.method).kind;
  if (pattern.mode == controller::PatternMode::kOff ||
      (kind != controller::ShaperKind::kPatentStep && kind != controller::ShaperKind::kImpulse)) {
    return;
  }
  // DesignFrequencies() and DesignDampingRatios() read in place (they copy the lists: two
  // allocations a sweep point).
  const std::vector<double>& listed = pattern.frequencies_hz;
  const std::size_t lowest =
      listed.empty() ? 0 : static_cast<std::size_t>(std::min_element(listed.begin(), listed.end()) - listed.begin());
  m->pattern_frequency_hz = listed.empty() ? pattern.frequency_hz : listed[lowest];
  const double damping_ratio =
      pattern.damping_ratios.empty() ? pattern.design_damping_ratio : pattern.damping_ratios[lowest];
  m->pattern_damping_ratio = kind == controller::ShaperKind::kPatentStep ? 0.0 : damping_ratio;
}

Metrics FinishMetrics(const RunPlan& plan, const MetricTally& t) {
  Metrics m;
  const double dt = plan.dt_s;
  m.static_displacement_m = t.static_m;
  m.static_displacement_x_m = t.static_vector(0);
  m.static_displacement_y_m = t.static_vector(1);
  m.static_displacement_z_m = t.static_vector(2);
  m.motion_time_s = static_cast<double>(plan.window.motion_ticks) * dt;
  if (t.settled) {
    // The sample's time as the samples have it: dt * count / substeps.
    m.settling_time_s = t.last_outside_band < 0
                            ? 0.0
                            : plan.SampleTime(t.last_outside_band) + dt / plan.substeps - m.motion_time_s;
  }
  // A model whose static deflections cancel in the view (opposite gains) has no static
  // reference: its ratios are n/a (NaN), the absolute metrics stand.
  const auto ratio = [&t](double x) { return t.static_m > 0.0 ? x / t.static_m : NAN; };
  m.peak_deflection_m = t.peak;
  m.peak_ratio = ratio(t.peak);
  m.residual_amplitude_m = t.residual_m;
  m.residual_ratio = ratio(t.residual_m);
  m.residual_peak_m = t.residual;
  m.residual_peak_ratio = ratio(t.residual);
  m.cruise_residual_ratio = ratio(t.cruise_m);
  m.max_contour_error_m = std::sqrt(t.contour_sq);
  m.radial_error_m = t.radial_error_m;
  if (t.nonlinear) FinishNonlinearMetrics(t, &m);
  m.peak_deflection_x_m = t.peak_axes(0);
  m.peak_deflection_y_m = t.peak_axes(1);
  m.peak_deflection_z_m = t.peak_axes(2);
  m.short_block_clamps = plan.command.short_block_clamps;
  m.stroke_overshoot_m = t.overshoot_m;
  m.stroke_alarm = plan.command.stroke_alarm ? 1.0 : 0.0;
  m.peak_command_acceleration_m_s2 = plan.samples.max_accel_m_s2;
  if (t.static_unknown) {
    m.static_displacement_m = m.static_displacement_x_m = m.static_displacement_y_m = m.static_displacement_z_m = NAN;
    m.settling_time_s = NAN;
  }
  SetPatternMetrics(plan.scenario.controller.pattern, &m);
  RefuseInfiniteMetrics(m);
  return m;
}

}  // namespace shapebench::bench
