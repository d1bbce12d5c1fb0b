#include "bench/run/closed_form_sampler.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "bench/run/deferred_substeps.h"
#include "bench/run/run_work.h"
#include "bench/run/finish_metrics.h"
#include "common/math_constants.h"
#include "model/band_crossing.h"
#include "model/free_response.h"
#include "model/machine.h"

namespace shapebench::bench {
namespace {

// What a substep's deflection can exceed the period's bound by: its rounding (a few
// operations on values of the run's scale, ~1e-15 of it) with a thousandfold margin. (The
// general path's 1e-9, deferred_substeps.h, would keep a quiet residual window sampled:
// a contour error of rounding size, 1e-15 m, stays below a margin of 1e-13 m.)
constexpr double kSampleMargin = 1e-12;

// q' changed sign over the period: a stationary point lies inside it.
bool SignChanged(double v0, double v1) { return (v0 > 0.0 && v1 < 0.0) || (v0 < 0.0 && v1 > 0.0); }

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
    const double w = 2.0 * kPi * mode.frequency_hz;
    w2_ = w * w;
    sigma_ = mode.damping_ratio * w;
    wd_ = w * std::sqrt(1.0 - mode.damping_ratio * mode.damping_ratio);
    gain_ = mode.gain;
    cap_ = model::ResidualCap(mode.damping_ratio);
    start_ = line.start_m(axis);
    direction_ = line.direction(axis);
    length_ = line.length_m;
    period_ = At(dt);
    g_q_ = -(1.0 - period_.xx) / w2_;
    g_v_ = period_.vx / w2_;
    twice_ = At(2.0 * dt);
    h_q_ = period_.xx * g_q_ + period_.xv * g_v_;  // phi gamma: a held over the first of two
    h_v_ = period_.vx * g_q_ + period_.vv * g_v_;
    inner_.resize(static_cast<std::size_t>(substeps));
    taus_.resize(static_cast<std::size_t>(substeps));
    for (int j = 1; j <= substeps; ++j) {
      taus_[j - 1] = dt * static_cast<double>(j) / substeps;
      inner_[j - 1] = At(taus_[j - 1]);
    }
  }

  // Of the free vibration about q = 0 (a = 0): the envelope, capped at ResidualCap(zeta)
  // times the free response's largest |value| (model/free_response.h, CappedResidual).
  double ModalAmplitude() const {
    const double envelope = std::abs(gain_) * std::hypot(q_, (v_ + sigma_ * q_) / wd_);
    return model::CappedResidual(envelope, std::abs(gain_) * model::PairPeak(q_, v_, sigma_, wd_), cap_);
  }
  double StaticGain() const { return -gain_ / w2_; }  // deflection per m/s^2
  // |deflection| never exceeds this from rest under accelerations of the given sum of
  // |a| dt (m/s): |impulse response| <= 1 / w_d.
  double DeflectionBound(double accel_l1_m_s) const { return std::abs(gain_) / wd_ * accel_l1_m_s; }

