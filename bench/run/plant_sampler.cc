#include "bench/run/plant_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "bench/run/cross_check_family.h"
#include "bench/run/finish_metrics.h"
#include "bench/run/run_work.h"
#include "common/format.h"
#include "model/cvode_cross_check.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench {
namespace {

// The machine a nonlinear run integrates: an axis the command never moves starts at rest
// and is never driven, so its structure, its servo and its elements stay exactly at rest
// (every element's force is 0 there): it is left out like a rigid axis, whose outputs are
// the same exact zeros. A third fewer states on an XY program of a three-axis machine.
model::MachinePlant IdleAxesRigid(const Scenario& scenario, const CommandSamples& samples) {
  model::MultiAxisMachineConfig machine = scenario.machine;
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    bool idle = true;
    for (std::size_t k = 0; k <= samples.n && idle; ++k) {
      idle = samples.accel[k](axis) == 0.0 && samples.velocity[k](axis) == 0.0;
    }
    // Coupled modes sit at the driven axis but answer every axis: never left out.
    if (idle && machine.CoupledModes() == nullptr) machine.axes[axis].reset();
  }
  return model::BuildMachinePlant(machine, scenario.drive);
}

}  // namespace

PlantSampler::PlantSampler(const RunPlan& plan, SamplerKind fastest, RunResult* result)
    : plan_(plan),
      samples_(plan.samples),
      window_(plan.window),
      result_(*result),
      dt_(plan.dt_s),
      substeps_(plan.substeps),
      contour_gauge_(plan.path, plan.command.path_position_m, plan.dt_s, ContourLag(plan.command, plan.scenario.drive)),
      machine_(model::BuildMachinePlant(plan.scenario.machine, plan.scenario.drive)),
      integrator_config_(plan.scenario.integrator) {
  nonlinear_ = !machine_.nonlinear.empty();
  for (const controller::PathElement& e : plan.path.elements()) {
    if (e.is_arc()) arcs_.push_back({&e, 0.0, 0});
    if (e.is_arc() && nonlinear_) glitches_.emplace_back(e);
  }
  result_.substeps = substeps_;
  if (plan.scenario.fmu) {
    SetUpFmu();
  } else {
    SetStaticReference(plan, machine_.static_gain, &tally_);
    SetUpPlant();
  }
  SetUpSampling(fastest);
  result_.sampler = kind_;
  if (!window_.cruise_probe_ticks.empty()) next_probe_tick_ = window_.cruise_probe_ticks.front();
  if (window_.motion_ticks == 0) ProbeMotionEnd();  // no motion: the state at rest
}

void PlantSampler::SetUpPlant() {
  if (nonlinear_) integrated_ = IdleAxesRigid(plan_.scenario, samples_);
  const model::LinearPlant& plant = nonlinear_ ? integrated_.plant : machine_.plant;
  if (plant.num_states() > 0) {
    const double scale_accel = std::max(samples_.max_accel_m_s2, 1e-12);
    CrossCheckCvode(plant, scale_accel);
    if (nonlinear_) {
      // CVODE with events; its free response is read sample by sample (TrackFreeResponse).
      integrator_ = model::MakePlantIntegrator({plant, integrated_.nonlinear, integrated_.following_error_axis}, integrator_config_, dt_, substeps_,
                                               scale_accel, samples_.max_speed_m_s);
    } else {
      integrator_ = model::MakeIntegrator(plant, integrator_config_, dt_, substeps_, scale_accel,
                                          samples_.max_speed_m_s);
      residual_vibration_ = std::make_unique<ResidualVibration>(plant, plan_.view);
      // The peaks of the view's axis exactly (one sign change of its rate a period, closed
      // form per mode: model/tick_extremum.h), not only at the substeps.
      const model::IntegratorCapabilities caps = integrator_->Capabilities();
      if (plan_.view.axis >= 0 && caps.period_extremum) {
        exact_extrema_ = integrator_->WatchExtremum(model::kDeflectionRow + plan_.view.axis);
      }
      // The trace shows the tail: simulated then. CVODE's tail too is found in closed form
      // from its state at the residual window's end (its peak sampled, not exact): a damped
      // sweep's points spent about 40% of their steps simulating it (docs/performance.md).
      const bool cvode = model::ResolveMethod(integrator_config_.method, plant) == model::IntegratorMethod::kCvode;
      if ((exact_extrema_ ? caps.advance_at_rest : cvode && plan_.view.axis >= 0) && !plan_.record_trace &&
          !window_.never_settles_late && plant.num_outputs() == model::kNumOutputRows) {
        damped_tail_ = std::make_unique<DampedTail>(plant, plan_.view);
      }
    }
    if (nonlinear_ || model::ResolveMethod(integrator_config_.method, plant) == model::IntegratorMethod::kCvode) {
      result_.integrator_rtol_used = integrator_config_.rtol;
      work_stride_ = 1;
    }
    integrator_->Reset(Eigen::VectorXd::Zero(plant.num_inputs()));
    holds_ = integrator_->Capabilities().input_holds;
    CheckEstimatedWork(plan_, integrator_->PeriodWorkAtLeast());  // the extremum's grid known now
  }
  rows_ = plant.num_outputs();
  width_ = rows_;
  outputs_.assign(static_cast<std::size_t>(substeps_) * std::max(rows_, model::kNumOutputRows), 0.0);
}

