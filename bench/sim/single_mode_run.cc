#include "bench/sim/single_mode_run.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "bench/sim/deferred_substeps.h"
#include "bench/sim/metric_accumulator.h"
#include "bench/sim/output_view.h"
#include "bench/sim/run_window.h"
#include "model/band_crossing.h"
#include "model/machine.h"

namespace shapebench::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The mode of the run's one modelled axis, or null.
const model::ModalMode* OnlyMode(const Scenario& scenario, int axis) {
  const model::MultiAxisMachineConfig& machine = scenario.machine;
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (a != axis && machine.axes[a].has_value()) return nullptr;
  }
  if (!machine.axes[axis].has_value()) return nullptr;
  const auto* modal = std::get_if<model::ModalMachineConfig>(&machine.axes[axis]->form);
  if (modal == nullptr || modal->modes.size() != 1 || modal->coupled()) return nullptr;
  return &modal->modes.front();
}

// The one straight element of the path along `axis`, or null.
const controller::PathElement* OnlyLine(const controller::PathGeometry& path, int axis) {
  if (path.elements().size() != 1) return nullptr;
  const controller::PathElement& e = path.elements().front();
  if (e.is_arc() || std::abs(e.direction(axis)) != 1.0) return nullptr;
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (a != axis && e.direction(a) != 0.0) return nullptr;
  }
  return &e;
}

// The view's axis when the output is one axis' and the scenario names it, or -1 (auto is
// resolved by the caller from the command).
int ViewAxis(const Scenario& scenario, int moving) {
  switch (scenario.output.direction) {
    case OutputDirection::kX: return 0;
    case OutputDirection::kY: return 1;
    case OutputDirection::kZ: return 2;
    case OutputDirection::kMagnitude: return -1;
    case OutputDirection::kAuto: return moving;
  }
  return -1;
}

// The mode's transition over tau: x(tau) = phi (x0, v0), x = q - q_eq (a held).
struct Transition {
  double xx = 1.0, xv = 0.0, vx = 0.0, vv = 1.0;
};

// One mode, one line: the constant part of the run (MuJoCo's model), then the run's state.
class SingleModeKernel {
 public:
  SingleModeKernel(const model::ModalMode& mode, const controller::PathElement& line, int axis,
                   const CommandSamples& samples, double dt, int substeps)
      : s_(samples), axis_(axis), dt_(dt), substeps_(substeps) {
    w_ = 2.0 * kPi * mode.frequency_hz;
    sigma_ = mode.damping_ratio * w_;
    wd_ = w_ * std::sqrt(1.0 - mode.damping_ratio * mode.damping_ratio);
    gain_ = mode.gain;
    start_ = line.start_m(axis);
    direction_ = line.direction(axis);
    length_ = line.length_m;
    period_ = At(dt);
    inner_.resize(static_cast<std::size_t>(substeps));
    taus_.resize(static_cast<std::size_t>(substeps));
    for (int j = 1; j <= substeps; ++j) {
      taus_[j - 1] = dt * static_cast<double>(j) / substeps;
      inner_[j - 1] = At(taus_[j - 1]);
    }
  }

  double ModalAmplitude() const {  // of the free vibration about q = 0 (a = 0)
    return std::abs(gain_) * std::hypot(q_, (v_ + sigma_ * q_) / wd_);
  }
  double StaticGain() const { return -gain_ / (w_ * w_); }  // deflection per m/s^2

  // Period k: the state to its end; returns |deflection| at the end and sets *inside to
  // the largest |deflection| at a stationary point inside (0 when none).
  double Advance(double a, double* inside) {
    q_eq_ = -a / (w_ * w_);
    x0_ = q_ - q_eq_;
    v0_ = v_;
    const double x1 = period_.xx * x0_ + period_.xv * v0_;
    v_ = period_.vx * x0_ + period_.vv * v0_;
    q_ = x1 + q_eq_;
    *inside = v0_ * v_ < 0.0 ? Extremum() : 0.0;
    return std::abs(gain_ * q_);
  }
  // The deflection at substep j (0-based) of the period Advance stepped last.
  double Substep(int j) const {
    const Transition& t = inner_[static_cast<std::size_t>(j)];
    return gain_ * (t.xx * x0_ + t.xv * v0_ + q_eq_);
  }
  // The free response from the current state (input 0 from now on) as one pole pair.
  model::FreeTerms Free() const {
    model::FreeTerms terms;
    terms.q = {std::complex<double>(gain_ * q_, -gain_ * (v_ + sigma_ * q_) / wd_)};
    terms.lambda = {std::complex<double>(-sigma_, wd_)};
    return terms;
  }

  const CommandSamples& s_;
  const int axis_;
  const double dt_;
  const int substeps_;
  double start_ = 0.0, direction_ = 1.0, length_ = 0.0;
  std::vector<double> taus_;

