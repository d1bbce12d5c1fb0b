// The closed form of one structural mode under a held base acceleration: the state's
// transition over a period, over two, over a stretch of periods, and the extrema inside
// them (docs/samplers.md derives them). The closed-form sampler's constant part and state.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "bench/run/command_samples.h"
#include "common/math_constants.h"
#include "controller/path_geometry.h"
#include "model/band_crossing.h"
#include "model/free_response.h"
#include "model/machine.h"

namespace shapebench::bench::single_mode {

// q' changed sign over the period: a stationary point lies inside it.
inline bool SignChanged(double v0, double v1) { return (v0 > 0.0 && v1 < 0.0) || (v0 < 0.0 && v1 > 0.0); }

// The mode's transition over tau: x(tau) = phi (x0, v0), x = q - q_eq (a held).
struct Transition {
  double xx = 1.0, xv = 0.0, vx = 0.0, vv = 1.0;
};

// One mode, one line: the constant part of the run (MuJoCo's model), then the run's state.
class SingleModeKernel {
 public:
  // Jump's cost (an exp, a cos and a sin, and as many per stationary point it must
  // evaluate) against StepPeaks' few multiplications a period: longer stretches jump.
  static constexpr std::size_t kJumpTicks = 16;

  SingleModeKernel(const model::ModalMode& mode, const controller::PathElement& line, int axis,
                   const CommandSamples& samples, double dt, int substeps)
      : s_(samples), axis_(axis), dt_(dt), substeps_(substeps) {
    const double w = 2.0 * kPi * mode.frequency_hz;
    w2_ = w * w;
    sigma_ = mode.damping_ratio * w;
    wd_ = w * std::sqrt(1.0 - mode.damping_ratio * mode.damping_ratio);
    gain_ = mode.gain;
    cap_ = model::ResidualCap(mode.damping_ratio);
    cap_can_act_ = model::ResidualCapCanAct(mode.damping_ratio);
    start_ = line.start_m(axis);
    direction_ = line.direction(axis);
    length_ = line.length_m;
    period_ = At(dt);
    g_q_ = -(1.0 - period_.xx) / w2_;
    g_v_ = period_.vx / w2_;
    twice_ = At(2.0 * dt);
    h_q_ = period_.xx * g_q_ + period_.xv * g_v_;  // phi gamma: a held over the first of two
    h_v_ = period_.vx * g_q_ + period_.vv * g_v_;
  }

  // The substeps' times and transitions (an exp, a cos and a sin each), made when a
  // sample inside a period is first needed (Substep, taus_): a run that reads none (its
  // contour error unread, its settling decided at the periods' ends) never makes them.
  void PrepareSubsteps() {
    if (!inner_.empty()) return;
    inner_.resize(static_cast<std::size_t>(substeps_));
    taus_.resize(static_cast<std::size_t>(substeps_));
    for (int j = 1; j <= substeps_; ++j) {
      taus_[j - 1] = dt_ * static_cast<double>(j) / substeps_;
      inner_[j - 1] = At(taus_[j - 1]);
    }
  }