// CVODE on a linear plant is checked against the exact discretisation once per distinct
// plant and settings (model/cvode_cross_check.h): beyond the documented accuracy the run is
// refused, or warned about. A default rtol (not in the scenario) is first tightened by
// decades down to kTightestRtol until the check passes: the patent's exponential acc/dec
// at a 0.1 ms period needs 1e-9 (issue 32 item 11); a tolerance the user wrote is kept.
void PlantSampler::CrossCheckCvode(const model::LinearPlant& plant, double scale_accel) {
  model::IntegratorConfig& config = integrator_config_;
  // A plant with nonlinear elements runs on CVODE whatever auto says; its linear part is
  // checked through the same integrator (docs/nonlinear.md).
  const model::CheckedIntegrator checked =
      nonlinear_ ? model::CheckedIntegrator::kNonlinear : model::CheckedIntegrator::kLinear;
  if (config.cross_check == model::CrossCheckPolicy::kOff ||
      (!nonlinear_ && model::ResolveMethod(config.method, plant) != model::IntegratorMethod::kCvode)) {
    return;
  }
  model::CheckMethodFitsPlant(config.method, integrated_.nonlinear);
  // The metrics are read up to the end of the residual window.
  const double run_s = static_cast<double>(window_.window_end()) * dt_;
  const double first_rtol = config.rtol;
  // A sweep's family of plants (cross_check_family.h): one check covers its points with a
  // margin; a point it does not cover is checked alone below, as every point was before.
  if (!nonlinear_ && FamilyCoversRun(plan_.scenario, plant, config, dt_,
                                     samples_.max_speed_m_s / scale_accel, run_s)) {
    return;
  }
  model::CrossCheckResult check = model::CachedCrossCheckCvode(
      plant, config, dt_, substeps_, scale_accel, samples_.max_speed_m_s, checked);
  while (!config.rtol_given && !check.Passed(run_s) && check.solver_failure.empty() &&
         config.rtol / 10.0 >= model::kTightestRtol * (1.0 - 1e-9)) {
    config.rtol /= 10.0;
    check = model::CachedCrossCheckCvode(plant, config, dt_, substeps_, scale_accel, samples_.max_speed_m_s, checked);
  }
  if (check.Passed(run_s)) return;
  std::string message = model::CrossCheckMessage(check, config, run_s, checked);
  if (config.rtol < first_rtol) {
    message += " (integrator.rtol was not set: the default " + FormatNumber(first_rtol) +
               " was tightened by decades to " + FormatNumber(config.rtol) + ", the tightest allowed)";
  }
  if (!check.solver_failure.empty()) {
    // The run's own CVODE failure, if it has one, is the better report: it comes first.
    unchecked_ = std::move(message);
  } else if (config.cross_check == model::CrossCheckPolicy::kRefuse) {
    throw model::SolverError("CROSS_CHECK_FAILED", message);
  } else {
    result_.warnings.push_back(std::move(message));
  }
}