 private:
  Transition At(double tau) const {
    const double e = std::exp(-sigma_ * tau);
    const double c = std::cos(wd_ * tau);
    const double sn = std::sin(wd_ * tau);
    return {e * (c + sigma_ / wd_ * sn), e * sn / wd_, -e * (w_ * w_) / wd_ * sn, e * (c - sigma_ / wd_ * sn)};
  }
  // Where q' = e^{-sigma t} (v0 cos(w_d t) - ((sigma v0 + w^2 x0) / w_d) sin(w_d t))
  // vanishes inside the period: w_d t = atan2(w_d v0, sigma v0 + w^2 x0) (mod pi).
  double Extremum() const {
    const double half = kPi / wd_;
    double t = std::fmod(std::atan2(wd_ * v0_, sigma_ * v0_ + w_ * w_ * x0_), kPi) / wd_;
    if (t < 0.0) t += half;
    if (!(t > 0.0 && t < dt_)) return 0.0;  // rounding at an end: the ends are samples
    const double b = (v0_ + sigma_ * x0_) / wd_;
    const double x = std::exp(-sigma_ * t) * (x0_ * std::cos(wd_ * t) + b * std::sin(wd_ * t));
    return std::abs(gain_ * (x + q_eq_));
  }

  double w_ = 0.0, sigma_ = 0.0, wd_ = 0.0, gain_ = 1.0;
  Transition period_;
  std::vector<Transition> inner_;
  double q_ = 0.0, v_ = 0.0;                // the state at the last period's end
  double x0_ = 0.0, v0_ = 0.0, q_eq_ = 0.0;  // the last period's start, about its equilibrium
};

// The master's loop over the run's ticks, its accumulators as the general path keeps them
// (cosim.cc: SampleTick, DeferredTick, SettleTail).
class SingleModeMaster {
 public:
  SingleModeMaster(SingleModeKernel* kernel, const RunWindow& window, double static_m)
      : m_(*kernel), window_(window), static_m_(static_m) {
    acc_.band = RunWindow::kSettlingBand * static_m;
    acc_.quiet_since_tick = window.motion_ticks;
    next_probe_ = window.cruise_probe_ticks.begin();
    // Far above the rounding OffLineBound allows for (a few ulps of the coordinates).
    safe_margin_ = 1e-9 * (std::abs(kernel->start_) + kernel->length_) + 1e-12;
  }

  void Run(RunResult* result);

 private:
  template <RunPhase P> void Tick(std::size_t k);
  void Contour(std::size_t k, double bound);
  bool SettleTail(std::size_t k);

  SingleModeKernel& m_;
  const RunWindow& window_;
  const double static_m_;
  RunAccumulator acc_;
  std::vector<std::size_t>::const_iterator next_probe_;
  double start_abs_ = 0.0;  // |deflection| at the period's start
  double residual_m_ = 0.0;
  double cruise_m_ = NAN;
  bool first_probe_ = true;
  long deferred_ = 0;
  double safe_margin_ = 0.0;
  std::size_t last_tick_ = 0;
  bool settled_ = false;
  bool tail_closed_ = false;
};

template <RunPhase P>
void SingleModeMaster::Tick(std::size_t k) {
  double inside = 0.0;
  const double end = m_.Advance(m_.s_.AccelAt(k)(m_.axis_), &inside);
  const double largest = std::max(std::max(start_abs_, end), inside);
  acc_.peak = std::max(acc_.peak, std::max(end, inside));
  const bool motion_end = k == window_.motion_ticks;
  if constexpr (P == RunPhase::kWindow) {
    acc_.residual = std::max(acc_.residual, motion_end ? end : std::max(end, inside));
  }
  if constexpr (P != RunPhase::kMotion) {
    // The last sample outside the settling band: the end's, else an inner one's.
    int last = end >= acc_.band ? m_.substeps_ - 1 : -1;
    if (last < 0 && largest >= acc_.band && !motion_end) {
      for (int j = m_.substeps_ - 2; j >= 0; --j) {
        if (std::abs(m_.Substep(j)) >= acc_.band) {
          last = j;
          break;
        }
      }
    }
    if (last >= 0) {
      acc_.last_outside_band = static_cast<long>((k - 1) * static_cast<std::size_t>(m_.substeps_)) + last + 1;
      acc_.quiet_since_tick = k;
    }
  }
  Contour(k, largest + kDeferredMargin * (largest + static_m_));
  start_abs_ = end;
}