  // Of the free vibration about q = 0 (a = 0): the envelope, capped at ResidualCap(zeta)
  // times the free response's largest |value| (model/free_response.h, CappedResidual).
  double ModalAmplitude() const {
    const double envelope = std::abs(gain_) * std::hypot(q_, (v_ + sigma_ * q_) / wd_);
    if (!cap_can_act_) return envelope;
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
  // inside the line, no cruise probe). A stretch of more than kJumpTicks periods under one
  // held a (between two of the command's accel_changes) is crossed in one step (Jump) but
  // for its last period; shorter ones, and that last period, tick by tick (StepPeaks).
  // Returns the peak so far; *end_abs the last period's |deflection|.
  double AdvancePeaks(std::size_t from, std::size_t to, double peak, double* end_abs) {
    const std::vector<std::size_t>& changes = s_.accel_changes;
    auto change = std::upper_bound(changes.begin(), changes.end(), from);
    double q = q_;
    double v = v_;
    for (std::size_t k = from; k < to;) {
      const std::size_t stop = change == changes.end() ? to : std::min(*change, to);
      if (stop - k > kJumpTicks) {
        peak = Jump(s_.accel[k](axis_), stop - 1 - k, peak, &q, &v);
        k = stop - 1;
      }
      peak = StepPeaks(k, stop, peak, &q, &v);
      k = stop;
      if (change != changes.end() && *change == stop) ++change;
    }
    q_ = q;
    v_ = v;
    *end_abs = std::abs(gain_ * q);
    return peak;
  }
  // A stretch of m periods under a held a in one step (a free oscillation about q_eq =
  // -a / w^2): the state at its end and the peak over it, from its end and its stationary
  // points. Only the first two stationary points can raise the peak: later ones repeat
  // their signs, each smaller by exp(-sigma pi / w_d) (undamped, equal). The stretch's
  // start is the previous period's end, already in the peak.
  double Jump(double a, std::size_t m, double peak, double* q, double* v) const {
    const double q_eq = -a / w2_;
    const double q_start = *q;
    const double x0 = q_start - q_eq;
    const double v0 = *v;
    const double b = (v0 + sigma_ * x0) / wd_;
    const double length = dt_ * static_cast<double>(m);
    const double e = std::exp(-sigma_ * length);
    const double c = std::cos(wd_ * length);
    const double sn = std::sin(wd_ * length);
    *q = q_eq + e * (x0 * c + b * sn);
    *v = e * (v0 * c - (sigma_ * v0 + w2_ * x0) / wd_ * sn);
    peak = std::max(peak, std::abs(gain_ * *q));
    if (ExtremumBound(q_start, v0, a) < peak) return peak;
    double t = FirstStationary(q_start, v0, a);
    for (int i = 0; i < 2; ++i, t += HalfPeriod()) {
      if (!(t > 0.0 && t < length)) break;
      const double x = std::exp(-sigma_ * t) * (x0 * std::cos(wd_ * t) + b * std::sin(wd_ * t));
      peak = std::max(peak, std::abs(gain_ * (x + q_eq)));
    }
    return peak;
  }
  // The first time t >= 0 at which q' vanishes, from (q0, v0) under a held a: w_d t =
  // atan2(w_d v0, sigma v0 + w^2 x0) (mod pi), x0 = q0 + a / w^2 (Extremum's derivation);
  // the later ones follow every HalfPeriod().
  double FirstStationary(double q0, double v0, double a) const {
    const double x0 = q0 + a / w2_;
    const double t = std::fmod(std::atan2(wd_ * v0, sigma_ * v0 + w2_ * x0), kPi) / wd_;
    return t < 0.0 ? t + HalfPeriod() : t;
  }
  double HalfPeriod() const { return kPi / wd_; }
  // The free response's deflection t after the current state (a = 0 from now on), and
  // its envelope now (no later |deflection| exceeds it).
  double FreeAt(double t) const {
    const double b = (v_ + sigma_ * q_) / wd_;
    return gain_ * std::exp(-sigma_ * t) * (q_ * std::cos(wd_ * t) + b * std::sin(wd_ * t));
  }
  double FreeEnvelope() const { return std::abs(gain_) * std::hypot(q_, (v_ + sigma_ * q_) / wd_); }
  double q() const { return q_; }
  double v() const { return v_; }
  void SetState(double q, double v) {
    q_ = q;
    v_ = v;
  }

  // Periods [from, to) tick by tick: Advance's arithmetic with the state in registers,
  // the floor's loop.
  double StepPeaks(std::size_t from, std::size_t to, double peak, double* q_io, double* v_io) {
    const double* accel = s_.accel.front().data() + axis_;  // Vector3d: 3 doubles, packed
    double q = *q_io;
    double v = *v_io;
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
    for (; k < to; ++k) {
      q0_ = q;
      v0_ = v;
      a_ = accel[3 * k];
      q = period_.xx * q0_ + period_.xv * v0_ + g_q_ * a_;
      v = period_.vx * q0_ + period_.vv * v0_ + g_v_ * a_;
      peak = std::max(Turning(q0_, v0_, a_, v, peak), std::abs(gain_ * q));
    }
    *q_io = q;
    *v_io = v;
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
  // The deflection at substep j (0-based) of the period Advance stepped last (after
  // PrepareSubsteps).
  double Substep(int j) const {
    const Transition& t = inner_[static_cast<std::size_t>(j)];
    const double q_eq = -a_ / w2_;
    return gain_ * (t.xx * (q0_ - q_eq) + t.xv * v0_ + q_eq);
  }
  // The free response from the current state (input 0 from now on) as one pole pair:
  // Re(FreeQ() exp(FreeLambda() t)); Free() as model/band_crossing.h's terms.
  std::complex<double> FreeQ() const { return {gain_ * q_, -gain_ * (v_ + sigma_ * q_) / wd_}; }
  std::complex<double> FreeLambda() const { return {-sigma_, wd_}; }
  model::FreeTerms Free() const {
    model::FreeTerms terms;
    terms.q = {FreeQ()};
    terms.lambda = {FreeLambda()};
    return terms;
  }

  // |deflection| within the period starting at (q0, v0) under a: the free oscillation's
  // amplitude about the equilibrium (which decays) plus the equilibrium's distance from 0,
  // with a margin for the rounding of both (1e-12: a bound, not a value).
  double ExtremumBound(double q0, double v0, double a) const {
    const FreeOscillation o = About(q0, v0, a);
    return std::abs(gain_) * (std::sqrt(o.x0 * o.x0 + o.b * o.b) + std::abs(o.q_eq)) * (1.0 + 1e-12);
  }
  // ExtremumBound from below (the larger of |x0| and |b| for their hypotenuse, less a
  // relative 1e-12), for tests that only refuse where the bound is certainly large.
  double ExtremumBoundBelow(double q0, double v0, double a) const {
    const FreeOscillation o = About(q0, v0, a);
    return std::abs(gain_) * (std::max(std::abs(o.x0), std::abs(o.b)) + std::abs(o.q_eq)) * (1.0 - 1e-12);
  }

  // The margin QuietStretchEnd adds to what a stretch may keep off the line's ends (and
  // NotQuiet's lower bound of it: the same one, or the bound would not be one).
  double StretchMargin() const { return 1e-9 * length_ + 1e-12; }

  const CommandSamples& s_;
  const int axis_;
  const double dt_;
  const int substeps_;
  double start_ = 0.0, direction_ = 1.0, length_ = 0.0;
  std::vector<double> taus_;

 private:
  // The free oscillation about the equilibrium of a held a: q_eq = -a / w^2, x0 = q0 -
  // q_eq, and b = (v0 + sigma x0) / w_d, its amplitude sqrt(x0^2 + b^2).
  struct FreeOscillation {
    double q_eq, x0, b;
  };
  FreeOscillation About(double q0, double v0, double a) const {
    const double q_eq = -a / w2_;
    const double x0 = q0 - q_eq;
    return {q_eq, x0, (v0 + sigma_ * x0) / wd_};
  }
  Transition At(double tau) const {
    const double e = std::exp(-sigma_ * tau);
    const double c = std::cos(wd_ * tau);
    const double sn = std::sin(wd_ * tau);
    return {e * (c + sigma_ / wd_ * sn), e * sn / wd_, -e * w2_ / wd_ * sn, e * (c - sigma_ / wd_ * sn)};
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
  bool cap_can_act_ = true;
  Transition period_;
  double g_q_ = 0.0, g_v_ = 0.0;  // the period's response to a held a = 1 from rest
  Transition twice_;               // over two periods
  double h_q_ = 0.0, h_v_ = 0.0;  // two periods on, of a = 1 held over the first
  std::vector<Transition> inner_;
  double q_ = 0.0, v_ = 0.0;              // the state at the last period's end
  double q0_ = 0.0, v0_ = 0.0, a_ = 0.0;  // the last period's start and input
};

}  // namespace shapebench::bench::single_mode