  // Period k under the held a: the state to its end, as the floor benchmark steps it;
  // returns |deflection| at the end. *inside: the largest |deflection| at a stationary
  // point inside the period, computed only where it can exceed `needed` (the metrics it
  // could raise), else 0; *within: a bound of |deflection| inside the period (the extremum
  // where computed, else ExtremumBound; 0 without a stationary point).
  double Advance(double a, double needed, double* inside, double* within) {
    const double q1 = period_.xx * q_ + period_.xv * v_ + g_q_ * a;
    const double v1 = period_.vx * q_ + period_.vv * v_ + g_v_ * a;
    q0_ = q_;
    v0_ = v_;
    a_ = a;
    q_ = q1;
    v_ = v1;
    *inside = 0.0;
    *within = 0.0;
    if (SignChanged(v0_, v1)) {
      *within = ExtremumBound(q0_, v0_, a);
      if (!(*within < needed)) *inside = *within = Extremum(q0_, v0_, a);
    }
    return std::abs(gain_ * q1);
  }
  // Periods [from, to) of the motion in which only the peak can change (the tool stays
  // inside the line, no cruise probe): Advance's arithmetic with the state in registers,
  // the floor's loop. Returns the peak so far; *end_abs the last period's |deflection|.
  double AdvancePeaks(std::size_t from, std::size_t to, double peak, double* end_abs) {
    const double* accel = s_.accel.front().data() + axis_;  // Vector3d: 3 doubles, packed
    double q = q_;
    double v = v_;
    std::size_t k = from;
    // Two periods a step: the state two periods on straight from (q, v) through the
    // two-period transition, the one between off that chain: the chain of dependent
    // products (the loop's latency) is half as long a period.
    for (; k + 1 < to; k += 2) {
      const double a0 = accel[3 * k];
      const double a1 = accel[3 * k + 3];
      const double qm = period_.xx * q + period_.xv * v + g_q_ * a0;
      const double vm = period_.vx * q + period_.vv * v + g_v_ * a0;
      const double q2 = (twice_.xx * q + twice_.xv * v) + (h_q_ * a0 + g_q_ * a1);
      const double v2 = (twice_.vx * q + twice_.vv * v) + (h_v_ * a0 + g_v_ * a1);
      peak = Turning(q, v, a0, vm, peak);
      peak = Turning(qm, vm, a1, v2, peak);
      peak = std::max(peak, std::max(std::abs(gain_ * qm), std::abs(gain_ * q2)));
      q = q2;
      v = v2;
    }
    double q0 = q, v0 = v, a = 0.0;
    for (; k < to; ++k) {
      q0 = q;
      v0 = v;
      a = accel[3 * k];
      q = period_.xx * q0 + period_.xv * v0 + g_q_ * a;
      v = period_.vx * q0 + period_.vv * v0 + g_v_ * a;
      peak = std::max(Turning(q0, v0, a, v, peak), std::abs(gain_ * q));
    }
    q_ = q;
    v_ = v;
    q0_ = q0;
    v0_ = v0;
    a_ = a;
    *end_abs = std::abs(gain_ * q);
    return peak;
  }
  // The peak after a period from (q0, v0) under a that ends at rate v1: its stationary
  // point's |deflection| where q' changed sign and it can exceed the peak.
  double Turning(double q0, double v0, double a, double v1, double peak) const {
    if (SignChanged(v0, v1) && !(ExtremumBound(q0, v0, a) < peak)) {
      return std::max(peak, Extremum(q0, v0, a));
    }
    return peak;
  }
  // The deflection at substep j (0-based) of the period Advance stepped last.
  double Substep(int j) const {
    const Transition& t = inner_[static_cast<std::size_t>(j)];
    const double q_eq = -a_ / w2_;
    return gain_ * (t.xx * (q0_ - q_eq) + t.xv * v0_ + q_eq);
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
    return {e * (c + sigma_ / wd_ * sn), e * sn / wd_, -e * w2_ / wd_ * sn, e * (c - sigma_ / wd_ * sn)};
  }
  // |deflection| within the period starting at (q0, v0) under a: the free oscillation's
  // amplitude about the equilibrium (which decays) plus the equilibrium's distance from 0,
  // with a margin for the rounding of both (1e-12: a bound, not a value).
  double ExtremumBound(double q0, double v0, double a) const {
    const double q_eq = -a / w2_;
    const double x0 = q0 - q_eq;
    const double b = (v0 + sigma_ * x0) / wd_;
    return std::abs(gain_) * (std::sqrt(x0 * x0 + b * b) + std::abs(q_eq)) * (1.0 + 1e-12);
  }
  // The period's stationary point (q' changed sign). About the equilibrium, x0 = q0 + a /
  // w^2; undamped, the extremum is the free oscillation's amplitude sqrt(x0^2 + (v0 /
  // w)^2), a maximum where v0 > 0; damped, it lies where q' = e^{-sigma t} (v0 cos(w_d t) -
  // ((sigma v0 + w^2 x0) / w_d) sin(w_d t)) vanishes: w_d t = atan2(w_d v0, sigma v0 + w^2
  // x0) (mod pi). Out of line: rare (twice a natural period), and the loops stay small.
  [[gnu::noinline]] double Extremum(double q0, double v0, double a) const {
    const double q_eq = -a / w2_;
    const double x0 = q0 - q_eq;
    double x = 0.0;
    if (sigma_ == 0.0) {
      x = std::copysign(std::sqrt(x0 * x0 + v0 * v0 / w2_), v0);
    } else {
      double t = std::fmod(std::atan2(wd_ * v0, sigma_ * v0 + w2_ * x0), kPi) / wd_;
      if (t < 0.0) t += kPi / wd_;
      if (!(t > 0.0 && t < dt_)) return 0.0;  // rounding at an end: the ends are samples
      x = std::exp(-sigma_ * t) * (x0 * std::cos(wd_ * t) + (v0 + sigma_ * x0) / wd_ * std::sin(wd_ * t));
    }
    return std::abs(gain_ * (x + q_eq));
  }

