#include "controller/grid_realization.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include <Eigen/Dense>

namespace shapebench::controller {

std::vector<GridImpulse> RealizeOnGrid(const std::vector<Impulse>& group, double period_s,
                                       double design_frequency_hz) {
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
  const int n = static_cast<int>(weights.size());
  if (group.size() >= 2 && n >= 4 && design_frequency_hz > 0.0) {
    const double w = 2.0 * 3.14159265358979323846 * design_frequency_hz;
    const long t_ref = weights.begin()->first;  // phases relative to the group: conditioning
    std::complex<double> ideal = 0.0;
    for (const Impulse& impulse : group) {
      ideal += impulse.amplitude * std::polar(1.0, w * (impulse.time_s - t_ref * period_s));
    }
    std::complex<double> realized = 0.0;
    Eigen::MatrixXd constraints(4, n);
    int col = 0;
    for (const auto& [tick, weight] : weights) {
      const double t = static_cast<double>(tick - t_ref) * period_s;
      realized += weight * std::polar(1.0, w * t);
      constraints(0, col) = 1.0;              // acceleration after the group unchanged
      constraints(1, col) = t / period_s;     // velocity after the group unchanged
      constraints(2, col) = std::cos(w * t);  // vibration phasor ...
      constraints(3, col) = std::sin(w * t);  // ... equal to the ideal group's
      ++col;
    }
    Eigen::Vector4d rhs(0.0, 0.0, (ideal - realized).real(), (ideal - realized).imag());
    // Minimum-norm correction: the smallest change to the plain split.
    const Eigen::VectorXd delta = constraints.completeOrthogonalDecomposition().solve(rhs);
    if ((constraints * delta - rhs).norm() <= 1e-9 * (1.0 + rhs.norm())) {
      col = 0;
      for (auto& entry : weights) entry.second += delta(col++);
    }
  }
  std::vector<GridImpulse> result;
  for (const auto& [tick, weight] : weights) {
    if (weight != 0.0) result.push_back({tick, weight});
  }
  return result;
}

}  // namespace shapebench::controller
