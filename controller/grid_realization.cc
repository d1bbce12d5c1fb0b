#include "controller/grid_realization.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "common/math_constants.h"

namespace shapebench::controller {
namespace {

// (tick, weight) ordered by tick: deterministic sums. A sorted vector, not a map: a group
// has a handful of ticks, and this runs dozens of times per command (the exact-distance
// search); the arithmetic (each += in impulse order) is the same.
using TickWeights = std::vector<std::pair<long, double>>;

// The weight of a tick, inserted as 0 when the tick has none yet.
double& WeightAt(TickWeights* weights, long tick) {
  auto it = std::lower_bound(weights->begin(), weights->end(), tick,
                             [](const std::pair<long, double>& w, long t) { return w.first < t; });
  if (it == weights->end() || it->first != tick) it = weights->insert(it, {tick, 0.0});
  return it->second;
}

// Each impulse split between its two neighbouring ticks in proportion to its distance
// from them: the acceleration and the velocity after the group stay exact.
TickWeights SplitBetweenTicks(const std::vector<Impulse>& group, double period_s) {
  TickWeights weights;
  weights.reserve(2 * group.size() + 2);
  for (const Impulse& impulse : group) {
    const double position = impulse.time_s / period_s;
    long tick = static_cast<long>(std::floor(position));
    double fraction = position - static_cast<double>(tick);
    // Times meant to be on the grid but off by rounding are snapped to it.
    if (fraction < 1e-9) fraction = 0.0;
    if (fraction > 1.0 - 1e-9) {
      ++tick;
      fraction = 0.0;
    }
    WeightAt(&weights, tick) += impulse.amplitude * (1.0 - fraction);
    if (fraction > 0.0) WeightAt(&weights, tick + 1) += impulse.amplitude * fraction;
  }
  return weights;
}

std::vector<GridImpulse> NonZero(const TickWeights& weights) {
  std::vector<GridImpulse> result;
  result.reserve(weights.size());
  for (const auto& [tick, w] : weights) {
    if (w != 0.0) result.push_back({tick, w});
  }
  return result;
}

bool IsDesigned(const GridDesign& design) {
  bool designed = !design.frequencies_hz.empty();
  for (const double f : design.frequencies_hz) designed = designed && f > 0.0 && std::isfinite(f);
  return designed;
}

double RadPerS(double frequency_hz) { return 2.0 * kPi * frequency_hz; }

// The ticks the split group covers: first_tick .. first_tick + periods.
struct Span {
  long first_tick;
  long periods;
};

// The design's phasors relative to the group's first tick (which keeps the least squares
// well conditioned): damped, e^{(zeta w + i w_d) t}; undamped, exactly the plain e^{iwt}.
struct GroupPhasor {
  const GridDesign& design;
  long first_tick;
  double period_s;