  double w2_ = 0.0, sigma_ = 0.0, wd_ = 0.0, gain_ = 1.0, cap_ = 1.0;
  Transition period_;
  double g_q_ = 0.0, g_v_ = 0.0;  // the period's response to a held a = 1 from rest
  Transition twice_;               // over two periods
  double h_q_ = 0.0, h_v_ = 0.0;  // two periods on, of a = 1 held over the first
  std::vector<Transition> inner_;
  double q_ = 0.0, v_ = 0.0;              // the state at the last period's end
  double q0_ = 0.0, v0_ = 0.0, a_ = 0.0;  // the last period's start and input
};

// The sampler: the kernel through the run's ticks, its tally as the plant samplers keep it
// (plant_sampler.cc: SampleTick, DeferredTick, SettleTail).
class ClosedFormSampler final : public Sampler {
 public:
  ClosedFormSampler(const RunPlan& plan, RunResult* result)
      : plan_(plan),
        result_(*result),
        kernel_(*plan.single_mode.mode, *plan.single_mode.line, plan.single_mode.axis, plan.samples, plan.dt_s,
                plan.substeps),
        window_(plan.window) {
    Eigen::Matrix3d static_gain = Eigen::Matrix3d::Zero();
    static_gain(kernel_.axis_, kernel_.axis_) = kernel_.StaticGain();
    SetStaticReference(plan, static_gain, &tally_);
    static_m_ = tally_.static_m;
    contour_floor_ = 1e-12 * static_m_;
    next_probe_ = window_.cruise_probe_ticks.begin();
    const CommandSamples& s = kernel_.s_;
    const double end = s.positions.back()(kernel_.axis_);
    // OffLineBound's rounding term, at its largest over the run's positions (within the
    // line's ends and the largest deflection, which the reach bounds).
    const double largest = std::abs(kernel_.start_) + kernel_.length_ +
                           kernel_.DeflectionBound(s.accel_l1_m_s[kernel_.axis_]) + s.max_speed_m_s * kernel_.dt_ +
                           s.max_accel_m_s2 * kernel_.dt_ * kernel_.dt_;
    rounding_ = 8.0 * std::numeric_limits<double>::epsilon() *
                (std::abs(kernel_.start_) + largest + kernel_.length_) * 2.0;
    end_off_ = std::abs((end - kernel_.start_) * kernel_.direction_ - kernel_.length_) + rounding_;
    FindInnerTicks();
  }

  MetricTally Run() override;
  std::size_t Tick(std::size_t k);
  bool SettleTail(std::size_t k);
  // limits.max_work (run_work.h): output samples only; a tick costs a few of them.
  std::size_t CheckWork(std::size_t k) const {
    bench::CheckWork(plan_, k, 0, {});
    return 1024;
  }

 private:
  template <RunPhase P> void TickIn(std::size_t k);
  void FindInnerTicks();
  [[gnu::always_inline]] bool ContourCannotGrow(std::size_t k, double bound) const;
  [[gnu::noinline]] void Contour(std::size_t k, double bound);
  long LastSampleOutside(const model::FreeTerms& free) const;