void PlantSampler::SetUpSampling(SamplerKind fastest) {
  if (plan_.record_trace) {
    StartTrace();
    return;
  }
  if (fastest == SamplerKind::kGeneral || fmu_ != nullptr) return;
  SetUpSingleAxis();
  if (single_.axis < 0 || rows_ != model::kNumOutputRows) return;
  kind_ = SamplerKind::kSingleAxis;
  if (fastest != SamplerKind::kSingleAxis && QualifiesForDeferredSubsteps()) kind_ = SamplerKind::kDeferredSubsteps;
}

// For how many periods from tick k on the held acceleration stays a_k (the tail's is
// zero): an integrator that can (CVODE) integrates across those ticks (AdvancePeriod).
long PlantSampler::SameInput(std::size_t k) {
  if (!holds_) return 1;
  if (k >= next_change_) {
    const Eigen::Vector3d& here = samples_.AccelAt(k);
    next_change_ = k + 1;
    while (next_change_ <= window_.max_ticks) {
      const Eigen::Vector3d& next = samples_.AccelAt(next_change_);
      if (next(0) != here(0) || next(1) != here(1) || next(2) != here(2)) break;
      ++next_change_;
    }
  }
  return static_cast<long>(next_change_ - k);
}

// Every output of period k finite, else the run fails (a degenerate model: never reported
// as numbers), at the first substep that is not.
void PlantSampler::CheckFinite(std::size_t k) const {
  for (int i = 0; i < substeps_ * width_; ++i) {
    if (!std::isfinite(outputs_[i])) {
      const long count = static_cast<long>((k - 1) * substeps_) + i / width_ + 1;
      throw model::SolverError("NON_FINITE_STATE",
                               "the plant's deflection became non-finite at t = " +
                                   std::to_string(dt_ * static_cast<double>(count) / substeps_) +
                                   " s (a degenerate model)");
    }
  }
}

bool PlantSampler::StepPlant(std::size_t k) {
  bool others_zero = single_.axis >= 0 && rows_ == model::kNumOutputRows;
  if (!integrator_) return others_zero;
  integrator_->AdvancePeriod(samples_.AccelAt(k).data(), SameInput(k), outputs_.data());
  if (others_zero && !watched_rows_.empty()) {
    // Branch-free: the other rows' bits all zero (rows the integrator guarantees 0 are
    // not even looked at). Anything else (-0.0 included) takes the general samples.
    std::uint64_t other_bits = 0;
    for (int j = 0; j < substeps_; ++j) {
      const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
      for (int r : watched_rows_) {
        std::uint64_t bits;
        std::memcpy(&bits, out + r, sizeof bits);
        other_bits |= bits;
      }
    }
    others_zero = other_bits == 0;
  }
  // The single-axis samples check their own values' finiteness.
  if (!others_zero) CheckFinite(k);
  return others_zero;
}

std::size_t PlantSampler::Tick(std::size_t k) {
  if (kind_ == SamplerKind::kDeferredSubsteps) {
    if (k < window_.motion_ticks) {
      DeferredTick<RunPhase::kMotion>(k);
    } else if (k <= window_.window_end()) {
      DeferredTick<RunPhase::kWindow>(k);
    } else {
      DeferredTick<RunPhase::kTail>(k);
    }
    Probes(k);
    return k;
  }
  const bool others_zero = StepPlant(k);
  if (k < window_.motion_ticks) {
    SampleTick<RunPhase::kMotion>(k, others_zero);
  } else if (k <= window_.window_end()) {
    SampleTick<RunPhase::kWindow>(k, others_zero);
  } else {
    SampleTick<RunPhase::kTail>(k, others_zero);
  }
  Probes(k);
  if (nonlinear_ && k >= window_.motion_ticks) TrackFreeResponse(k, others_zero);
  return k;
}

// The free vibration read at the cruise probes and at motion end, from the state at t_k.
void PlantSampler::Probes(std::size_t k) {
  if (k == next_probe_tick_ && k < window_.motion_ticks) ProbeCruise(k);
  if (k == window_.motion_ticks) ProbeMotionEnd();
}

