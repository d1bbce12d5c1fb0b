#include "controller/grid_realization.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include <Eigen/Dense>

namespace shapebench::controller {

std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       double design_frequency_hz, double accel_before_m_s2,
                                       double accel_limit_m_s2) {
  std::map<long, double> weights;  // ordered by tick: deterministic sums
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
    weights[tick] += impulse.amplitude * (1.0 - fraction);
    if (fraction > 0.0) weights[tick + 1] += impulse.amplitude * fraction;
  }
  const long first_tick = weights.begin()->first;
  const long periods = weights.rbegin()->first - first_tick;  // the group's span
  if (group.size() >= 2 && periods >= 3 && design_frequency_hz > 0.0) {
    const double w = 2.0 * 3.14159265358979323846 * design_frequency_hz;
    // Phases relative to the group's first tick keep the system well conditioned.
    auto phase = [&](double t_s) { return std::polar(1.0, w * (t_s - first_tick * period_s)); };
    std::complex<double> mismatch = 0.0;  // jerk phasor: ideal minus plain split
    for (const Impulse& impulse : group) mismatch += impulse.amplitude * phase(impulse.time_s);
    for (const auto& [tick, weight] : weights) mismatch -= weight * phase(tick * period_s);
    // Correct the acceleration of periods of the span by e_p, as little as possible
    // (least squares, spread over the span rather than piled onto one period):
    // sum e_p = 0 keeps the velocity after the group, and
    // sum e_p (e^{iwt_{p+1}} - e^{iwt_p}) = -mismatch makes the jerk phasor the ideal one.
    // Periods already at the largest acceleration are left alone where possible, so the
    // correction does not raise the run's peak acceleration (and static deflection).
    std::vector<double> level(periods);  // acceleration over each period of the span
    double running = accel_before_m_s2;
    for (long p = 0; p < periods; ++p) {
      const auto it = weights.find(first_tick + p);
      if (it != weights.end()) running += it->second;
      level[p] = running;
    }
    auto solve = [&](bool spare_the_peak) -> std::vector<double> {
      std::vector<long> free;
      for (long p = 0; p < periods; ++p) {
        if (!spare_the_peak || std::abs(level[p]) < accel_limit_m_s2 * (1.0 - 1e-9)) free.push_back(p);
      }
      if (free.size() < 3) return {};
      Eigen::MatrixXd constraints(3, static_cast<long>(free.size()));
      for (std::size_t i = 0; i < free.size(); ++i) {
        const long p = free[i];
        const std::complex<double> c =
            phase((first_tick + p + 1) * period_s) - phase((first_tick + p) * period_s);
        constraints(0, i) = 1.0;
        constraints(1, i) = c.real();
        constraints(2, i) = c.imag();
      }
      const Eigen::Vector3d rhs(0.0, -mismatch.real(), -mismatch.imag());
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
        weights[first_tick + p] += current - previous;  // acceleration change at the tick
        previous = current;
      }
    }
  }
  std::vector<GridImpulse> result;
  for (const auto& [tick, weight] : weights) {
    if (weight != 0.0) result.push_back({tick, weight});
  }
  return result;
}

}  // namespace shapebench::controller
