#include "bench/run/closed_form_sampler.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "bench/run/deferred_substeps.h"
#include "bench/run/single_mode_kernel.h"
#include "bench/run/run_work.h"
#include "bench/run/finish_metrics.h"
#include "common/math_constants.h"
#include "model/band_crossing.h"
#include "model/free_response.h"
#include "model/machine.h"

namespace shapebench::bench {
namespace {

using single_mode::SingleModeKernel;

// What a substep's deflection can exceed the period's bound by: its rounding (a few
// operations on values of the run's scale, ~1e-15 of it) with a thousandfold margin. (The
// general path's 1e-9, deferred_substeps.h, would keep a quiet residual window sampled:
// a contour error of rounding size, 1e-15 m, stays below a margin of 1e-13 m.)
constexpr double kSampleMargin = 1e-12;

// ContourUnreadScope's state on this thread.
thread_local bool contour_unread = false;

// The sampler: the kernel through the run's ticks, its tally as the plant samplers keep it
// (plant_sampler.cc: SampleTick, DeferredTick, SettleTail).
class ClosedFormSampler final : public Sampler {
 public:
  ClosedFormSampler(const RunPlan& plan, RunResult* result)
      : plan_(plan),
        result_(*result),
        kernel_(*plan.single_mode.mode, *plan.single_mode.line, plan.single_mode.axis, plan.samples, plan.dt_s,
                plan.substeps),
        window_(plan.window),
        contour_(!contour_unread) {
    Eigen::Matrix3d static_gain = Eigen::Matrix3d::Zero();
    static_gain(kernel_.axis_, kernel_.axis_) = kernel_.StaticGain();
    SetStaticReference(plan, static_gain, &tally_);
    static_m_ = tally_.static_m;
    contour_floor_ = 1e-12 * static_m_;
    next_probe_ = window_.cruise_probe_ticks.begin();
    change_cursor_ = kernel_.s_.accel_changes.begin();
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
    // Unread: no sample can raise it (every bound test passes), reported NaN by Run.
    if (!contour_) tally_.contour_sq = std::numeric_limits<double>::infinity();
  }

  MetricTally Run() override;
  std::size_t Tick(std::size_t k);
  std::size_t MotionTicks(std::size_t k);
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
  long LastSampleOutside(std::complex<double> q, std::complex<double> lambda) const;
  std::size_t QuietStretchEnd(std::size_t k) const;
  bool NotQuiet(std::size_t k) const;
  std::size_t UnreadTicks(std::size_t k);
  bool FreeWindowApplies(std::size_t k) const;
  void FreeWindow(std::size_t from);
  long LastWindowSampleOutside(long count) const;
  void FreeWindowContour(long count);