  std::complex<double> operator()(std::size_t j, double t_s) const {
    const double zeta = design.DampingAt(j);
    const double w = RadPerS(design.frequencies_hz[j]);
    const double dt = t_s - first_tick * period_s;
    if (zeta == 0.0) return std::polar(1.0, w * dt);
    return std::exp(zeta * w * dt) * std::polar(1.0, w * std::sqrt(1.0 - zeta * zeta) * dt);
  }
};

// Per design frequency: the ideal group's phasor minus the plain split's.
std::vector<std::complex<double>> PhasorMismatch(const std::vector<Impulse>& group,
                                                 const TickWeights& weights,
                                                 const GroupPhasor& phase, double period_s) {
  std::vector<std::complex<double>> mismatch(phase.design.frequencies_hz.size(), 0.0);
  for (std::size_t j = 0; j < mismatch.size(); ++j) {
    for (const Impulse& impulse : group) mismatch[j] += impulse.amplitude * phase(j, impulse.time_s);
    for (const auto& [tick, weight] : weights) mismatch[j] -= weight * phase(j, tick * period_s);
  }
  return mismatch;
}

// What rounding alone leaves in the mismatch: the phase of a time t is good to about
// w eps |t| (and the sums to eps): a group whose steps lie on ticks leaves only that,
// and a correction of it would be noise on every tick of the span.
bool OnlyRoundingLeft(const std::vector<Impulse>& group, const GridDesign& design, Span span,
                      double period_s, const std::vector<std::complex<double>>& mismatch) {
  double scale = 0.0;
  double latest_s = 0.0;
  for (const Impulse& impulse : group) {
    scale += std::abs(impulse.amplitude);
    latest_s = std::max(latest_s, std::abs(impulse.time_s));
  }
  latest_s = std::max(latest_s, std::abs((span.first_tick + span.periods) * period_s));
  bool rounding_only = true;
  for (std::size_t j = 0; j < mismatch.size(); ++j) {
    const double w = RadPerS(design.frequencies_hz[j]);
    const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * (1.0 + w * latest_s);
    rounding_only = rounding_only && std::abs(mismatch[j]) <= rounding * scale;
  }
  return rounding_only;
}

// The phasor at each tick of the span, once (the same values the least squares would
// compute again and again); only after OnlyRoundingLeft: a group on ticks needs few.
class TickPhasors {
 public:
  TickPhasors(const GroupPhasor& phase, Span span)
      : span_(span), values_((span.periods + 1) * phase.design.frequencies_hz.size()) {
    for (std::size_t j = 0; j < phase.design.frequencies_hz.size(); ++j) {
      for (long p = 0; p <= span.periods; ++p) {
        values_[j * (span.periods + 1) + p] = phase(j, (span.first_tick + p) * phase.period_s);
      }
    }
  }
  // The phasor of design frequency j at the span's p-th tick.
  std::complex<double> at(std::size_t j, long p) const { return values_[j * (span_.periods + 1) + p]; }

 private:
  Span span_;
  std::vector<std::complex<double>> values_;
};

// The acceleration over each period of the span.
std::vector<double> AccelerationLevels(const TickWeights& weights, Span span,
                                       double accel_before_m_s2) {
  std::vector<double> level(span.periods);
  double running = accel_before_m_s2;
  for (long p = 0, next = 0; p < span.periods; ++p) {
    if (weights[next].first == span.first_tick + p) running += weights[next++].second;
    level[p] = running;
  }
  return level;
}

// Corrects the acceleration of periods of the span by e_p, as little as possible (least
// squares, spread over the span rather than piled onto one period):
// sum e_p = 0 keeps the velocity after the group, and
// sum e_p (e^{iwt_{p+1}} - e^{iwt_p}) = -mismatch makes the jerk phasor the ideal one
// (one such pair of rows per design frequency).
class LeastCorrection {
 public:
  LeastCorrection(Span span, const TickPhasors& tick_phase,
                  const std::vector<std::complex<double>>& mismatch, std::vector<double> level,
                  double accel_limit_m_s2)
      : span_(span),
        tick_phase_(tick_phase),
        mismatch_(mismatch),
        rows_(1 + 2 * static_cast<long>(mismatch.size())),
        level_(std::move(level)),
        accel_limit_m_s2_(accel_limit_m_s2) {}

  // e_p per period of the span; empty when there is none (too few free periods, or
  // sparing the peak, the peak would be raised). Spare the peak: periods already at the
  // largest acceleration are left alone, so the correction does not raise the run's peak
  // acceleration (and static deflection).
  std::vector<double> Solve(bool spare_the_peak) const {
    std::vector<long> free;
    for (long p = 0; p < span_.periods; ++p) {
      if (!spare_the_peak || std::abs(level_[p]) < accel_limit_m_s2_ * (1.0 - 1e-9)) free.push_back(p);
    }
    if (static_cast<long>(free.size()) < rows_) return {};
    const Eigen::MatrixXd constraints = Constraints(free);
    const Eigen::VectorXd rhs = RightHandSide();
    const Eigen::VectorXd e = constraints.completeOrthogonalDecomposition().solve(rhs);
    if ((constraints * e - rhs).norm() > 1e-9 * (1.0 + rhs.norm())) return {};
    std::vector<double> correction(span_.periods, 0.0);
    for (std::size_t i = 0; i < free.size(); ++i) correction[free[i]] = e(i);
    if (spare_the_peak) {
      for (long p = 0; p < span_.periods; ++p) {
        if (std::abs(level_[p] + correction[p]) > accel_limit_m_s2_ * (1.0 + 1e-12)) return {};
      }
    }
    return correction;
  }