// A nonlinear plant's deflection in the view from the end of motion on (at the motion-end
// tick only its last sample, as the residual window counts it).
void PlantSampler::TrackFreeResponse(std::size_t k, bool others_zero) {
  const int first = k == window_.motion_ticks ? substeps_ - 1 : 0;
  for (int j = first; j < substeps_; ++j) {
    if (others_zero) {
      free_.Add(outputs_[static_cast<std::size_t>(j * width_ + deflection_at_)]);
    } else {
      const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
      free_.Add(plan_.view.Of(Eigen::Vector3d(out[model::kDeflectionRow], out[model::kDeflectionRow + 1],
                                         out[model::kDeflectionRow + 2])));
    }
  }
}

template <RunPhase P>
void PlantSampler::SampleTick(std::size_t k, bool others_zero) {
  // Two accumulators, so that the single-axis one never has its address taken by the
  // general samples (an out-of-line call): it then stays in registers.
  TickTally tick = tally_.StartTick(P, k, window_.motion_ticks, substeps_);
  if (others_zero) {
    SampleSingleAxis<P>(k, &tick);
  } else {
    TickTally general = tick;
    SampleGeneral<P>(k, &general);
    tick = general;
  }
  if (exact_extrema_) {
    // An extremum inside the period (its ends are samples); at the motion-end tick it is
    // the motion's (only that tick's last sample counts as after the motion).
    const double inside = integrator_->PeriodExtremum();
    tick.peak = std::max(tick.peak, inside);
    if constexpr (P == RunPhase::kWindow) {
      if (k != window_.motion_ticks) tick.residual = std::max(tick.residual, inside);
    }
  }
  tally_.Merge(tick, k, substeps_);
}

bool PlantSampler::SettleTail(std::size_t k) {
  if (!damped_tail_ || k != window_.window_end() || !damped_tail_->Split(integrator_->PlantState())) return false;
  // The tail adds nothing to the peaks or the contour error (the path's end is the command's
  // last position): every row's envelope within what the run has already seen, with a
  // margin for rounding.
  constexpr double kMargin = 1.0 + 1e-9;
  double tool_error_sq = 0.0;
  for (int b = 0; b < model::kNumAxes; ++b) {
    const double seen = b == plan_.view.axis ? std::max(tally_.peak, peak_axes_(b)) : peak_axes_(b);
    if (!(damped_tail_->Envelope(model::kDeflectionRow + b) * kMargin <= seen)) return false;
    tool_error_sq += std::pow(damped_tail_->Envelope(model::kToolErrorRow + b), 2);
  }
  if (!(tool_error_sq * kMargin <= tally_.contour_sq)) return false;
  const double crossing = damped_tail_->LastCrossing(tally_.band);
  if (std::isnan(crossing)) return false;
  // The last sample on the run's grid (dt / substeps) at or before the crossing outside
  // the band: settling_time_s as the simulated tail had it.
  long last_outside = tally_.last_outside_band;
  std::size_t quiet = tally_.quiet_since_tick;
  const long from = crossing >= 0.0 ? static_cast<long>(std::floor(crossing * substeps_ / dt_)) + 1 : 0;
  for (long j = from; j >= 1; --j) {
    if (std::abs(damped_tail_->ViewAt(dt_ * static_cast<double>(j) / substeps_)) >= tally_.band) {
      last_outside = static_cast<long>(k) * substeps_ + j;
      quiet = static_cast<std::size_t>((last_outside - 1) / substeps_ + 1);
      break;
    }
  }
  const std::size_t stop = quiet + window_.period_ticks;  // > k: Done(k) was false
  const std::size_t end = std::min(stop, window_.max_ticks);
  if (end < k) return false;
  // CVODE is not advanced: nothing reads its state after the tail (its stats stop here).
  if (integrator_->Capabilities().advance_at_rest) integrator_->AdvanceAtRest(static_cast<long>(end - k));
  tally_.last_outside_band = last_outside;
  tally_.quiet_since_tick = quiet;
  tally_.settled = stop <= window_.max_ticks;
  tally_.last_tick = end;
  result_.tail_in_closed_form = true;
  return true;
}