  const RunPlan& plan_;
  RunResult& result_;
  SingleModeKernel kernel_;
  const RunWindow& window_;
  double static_m_ = 0.0;
  MetricTally tally_;
  std::vector<std::size_t>::const_iterator next_probe_;
  double start_abs_ = 0.0;  // |deflection| at the period's start
  bool first_probe_ = true;
  long deferred_ = 0;
  double end_off_ = 0.0;   // the command's end from the line's end, and the rounding there
  double rounding_ = 0.0;  // OffLineBound's rounding term, at most
  // Contour errors below this are rounding (1e-12 of the static displacement: femtometres):
  // not sampled for (a quiet residual window would otherwise be sampled throughout, chasing
  // distances of 1e-15 m that the samples' own arithmetic makes).
  double contour_floor_ = 0.0;
  // Ticks [inner_from_, inner_to_]: the tool stays inside the line, whatever the mode does.
  std::size_t inner_from_ = 1;
  std::size_t inner_to_ = 0;
  bool tail_closed_ = false;
};

template <RunPhase P>
void ClosedFormSampler::TickIn(std::size_t k) {
  const bool motion_end = k == window_.motion_ticks;
  const double needed = P == RunPhase::kWindow && !motion_end ? std::min(tally_.peak, tally_.residual) : tally_.peak;
  double inside = 0.0;
  double within = 0.0;
  const double end = kernel_.Advance(kernel_.s_.AccelAt(k)(kernel_.axis_), needed, &inside, &within);
  const double largest = std::max(std::max(start_abs_, end), within);
  tally_.peak = std::max(tally_.peak, std::max(end, inside));
  if constexpr (P == RunPhase::kWindow) {
    tally_.residual = std::max(tally_.residual, motion_end ? end : std::max(end, inside));
  }
  if constexpr (P != RunPhase::kMotion) {
    // The last sample outside the settling band: the end's, else an inner one's.
    int last = end >= tally_.band ? kernel_.substeps_ - 1 : -1;
    if (last < 0 && largest >= tally_.band && !motion_end) {
      for (int j = kernel_.substeps_ - 2; j >= 0; --j) {
        if (std::abs(kernel_.Substep(j)) >= tally_.band) {
          last = j;
          break;
        }
      }
    }
    if (last >= 0) {
      tally_.last_outside_band = static_cast<long>((k - 1) * static_cast<std::size_t>(kernel_.substeps_)) + last + 1;
      tally_.quiet_since_tick = k;
    }
  }
  const double bound = largest + kSampleMargin * (largest + static_m_);
  if ((k >= inner_from_ && k <= inner_to_) || ContourCannotGrow(k, bound)) {
    ++deferred_;
  } else {
    Contour(k, bound);
  }
  start_abs_ = end;
}

// A quick bound first (inline): no sample of period k can raise the contour error. The
// command within |v0| h + |a| h^2 / 2 of p0 (at rest at its end after the command), the
// tool within `bound` of it: its distance from the line is at most this; Contour's bound
// (OffLineBound on the exact range) is never larger.
inline bool ClosedFormSampler::ContourCannotGrow(std::size_t k, double bound) const {
  const CommandSamples& s = kernel_.s_;
  double off = 0.0;
  if (k > s.n) {
    off = bound * (1.0 + 1e-15) + end_off_;
  } else {
    const int ax = kernel_.axis_;
    const double dt = kernel_.dt_;
    const double reach = std::abs(s.velocity[k - 1](ax)) * dt + 0.5 * std::abs(s.accel[k](ax)) * dt * dt + bound;
    const double along = (s.positions[k - 1](ax) - kernel_.start_) * kernel_.direction_;
    // Strictly inside a line from 0: every distance is an exact 0 (OffLineBound).
    if (kernel_.start_ == 0.0 && along - reach > rounding_ && along + reach < kernel_.length_ - rounding_) return true;
    off = std::max(0.0, std::max(reach - along, along + reach - kernel_.length_)) * (1.0 + 1e-15) + rounding_;
  }
  return off < contour_floor_ || off * off < tally_.contour_sq;
}