// The largest squared contour error, from the substeps of the periods where the tool can
// leave the line (its ends: OffLineBound, deferred_substeps.h).
void SingleModeMaster::Contour(std::size_t k, double bound) {
  const CommandSamples& s = m_.s_;
  const bool commanded = k <= s.n;
  const double p0 = (commanded ? s.positions[k - 1] : s.positions.back())(m_.axis_);
  const double v0 = commanded ? s.velocity[k - 1](m_.axis_) : 0.0;
  const double half_a = 0.5 * s.AccelAt(k)(m_.axis_);
  // Most periods lie well inside the line: the command moves at most |v0| h + |a| h^2 / 2
  // from p0 (no division, unlike the vertex), the tool within `bound` of it. From a start
  // at 0 only (as OffLineBound: elsewhere a sample's distance is a rounding residue).
  const double reach = std::abs(v0) * m_.dt_ + std::abs(half_a) * m_.dt_ * m_.dt_ + bound;
  const double along = (p0 - m_.start_) * m_.direction_;
  if (m_.start_ == 0.0 && along - reach > safe_margin_ && along + reach < m_.length_ - safe_margin_) {
    ++deferred_;
    return;
  }
  double lo = 0.0;
  double hi = 0.0;
  QuadraticRange(p0, v0, half_a, m_.dt_, &lo, &hi);
  const double off_bound = OffLineBound(m_.start_, m_.direction_, m_.length_, lo - bound, hi + bound);
  if (off_bound == 0.0 || off_bound * off_bound < acc_.contour_sq) {
    ++deferred_;
    return;
  }
  for (int j = 0; j < m_.substeps_; ++j) {
    const double tau = m_.taus_[static_cast<std::size_t>(j)];
    const double actual = p0 + v0 * tau + half_a * tau * tau + m_.Substep(j);
    const double along = std::clamp((actual - m_.start_) * m_.direction_, 0.0, m_.length_);
    const double off = actual - (m_.start_ + along * m_.direction_);
    acc_.contour_sq = std::max(acc_.contour_sq, off * off);
  }
}

// At the residual window's end: the settling tail in closed form (cosim.cc's SettleTail
// with the one pole pair); false when the simulated tail must decide.
bool SingleModeMaster::SettleTail(std::size_t k) {
  if (window_.never_settles_late || k != window_.window_end()) return false;
  const model::FreeTerms free = m_.Free();
  constexpr double kMargin = 1.0 + 1e-9;
  const double envelope = free.Envelope(0.0);
  if (!(envelope * kMargin <= acc_.peak) || !(envelope * envelope * kMargin <= acc_.contour_sq)) return false;
  const double crossing = model::LastBandCrossing(free, acc_.band);
  if (std::isnan(crossing)) return false;
  const int substeps = m_.substeps_;
  long last_outside = acc_.last_outside_band;
  std::size_t quiet = acc_.quiet_since_tick;
  const long from = crossing >= 0.0 ? static_cast<long>(std::floor(crossing * substeps / m_.dt_)) + 1 : 0;
  for (long j = from; j >= 1; --j) {
    if (std::abs(free.At(m_.dt_ * static_cast<double>(j) / substeps)) >= acc_.band) {
      last_outside = static_cast<long>(k) * substeps + j;
      quiet = static_cast<std::size_t>((last_outside - 1) / substeps + 1);
      break;
    }
  }
  const std::size_t stop = quiet + window_.period_ticks;
  acc_.last_outside_band = last_outside;
  acc_.quiet_since_tick = quiet;
  settled_ = stop <= window_.max_ticks;
  last_tick_ = std::min(stop, window_.max_ticks);
  tail_closed_ = true;
  return true;
}

void SingleModeMaster::Run(RunResult* result) {
  const std::size_t motion = window_.motion_ticks;
  for (std::size_t k = 1; k <= window_.max_ticks; ++k) {
    last_tick_ = k;
    if (k < motion) {
      Tick<RunPhase::kMotion>(k);
      if (next_probe_ != window_.cruise_probe_ticks.end() && k == *next_probe_) {
        ++next_probe_;
        const double amplitude = m_.ModalAmplitude();
        if (first_probe_ || amplitude > cruise_m_) cruise_m_ = amplitude;
        first_probe_ = false;
      }
      continue;
    }
    if (k <= window_.window_end()) {
      Tick<RunPhase::kWindow>(k);
      if (k == motion) residual_m_ = m_.ModalAmplitude();
    } else {
      Tick<RunPhase::kTail>(k);
    }
    bool settled = false;
    if (window_.Done(k, acc_.quiet_since_tick, &settled)) {
      settled_ = settled;
      break;
    }
    if (SettleTail(k)) break;
  }
  const double dt = m_.dt_;
  const int substeps = m_.substeps_;
  Metrics& m = result->metrics;
  m.motion_time_s = static_cast<double>(motion) * dt;
  if (settled_) {
    m.settling_time_s = acc_.last_outside_band < 0 ? 0.0
                                                   : dt * static_cast<double>(acc_.last_outside_band) / substeps +
                                                         dt / substeps - m.motion_time_s;
  }
  m.peak_deflection_m = acc_.peak;
  m.peak_ratio = acc_.peak / static_m_;
  m.residual_amplitude_m = residual_m_;
  m.residual_ratio = residual_m_ / static_m_;
  m.residual_peak_m = acc_.residual;
  m.residual_peak_ratio = acc_.residual / static_m_;
  m.cruise_residual_ratio = cruise_m_ / static_m_;
  m.max_contour_error_m = std::sqrt(acc_.contour_sq);
  result->simulated_s = static_cast<double>(last_tick_) * dt;
  result->tail_in_closed_form = tail_closed_;
  result->deferred_periods = deferred_;
  result->stats.steps = static_cast<long>(last_tick_) * substeps;
  result->substeps = substeps;
}

}  // namespace