// The free vibration at motion end (the acceleration 0 from here on: equilibrium 0), per
// pole into the result, their sum into residual_amplitude_m.
void PlantSampler::ProbeMotionEnd() {
  if (fmu_ != nullptr) tally_.residual_m = FmuResidual();
  if (!residual_vibration_) return;
  result_.residual_modes = residual_vibration_->Amplitudes(integrator_->PlantState(), Eigen::Vector3d::Zero());
  tally_.residual_m = ResidualVibration::Total(result_.residual_modes);
  if (std::isnan(tally_.residual_m)) {
    result_.warnings.push_back(
        "the plant's state does not split into its modes (a critically damped pole?): residual_ratio is n/a");
  }
}

// Cruise probe k: the vibration about the equilibrium at the cruise velocity v_k.
void PlantSampler::ProbeCruise(std::size_t k) {
  ++next_probe_;
  next_probe_tick_ = next_probe_ < window_.cruise_probe_ticks.size() ? window_.cruise_probe_ticks[next_probe_]
                                                                      : std::numeric_limits<std::size_t>::max();
  // A nonlinear plant's state does not split into modes: no cruise amplitude (n/a).
  const double amplitude =
      residual_vibration_ ? ResidualVibration::Total(residual_vibration_->Amplitudes(
                                integrator_->PlantState(), samples_.velocity[k]))
      : fmu_ != nullptr   ? FmuResidual()
      : nonlinear_        ? NAN
                          : 0.0;
  // The largest; a failed split (NaN) stays.
  if (next_probe_ == 1 || std::isnan(amplitude) || amplitude > tally_.cruise_m) {
    tally_.cruise_m = amplitude;
    tally_.sources.cruise = k;
  }
}

// What the tally takes from the sampler's own state at the run's end.
void PlantSampler::Conclude() {
  Eigen::Vector3d peak_axes = peak_axes_;
  if (single_.axis >= 0) peak_axes(single_.axis) = std::max(peak_axes(single_.axis), tally_.peak);
  // The view's axis: its peak found inside the periods too (|deflection| of that axis).
  if (exact_extrema_) peak_axes(plan_.view.axis) = std::max(peak_axes(plan_.view.axis), tally_.peak);
  tally_.peak_axes = peak_axes;
  tally_.overshoot_m = overshoot_;
  tally_.sources.stepped = true;  // every tick went through Merge
  for (const ArcWindow& w : arcs_) {
    if (w.samples == 0) continue;
    const double programmed = 0.5 * (w.arc->start_radius_m + w.arc->end_radius_m);
    const double error = programmed - w.sum_radius_m / static_cast<double>(w.samples);
    if (std::isnan(tally_.radial_error_m) || std::abs(error) > std::abs(tally_.radial_error_m)) {
      tally_.radial_error_m = error;
    }
  }
  tally_.nonlinear = nonlinear_;
  if (free_.any) {
    tally_.free_half_range_m = 0.5 * (free_.max - free_.min);
    tally_.dead_band_m = std::abs(free_.last);
  }
  for (const ReversalWindows& g : glitches_) {
    const double glitch = g.Glitch();
    if (!std::isnan(glitch) && !(glitch <= tally_.quadrant_glitch_m)) tally_.quadrant_glitch_m = glitch;
  }
}

std::size_t PlantSampler::CheckWork(std::size_t k) const {
  if (!integrator_) {
    bench::CheckWork(plan_, k, 0, {});
    return 1024;
  }
  bench::CheckWork(plan_, k, integrator_->Work(), work_stride_ == 1 ? kCvodeWork : kExtremumWork);
  return work_stride_;
}

MetricTally PlantSampler::Run() {
  RunTicks(*this, window_, &tally_);
  Conclude();
  if (integrator_) result_.stats = integrator_->Stats();
  result_.work = RunWork(plan_, tally_.last_tick, integrator_ ? integrator_->Work() : 0);
  if (!unchecked_.empty()) {
    if (plan_.scenario.integrator.cross_check == model::CrossCheckPolicy::kRefuse) {
      throw model::SolverError("CROSS_CHECK_FAILED", unchecked_);
    }
    result_.warnings.push_back(unchecked_);
  }
  return tally_;
}

}  // namespace shapebench::bench