// The ticks in which no sample can leave the line, found once a run (two binary searches)
// instead of bounding every tick: the command's positions move one way along the line
// from its start at 0, within max speed dt + max |a| dt^2 / 2 of the tick's first one,
// and the deflection stays within DeflectionBound of the whole command's |a|.
void ClosedFormSampler::FindInnerTicks() {
  const CommandSamples& s = kernel_.s_;
  const int ax = kernel_.axis_;
  if (kernel_.start_ != 0.0 || s.n < 2 || s.monotone[ax] != (kernel_.direction_ > 0.0 ? 1 : -1)) return;
  const double dt = kernel_.dt_;
  // A margin far above the rounding OffLineBound allows for (a few ulps of the coordinates).
  const double margin = 1e-9 * (std::abs(kernel_.start_) + kernel_.length_) + 1e-12;
  const double keep = s.max_speed_m_s * dt + 0.5 * s.max_accel_m_s2 * dt * dt +
                      kernel_.DeflectionBound(s.accel_l1_m_s[ax]) * (1.0 + 1e-9) + margin;
  const auto along = [&](std::size_t i) { return (s.positions[i](ax) - kernel_.start_) * kernel_.direction_; };
  // Tick k spans positions k - 1 to k (nondecreasing along the line).
  std::size_t lo = 0;
  std::size_t hi = s.n + 1;  // the first position beyond `keep`
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (along(mid) > keep) hi = mid; else lo = mid + 1;
  }
  inner_from_ = lo + 1;
  lo = 0;
  hi = s.n + 1;  // the first position not below length - keep
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (along(mid) < kernel_.length_ - keep) lo = mid + 1; else hi = mid;
  }
  inner_to_ = lo == 0 ? 0 : lo - 1;
}

// The largest squared contour error, from the substeps of the periods where the tool can
// leave the line (its ends: OffLineBound, deferred_substeps.h); called where
// ContourCannotGrow's quick bound could not rule them out.
void ClosedFormSampler::Contour(std::size_t k, double bound) {
  const CommandSamples& s = kernel_.s_;
  const bool commanded = k <= s.n;
  const double p0 = (commanded ? s.positions[k - 1] : s.positions.back())(kernel_.axis_);
  const double v0 = commanded ? s.velocity[k - 1](kernel_.axis_) : 0.0;
  const double half_a = 0.5 * s.AccelAt(k)(kernel_.axis_);
  double lo = 0.0;
  double hi = 0.0;
  QuadraticRange(p0, v0, half_a, kernel_.dt_, &lo, &hi);
  const double off_bound = OffLineBound(kernel_.start_, kernel_.direction_, kernel_.length_, lo - bound, hi + bound);
  if (off_bound == 0.0 || off_bound * off_bound < tally_.contour_sq) {
    ++deferred_;
    return;
  }
  for (int j = 0; j < kernel_.substeps_; ++j) {
    const double tau = kernel_.taus_[static_cast<std::size_t>(j)];
    const double actual = p0 + v0 * tau + half_a * tau * tau + kernel_.Substep(j);
    const double along = std::clamp((actual - kernel_.start_) * kernel_.direction_, 0.0, kernel_.length_);
    const double off = actual - (kernel_.start_ + along * kernel_.direction_);
    tally_.contour_sq = std::max(tally_.contour_sq, off * off);
  }
}

// At the residual window's end: the settling tail in closed form (plant_sampler.cc's SettleTail
// with the one pole pair); false when the simulated tail must decide.
bool ClosedFormSampler::SettleTail(std::size_t k) {
  if (window_.never_settles_late || k != window_.window_end()) return false;
  const model::FreeTerms free = kernel_.Free();
  constexpr double kMargin = 1.0 + 1e-9;
  const double envelope = free.Envelope(0.0);
  if (!(envelope * kMargin <= tally_.peak) || !(envelope * envelope * kMargin <= tally_.contour_sq)) return false;
  const long last = LastSampleOutside(free);
  if (last == -2) return false;
  long last_outside = tally_.last_outside_band;
  std::size_t quiet = tally_.quiet_since_tick;
  if (last >= 1) {
    last_outside = static_cast<long>(k) * kernel_.substeps_ + last;
    quiet = static_cast<std::size_t>((last_outside - 1) / kernel_.substeps_ + 1);
  }
  const std::size_t stop = quiet + window_.period_ticks;
  tally_.last_outside_band = last_outside;
  tally_.quiet_since_tick = quiet;
  tally_.settled = stop <= window_.max_ticks;
  tally_.last_tick = std::min(stop, window_.max_ticks);
  tail_closed_ = true;
  return true;
}