 private:
  Eigen::MatrixXd Constraints(const std::vector<long>& free) const {
    Eigen::MatrixXd constraints(rows_, static_cast<long>(free.size()));
    for (std::size_t i = 0; i < free.size(); ++i) {
      const long p = free[i];
      constraints(0, i) = 1.0;
      for (std::size_t j = 0; j < mismatch_.size(); ++j) {
        const std::complex<double> c = tick_phase_.at(j, p + 1) - tick_phase_.at(j, p);
        constraints(1 + 2 * j, i) = c.real();
        constraints(2 + 2 * j, i) = c.imag();
      }
    }
    return constraints;
  }

  Eigen::VectorXd RightHandSide() const {
    Eigen::VectorXd rhs(rows_);
    rhs(0) = 0.0;
    for (std::size_t j = 0; j < mismatch_.size(); ++j) {
      rhs(1 + 2 * j) = -mismatch_[j].real();
      rhs(2 + 2 * j) = -mismatch_[j].imag();
    }
    return rhs;
  }

  Span span_;
  const TickPhasors& tick_phase_;
  const std::vector<std::complex<double>>& mismatch_;
  long rows_;  // velocity + a phasor each
  std::vector<double> level_;
  double accel_limit_m_s2_;
};

// The acceleration changes e_p - e_{p-1} at the span's ticks.
void AddCorrection(const std::vector<double>& correction, Span span, TickWeights* weights) {
  double previous = 0.0;
  for (long p = 0; p <= span.periods; ++p) {
    const double current = p < span.periods ? correction[p] : 0.0;
    WeightAt(weights, span.first_tick + p) += current - previous;
    previous = current;
  }
}

// The split group's weights corrected so that its phasor at every design frequency is the
// ideal group's (see the header), unless rounding alone separates them.
void MatchPhasors(const std::vector<Impulse>& group, double period_s, const GridDesign& design,
                  Span span, double accel_before_m_s2, double accel_limit_m_s2,
                  TickWeights* weights) {
  const GroupPhasor phase{design, span.first_tick, period_s};
  const std::vector<std::complex<double>> mismatch =
      PhasorMismatch(group, *weights, phase, period_s);
  if (OnlyRoundingLeft(group, design, span, period_s, mismatch)) return;
  const TickPhasors tick_phase(phase, span);
  const LeastCorrection least(span, tick_phase, mismatch,
                              AccelerationLevels(*weights, span, accel_before_m_s2),
                              accel_limit_m_s2);
  std::vector<double> correction = least.Solve(true);
  if (correction.empty()) correction = least.Solve(false);
  if (!correction.empty()) AddCorrection(correction, span, weights);
}

}  // namespace

std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       const GridDesign& design, double accel_before_m_s2,
                                       double accel_limit_m_s2) {
  TickWeights weights = SplitBetweenTicks(group, period_s);
  const Span span{weights.front().first, weights.back().first - weights.front().first};
  // The least squares needs at least as many periods as rows (velocity + a phasor each).
  const long rows = 1 + 2 * static_cast<long>(design.frequencies_hz.size());
  if (group.size() >= 2 && span.periods >= rows && IsDesigned(design)) {
    MatchPhasors(group, period_s, design, span, accel_before_m_s2, accel_limit_m_s2, &weights);
  }
  return NonZero(weights);
}

}  // namespace shapebench::controller
