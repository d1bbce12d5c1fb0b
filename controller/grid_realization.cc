#include "controller/grid_realization.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

namespace shapebench::controller {

std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       const GridDesign& design, double accel_before_m_s2,
                                       double accel_limit_m_s2) {
  // (tick, weight) ordered by tick: deterministic sums. A sorted vector, not a map: a group
  // has a handful of ticks, and this runs dozens of times per command (the exact-distance
  // search); the arithmetic (each += in impulse order) is the same.
  std::vector<std::pair<long, double>> weights;
  weights.reserve(2 * group.size() + 2);
  auto weight = [&weights](long tick) -> double& {
    auto it = std::lower_bound(weights.begin(), weights.end(), tick,
                               [](const std::pair<long, double>& w, long t) { return w.first < t; });
    if (it == weights.end() || it->first != tick) it = weights.insert(it, {tick, 0.0});
    return it->second;
  };
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
    weight(tick) += impulse.amplitude * (1.0 - fraction);
    if (fraction > 0.0) weight(tick + 1) += impulse.amplitude * fraction;
  }
  const long first_tick = weights.front().first;
  const long periods = weights.back().first - first_tick;  // the group's span
  const std::size_t frequencies = design.frequencies_hz.size();
  const long rows = 1 + 2 * static_cast<long>(frequencies);  // velocity + a phasor each
  bool designed = frequencies > 0;
  for (const double f : design.frequencies_hz) designed = designed && f > 0.0 && std::isfinite(f);
  if (group.size() >= 2 && periods >= rows && designed) {
    const double zeta = design.damping_ratio;
    // Phasors relative to the group's first tick keep the system well conditioned. The
    // damped phasor e^{(zeta w + i w_d) t}; undamped, exactly the plain e^{iwt}.
    auto phase = [&](std::size_t j, double t_s) {
      const double w = 2.0 * 3.14159265358979323846 * design.frequencies_hz[j];
      const double dt = t_s - first_tick * period_s;
      if (zeta == 0.0) return std::polar(1.0, w * dt);
      return std::exp(zeta * w * dt) * std::polar(1.0, w * std::sqrt(1.0 - zeta * zeta) * dt);
    };
    std::vector<std::complex<double>> mismatch(frequencies, 0.0);  // ideal minus plain split
    // What rounding alone leaves in the mismatch: the phase of a time t is good to about
    // w eps |t| (and the sums to eps): a group whose steps lie on ticks leaves only that,
    // and a correction of it would be noise on every tick of the span.
    double scale = 0.0;
    double latest_s = 0.0;
    for (const Impulse& impulse : group) {
      scale += std::abs(impulse.amplitude);
      latest_s = std::max(latest_s, std::abs(impulse.time_s));
    }
    latest_s = std::max(latest_s, std::abs((first_tick + periods) * period_s));
    bool rounding_only = true;
    for (std::size_t j = 0; j < frequencies; ++j) {
      for (const Impulse& impulse : group) mismatch[j] += impulse.amplitude * phase(j, impulse.time_s);
      for (const auto& [tick, weight] : weights) mismatch[j] -= weight * phase(j, tick * period_s);
      const double w = 2.0 * 3.14159265358979323846 * design.frequencies_hz[j];
      const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * (1.0 + w * latest_s);
      rounding_only = rounding_only && std::abs(mismatch[j]) <= rounding * scale;
    }
    if (rounding_only) {
      std::vector<GridImpulse> result;
      result.reserve(weights.size());
      for (const auto& [tick, w] : weights) {
        if (w != 0.0) result.push_back({tick, w});
      }
      return result;
    }
    // The phasor at each tick of the span, once (the same values the least squares below
    // would compute again and again); only here: a group on ticks needs a few of them.
    std::vector<std::complex<double>> tick_phase((periods + 1) * frequencies);
    for (std::size_t j = 0; j < frequencies; ++j) {
      for (long p = 0; p <= periods; ++p) {
        tick_phase[j * (periods + 1) + p] = phase(j, (first_tick + p) * period_s);
      }
    }
    auto phase_at_tick = [&](std::size_t j, long tick) {
      return tick_phase[j * (periods + 1) + (tick - first_tick)];
    };
    // Correct the acceleration of periods of the span by e_p, as little as possible
    // (least squares, spread over the span rather than piled onto one period):
    // sum e_p = 0 keeps the velocity after the group, and
    // sum e_p (e^{iwt_{p+1}} - e^{iwt_p}) = -mismatch makes the jerk phasor the ideal one
    // (one such pair of rows per design frequency).
    // Periods already at the largest acceleration are left alone where possible, so the
    // correction does not raise the run's peak acceleration (and static deflection).
    std::vector<double> level(periods);  // acceleration over each period of the span
    double running = accel_before_m_s2;
    for (long p = 0, next = 0; p < periods; ++p) {
      if (weights[next].first == first_tick + p) running += weights[next++].second;
      level[p] = running;
    }
    auto solve = [&](bool spare_the_peak) -> std::vector<double> {
      std::vector<long> free;
      for (long p = 0; p < periods; ++p) {
        if (!spare_the_peak || std::abs(level[p]) < accel_limit_m_s2 * (1.0 - 1e-9)) free.push_back(p);
      }
      if (static_cast<long>(free.size()) < rows) return {};
      Eigen::MatrixXd constraints(rows, static_cast<long>(free.size()));
      for (std::size_t i = 0; i < free.size(); ++i) {
        const long p = free[i];
        constraints(0, i) = 1.0;
        for (std::size_t j = 0; j < frequencies; ++j) {
          const std::complex<double> c =
              phase_at_tick(j, first_tick + p + 1) - phase_at_tick(j, first_tick + p);
          constraints(1 + 2 * j, i) = c.real();
          constraints(2 + 2 * j, i) = c.imag();
        }
      }
      Eigen::VectorXd rhs(rows);
      rhs(0) = 0.0;
      for (std::size_t j = 0; j < frequencies; ++j) {
        rhs(1 + 2 * j) = -mismatch[j].real();
        rhs(2 + 2 * j) = -mismatch[j].imag();
      }
      const Eigen::VectorXd e = constraints.completeOrthogonalDecomposition().solve(rhs);
      if ((constraints * e - rhs).norm() > 1e-9 * (1.0 + rhs.norm())) return {};
      std::vector<double> correction(periods, 0.0);
      for (std::size_t i = 0; i < free.size(); ++i) correction[free[i]] = e(i);
      if (spare_the_peak) {
        for (long p = 0; p < periods; ++p) {
          if (std::abs(level[p] + correction[p]) > accel_limit_m_s2 * (1.0 + 1e-12)) return {};
        }
      }
      return correction;
    };
    std::vector<double> correction = solve(true);
    if (correction.empty()) correction = solve(false);
    if (!correction.empty()) {
      double previous = 0.0;
      for (long p = 0; p <= periods; ++p) {
        const double current = p < periods ? correction[p] : 0.0;
        weight(first_tick + p) += current - previous;  // acceleration change at the tick
        previous = current;
      }
    }
  }
  std::vector<GridImpulse> result;
  result.reserve(weights.size());
  for (const auto& [tick, w] : weights) {
    if (w != 0.0) result.push_back({tick, w});
  }
  return result;
}

}  // namespace shapebench::controller