// The last sample j >= 1 of the free response's grid (dt / substeps) with |y| >= band; 0
// when there is none; -2 when undecided (no decay). From the envelope's crossing, where
// |y| < band for good, back sample by sample (y_j = Re(q z^j): one complex product a
// sample): a sample outside lies within half a natural period of it unless the damping
// is below about 1e-4 (the grid can miss the last crests, each only pi zeta higher than
// the next): beyond four periods back, model/band_crossing.h's search decides, as the
// general path's tail does.
long ClosedFormSampler::LastSampleOutside(const model::FreeTerms& free) const {
  const double band = tally_.band;
  const std::complex<double> q = free.q.front();
  const std::complex<double> lambda = free.lambda.front();
  const double envelope = std::abs(q);
  if (!(band > 0.0) || !(lambda.real() < 0.0)) return -2;
  if (envelope < band) return 0;
  const double h = kernel_.dt_ / kernel_.substeps_;
  const double crossing = std::log(envelope / band) / -lambda.real();
  const long top = static_cast<long>(std::floor(crossing / h)) + 1;
  const long reach = 4 * static_cast<long>(window_.period_ticks) * kernel_.substeps_ + 2;
  std::complex<double> term = q * std::exp(lambda * (h * static_cast<double>(top)));
  const std::complex<double> back = std::exp(-lambda * h);
  for (long j = top; j >= 1 && top - j <= reach; --j, term *= back) {
    if (std::abs(term.real()) >= band) return j;
  }
  if (top <= reach) return 0;
  // The bisection's last crossing, then the grid back from it (plant_sampler.cc SettleTail).
  const double last = model::LastBandCrossing(free, band);
  if (std::isnan(last)) return -2;
  for (long j = last >= 0.0 ? static_cast<long>(std::floor(last / h)) + 1 : 0; j >= 1; --j) {
    if (std::abs(free.At(h * static_cast<double>(j))) >= band) return j;
  }
  return 0;
}

std::size_t ClosedFormSampler::Tick(std::size_t k) {
  const std::size_t motion = window_.motion_ticks;
  if (k < motion) {
    if (k >= inner_from_ && k <= inner_to_) {
      std::size_t end = std::min(inner_to_ + 1, motion);
      if (next_probe_ != window_.cruise_probe_ticks.end()) end = std::min(end, *next_probe_);
      if (end > k) {
        tally_.peak = kernel_.AdvancePeaks(k, end, tally_.peak, &start_abs_);
        deferred_ += static_cast<long>(end - k);
        return end - 1;
      }
    }
    TickIn<RunPhase::kMotion>(k);
    if (next_probe_ != window_.cruise_probe_ticks.end() && k == *next_probe_) {
      ++next_probe_;
      const double amplitude = kernel_.ModalAmplitude();
      if (first_probe_ || amplitude > tally_.cruise_m) tally_.cruise_m = amplitude;
      first_probe_ = false;
    }
    return k;
  }
  if (k <= window_.window_end()) {
    TickIn<RunPhase::kWindow>(k);
    if (k == motion) tally_.residual_m = kernel_.ModalAmplitude();
  } else {
    TickIn<RunPhase::kTail>(k);
  }
  return k;
}

MetricTally ClosedFormSampler::Run() {
  RunTicks(*this, window_, &tally_);
  tally_.peak_axes(kernel_.axis_) = tally_.peak;
  result_.sampler = SamplerKind::kClosedForm;
  result_.single_mode = true;
  result_.tail_in_closed_form = tail_closed_;
  result_.deferred_periods = deferred_;
  result_.stats.steps = static_cast<long>(tally_.last_tick) * kernel_.substeps_;
  result_.work = RunWork(plan_, tally_.last_tick, 0);
  result_.substeps = kernel_.substeps_;
  const model::ModalMode& mode = *plan_.single_mode.mode;
  result_.residual_modes = {{mode.frequency_hz, mode.damping_ratio, tally_.residual_m}};
  return tally_;
}

}  // namespace

std::unique_ptr<Sampler> MakeClosedFormSampler(const RunPlan& plan, RunResult* result) {
  return std::make_unique<ClosedFormSampler>(plan, result);
}

}  // namespace shapebench::bench