  const RunPlan& plan_;
  RunResult& result_;
  SingleModeKernel kernel_;
  const RunWindow& window_;
  const bool contour_;  // max_contour_error_m read (ContourUnreadScope)
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
  // QuietStretchEnd's place in the command's accel_changes: the first change after its tick.
  mutable std::vector<std::size_t>::const_iterator change_cursor_;
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
      kernel_.PrepareSubsteps();
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
  if (!contour_ || (k >= inner_from_ && k <= inner_to_)) {
    ++deferred_;
  } else if (const double bound = largest + kSampleMargin * (largest + static_m_); ContourCannotGrow(k, bound)) {
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
  kernel_.PrepareSubsteps();
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
  // The pole pair, not model::FreeTerms (two vectors): its envelope now is |q|.
  const std::complex<double> q = kernel_.FreeQ();
  constexpr double kMargin = 1.0 + 1e-9;
  const double envelope = std::abs(q);
  if (!(envelope * kMargin <= tally_.peak) || !(envelope * envelope * kMargin <= tally_.contour_sq)) return false;
  const long last = LastSampleOutside(q, kernel_.FreeLambda());
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
long ClosedFormSampler::LastSampleOutside(std::complex<double> q, std::complex<double> lambda) const {
  const double band = tally_.band;
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
  const model::FreeTerms free = kernel_.Free();
  const double last = model::LastBandCrossing(free, band);
  if (std::isnan(last)) return -2;
  for (long j = last >= 0.0 ? static_cast<long>(std::floor(last / h)) + 1 : 0; j >= 1; --j) {
    if (std::abs(free.At(h * static_cast<double>(j))) >= band) return j;
  }
  return 0;
}

// Motion ticks from k to the last before the motion's end in one call: RunTicks has
// nothing to do between them (the run cannot end or settle before the residual window;
// the work is checked after them, its verdict the whole count's), and a period near the
// line's ends, one at a time, paid RunTicks' loop again.
std::size_t ClosedFormSampler::MotionTicks(std::size_t k) {
  const std::size_t motion = window_.motion_ticks;
  for (;;) {
    std::size_t next = k + 1;
    std::size_t end = k;
    if (k >= inner_from_ && k <= inner_to_) {
      end = std::min(inner_to_ + 1, motion);
      if (next_probe_ != window_.cruise_probe_ticks.end()) end = std::min(end, *next_probe_);
    }
    if (end <= k) end = QuietStretchEnd(k);
    if (end > k) {
      tally_.peak = kernel_.AdvancePeaks(k, end, tally_.peak, &start_abs_);
      deferred_ += static_cast<long>(end - k);
      next = end;
    } else if (!contour_ && !(next_probe_ != window_.cruise_probe_ticks.end() && k == *next_probe_)) {
      next = UnreadTicks(k);
    } else {
      TickIn<RunPhase::kMotion>(k);
      if (next_probe_ != window_.cruise_probe_ticks.end() && k == *next_probe_) {
        ++next_probe_;
        const double amplitude = kernel_.ModalAmplitude();
        if (first_probe_ || amplitude > tally_.cruise_m) tally_.cruise_m = amplitude;
        first_probe_ = false;
      }
    }
    if (next >= motion) return next - 1;
    k = next;
  }
}

std::size_t ClosedFormSampler::Tick(std::size_t k) {
  const std::size_t motion = window_.motion_ticks;
  if (k < motion) return MotionTicks(k);
  if (k <= window_.window_end()) {
    if (FreeWindowApplies(k)) {
      FreeWindow(k);
      return window_.window_end();
    }
    TickIn<RunPhase::kWindow>(k);
    if (k == motion) tally_.residual_m = kernel_.ModalAmplitude();
  } else {
    TickIn<RunPhase::kTail>(k);
  }
  return k;
}

// Motion ticks one at a time from k (one QuietStretchEnd refused) while the contour error
// is unread, to the first tick MotionTicks would treat otherwise (an inner tick, a quiet
// stretch, a cruise probe, the motion's end); returns it. Each tick is TickIn<kMotion>'s
// (Advance's arithmetic and peak, bit for bit) without its per-tick calls, and the next
// tick's QuietStretchEnd only where NotQuiet's cheaper test cannot already refuse it: the
// same ticks jump or step one at a time as with the contour read, so every other metric
// keeps its bits (ContourUnread.OtherMetricsBitForBitContourNa).
std::size_t ClosedFormSampler::UnreadTicks(std::size_t k) {
  const std::size_t motion = window_.motion_ticks;
  const std::size_t probe = next_probe_ != window_.cruise_probe_ticks.end() ? *next_probe_ : motion;
  const int ax = kernel_.axis_;
  const double* accel = kernel_.s_.accel.front().data() + ax;  // Vector3d: 3 doubles, packed
  double peak = tally_.peak;
  double end = 0.0;
  for (;;) {
    double inside = 0.0;
    double within = 0.0;
    end = kernel_.Advance(accel[3 * k], peak, &inside, &within);
    peak = std::max(peak, std::max(end, inside));
    ++deferred_;
    ++k;
    if (k >= motion || k == probe || (k >= inner_from_ && k <= inner_to_)) break;
    if (!NotQuiet(k) && QuietStretchEnd(k) > k) break;
  }
  tally_.peak = peak;
  start_abs_ = end;
  return k;
}

// True only where QuietStretchEnd(k) returns k: the tool within a lower bound of its
// `keep` of either end of the line (the speed at the stretch's start, the free
// oscillation's bound from below and the margin, less a relative 1e-12 for rounding: its
// keep adds only nonnegative terms to them). No cursor, no search: most ticks near the
// line's ends are refused here.
inline bool ClosedFormSampler::NotQuiet(std::size_t k) const {
  const CommandSamples& s = kernel_.s_;
  const int ax = kernel_.axis_;
  const double margin = kernel_.StretchMargin();
  const double bound = kernel_.ExtremumBoundBelow(kernel_.q(), kernel_.v(), s.accel[k](ax));
  const double low = (std::abs(s.velocity[k - 1](ax)) * kernel_.dt_ + bound + margin) * (1.0 - 1e-12);
  const double along = (s.positions[k - 1](ax) - kernel_.start_) * kernel_.direction_;
  return along <= low || along >= kernel_.length_ - low;
}

// Outside FindInnerTicks' ticks, per stretch of held a: the end of the one starting at
// motion tick k when no sample inside it can leave the line, else k. The test is
// FindInnerTicks' with the deflection bounded by the stretch's own free oscillation
// (ExtremumBound: its amplitude about the equilibrium decays), not the whole command's.
std::size_t ClosedFormSampler::QuietStretchEnd(std::size_t k) const {
  const CommandSamples& s = kernel_.s_;
  const int ax = kernel_.axis_;
  if (kernel_.start_ != 0.0 || s.monotone[ax] != (kernel_.direction_ > 0.0 ? 1 : -1)) return k;
  // upper_bound(k) by a cursor: the ticks come in order (a binary search a tick cost a
  // point more than the rest of this test).
  if (change_cursor_ != s.accel_changes.begin() && *(change_cursor_ - 1) > k) {
    change_cursor_ = std::upper_bound(s.accel_changes.begin(), s.accel_changes.end(), k);
  }
  while (change_cursor_ != s.accel_changes.end() && *change_cursor_ <= k) ++change_cursor_;
  const auto change = change_cursor_;
  std::size_t stop = change == s.accel_changes.end() ? window_.motion_ticks : std::min(*change, window_.motion_ticks);
  if (next_probe_ != window_.cruise_probe_ticks.end()) stop = std::min(stop, *next_probe_);
  if (stop <= k) return k;
  // Within a period the command moves at most its speed at either end of the stretch
  // (the velocity is linear in it) times dt, plus |a| dt^2 / 2, from a period's ends.
  const double dt = kernel_.dt_;
  const double a = s.accel[k](ax);
  const double speed = std::max(std::abs(s.velocity[k - 1](ax)), std::abs(s.velocity[stop - 1](ax)));
  const double margin = kernel_.StretchMargin();
  const double bound = kernel_.ExtremumBound(kernel_.q(), kernel_.v(), a);
  const double keep = speed * dt + 0.5 * std::abs(a) * dt * dt + bound * (1.0 + 1e-9) + margin;
  const auto along = [&](std::size_t i) { return (s.positions[i](ax) - kernel_.start_) * kernel_.direction_; };
  if (!(along(k - 1) > keep)) return k;
  // Toward the line's end: up to the first position within `keep` of it (monotone).
  std::size_t lo = k - 1;  // along(lo) < length - keep, the last known so
  if (!(along(lo) < kernel_.length_ - keep)) return k;
  std::size_t hi = stop;  // one past the last candidate
  // The whole stretch first (the cruise's, most often): the search would end there.
  if (along(stop - 1) < kernel_.length_ - keep) return stop;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (along(mid) < kernel_.length_ - keep) lo = mid; else hi = mid;
  }
  return lo + 1;  // ticks [k, lo + 1) span positions k - 1..lo
}

// The residual window after the motion's last period, when the command rests at its end
// from then on (a = 0, the position its last): a free response, which FreeWindow tallies
// in closed form.
bool ClosedFormSampler::FreeWindowApplies(std::size_t k) const {
  const CommandSamples& s = kernel_.s_;
  return k == window_.motion_ticks + 1 && k > s.n && k <= window_.window_end();
}

// Ticks from..window_end() of the free response in one step: what TickIn<kWindow> tallies
// tick by tick. The residual and the peak: the largest |deflection| over the stretch
// (Jump: its end and stationary points); the settling band's last sample outside, from
// the window's end back; the contour error from the largest and smallest deflection on
// the sample grid.
void ClosedFormSampler::FreeWindow(std::size_t from) {
  const std::size_t ticks = window_.window_end() - from + 1;
  const long count = static_cast<long>(ticks) * kernel_.substeps_;
  const long last = LastWindowSampleOutside(count);
  if (last > 0) {
    tally_.last_outside_band = static_cast<long>(from - 1) * kernel_.substeps_ + last;
    tally_.quiet_since_tick = from + static_cast<std::size_t>((last - 1) / kernel_.substeps_);
  }
  if (contour_) FreeWindowContour(count);
  double q = kernel_.q();
  double v = kernel_.v();
  const double largest = kernel_.Jump(0.0, ticks, 0.0, &q, &v);
  tally_.peak = std::max(tally_.peak, largest);
  tally_.residual = std::max(tally_.residual, largest);
  kernel_.SetState(q, v);
  start_abs_ = std::abs(kernel_.FreeAt(0.0));
  deferred_ += static_cast<long>(ticks);
}

// The last sample j (1..count, on the grid dt / substeps after the window's first tick
// begins) with |deflection| >= band, 0 when none: none once the envelope is below the
// band, so from where it crosses it (or the window's end) back, one complex product a
// sample (LastSampleOutside's walk).
long ClosedFormSampler::LastWindowSampleOutside(long count) const {
  const double band = tally_.band;
  const std::complex<double> q = kernel_.FreeQ();
  const std::complex<double> lambda = kernel_.FreeLambda();
  if (!(band > 0.0) || std::abs(q) < band) return 0;
  const double h = kernel_.dt_ / kernel_.substeps_;
  long top = count;
  if (lambda.real() < 0.0) {
    const double crossing = std::log(std::abs(q) / band) / -lambda.real();
    top = std::min(count, static_cast<long>(std::floor(crossing / h)) + 1);
  }
  std::complex<double> term = q * std::exp(lambda * (h * static_cast<double>(top)));
  const std::complex<double> back = std::exp(-lambda * h);
  for (long j = top; j >= 1; --j, term *= back) {
    if (std::abs(term.real()) >= band) return j;
  }
  return 0;
}

// The contour error over the window: the command rests at its end, the tool at it plus
// the deflection, so the distance off the line grows with the deflection beyond either
// end; its largest on the grid is at the largest or smallest deflection sampled. Between
// two stationary points the deflection is monotone: those lie at the grid's ends or next
// to a stationary point.
void ClosedFormSampler::FreeWindowContour(long count) {
  const CommandSamples& s = kernel_.s_;
  const double end = s.positions.back()(kernel_.axis_);
  const double envelope = kernel_.FreeEnvelope() * (1.0 + 1e-12);
  const double along_end = (end - kernel_.start_) * kernel_.direction_;
  const double reach = std::max(along_end + envelope - kernel_.length_, envelope - along_end);
  if (reach + rounding_ < contour_floor_ || (reach + rounding_) * (reach + rounding_) < tally_.contour_sq) return;
  const double h = kernel_.dt_ / kernel_.substeps_;
  double high = -std::numeric_limits<double>::infinity();
  double low = std::numeric_limits<double>::infinity();
  const auto sample = [&](long j) {
    if (j < 1 || j > count) return;
    const double y = kernel_.FreeAt(h * static_cast<double>(j));
    high = std::max(high, y);
    low = std::min(low, y);
  };
  sample(1);
  sample(count);
  const double span = h * static_cast<double>(count);
  for (double t = kernel_.FirstStationary(kernel_.q(), kernel_.v(), 0.0); t < span; t += kernel_.HalfPeriod()) {
    const long j = static_cast<long>(std::floor(t / h));
    sample(j);
    sample(j + 1);
  }
  for (const double y : {high, low}) {
    const double actual = end + y;
    const double along = std::clamp((actual - kernel_.start_) * kernel_.direction_, 0.0, kernel_.length_);
    const double off = actual - (kernel_.start_ + along * kernel_.direction_);
    tally_.contour_sq = std::max(tally_.contour_sq, off * off);
  }
}

MetricTally ClosedFormSampler::Run() {
  RunTicks(*this, window_, &tally_);
  tally_.peak_axes(kernel_.axis_) = tally_.peak;
  if (!contour_) tally_.contour_sq = std::numeric_limits<double>::quiet_NaN();
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

ContourUnreadScope::ContourUnreadScope(bool unread) : previous_(contour_unread) { contour_unread = unread; }
ContourUnreadScope::~ContourUnreadScope() { contour_unread = previous_; }

}  // namespace shapebench::bench