bool SingleModeQualifies(const Scenario& scenario, const controller::PathGeometry& path) {
  if (scenario.drive.type != model::DriveType::kKinematic ||
      scenario.integrator.method == model::IntegratorMethod::kCvode) {
    return false;
  }
  for (const auto& limits : scenario.machine.stroke_m) {
    if (limits.has_value()) return false;
  }
  int axis = -1;
  for (int a = 0; a < model::kNumAxes && path.elements().size() == 1; ++a) {
    if (path.elements().front().direction(a) != 0.0) axis = a;
  }
  if (axis < 0 || ViewAxis(scenario, axis) != axis || OnlyLine(path, axis) == nullptr) return false;
  const model::ModalMode* mode = OnlyMode(scenario, axis);
  if (mode == nullptr || !(mode->gain != 0.0) || !(mode->damping_ratio < 1.0) || !(mode->frequency_hz > 0.0)) {
    return false;
  }
  // At most one stationary point a period (model/tick_extremum.h's grid of one).
  const double wd = 2.0 * kPi * mode->frequency_hz * std::sqrt(1.0 - mode->damping_ratio * mode->damping_ratio);
  return wd * scenario.controller.period_s <= 0.5 * kPi;
}

bool RunSingleMode(const Scenario& scenario, const controller::MultiAxisCommand& command,
                   const CommandSamples& samples, const controller::PathGeometry& path, RunResult* result) {
  // The general path validates them building the plant: the same errors here.
  scenario.machine.validate();
  scenario.drive.validate();
  if (!SingleModeQualifies(scenario, path)) return false;
  const OutputView view = MakeOutputView(scenario.output, samples.axis_moves);
  const controller::PathElement& line = path.elements().front();
  const int axis = view.axis;
  if (axis < 0 || OnlyLine(path, axis) != &line) return false;
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (a != axis && (samples.axis_moves[a] || samples.positions.front()(a) != line.start_m(a))) return false;
  }
  const double dt = command.period_s;
  const model::MachineDynamics dynamics = model::AnalyzeMachine(scenario.machine);
  const RunWindow window = PlanRunWindow(scenario, samples, dynamics, dt);
  const int substeps = scenario.integrator.output_substeps > 0 ? scenario.integrator.output_substeps
                                                               : AutoSubsteps(dynamics, dt);
  const model::ModalMode& mode = *OnlyMode(scenario, axis);
  SingleModeKernel kernel(mode, line, axis, samples, dt, substeps);
  // The static displacement: the largest held acceleration's (cosim.cc StaticDisplacement).
  double static_m = 0.0;
  for (const std::size_t k : samples.accel_changes) {
    static_m = std::max(static_m, std::abs(kernel.StaticGain() * samples.accel[k](axis)));
  }
  Metrics& m = result->metrics;
  m.static_displacement_m = static_m;
  m.static_displacement_x_m = axis == 0 ? static_m : 0.0;
  m.static_displacement_y_m = axis == 1 ? static_m : 0.0;
  m.static_displacement_z_m = axis == 2 ? static_m : 0.0;
  SingleModeMaster master(&kernel, window, static_m);
  master.Run(result);
  m.peak_deflection_x_m = axis == 0 ? m.peak_deflection_m : 0.0;
  m.peak_deflection_y_m = axis == 1 ? m.peak_deflection_m : 0.0;
  m.peak_deflection_z_m = axis == 2 ? m.peak_deflection_m : 0.0;
  m.short_block_clamps = command.short_block_clamps;
  m.stroke_overshoot_m = 0.0;
  m.stroke_alarm = command.stroke_alarm ? 1.0 : 0.0;
  SetPatternMetrics(scenario.controller.pattern, &m);
  result->residual_modes = {{mode.frequency_hz, mode.damping_ratio, m.residual_amplitude_m}};
  return true;
}

}  // namespace shapebench::bench
