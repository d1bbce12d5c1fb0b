// Post-interpolation exponential acc/dec (seed 004 paras. 26-32); see the header.
#include "controller/exponential_acc_dec.h"

#include <cmath>

namespace shapebench::controller {

CommandTrajectory ApplyExponentialAccDec(const CommandTrajectory& input, double time_constant_s,
                                         double tail_tolerance_m) {
  CommandTrajectory output;
  output.period_s = input.period_s;
  const double dt = input.period_s;
  // y' = (u - y) / tau with u linear between ticks (the drive's view of the command):
  // y_k = beta y_{k-1} + (1 - beta) u_{k-1} + (u_k - u_{k-1}) (1 - tau (1 - beta) / dt).
  // Exact at the ticks, and the sum of the samples (the distance) is preserved.
  const double beta = std::exp(-dt / time_constant_s);
  const double ramp_gain = 1.0 - time_constant_s * (1.0 - beta) / dt;
  double remaining_m = 0.0;  // input distance not yet output
  double y = 0.0;
  output.velocity_m_s.push_back(0.0);
  const std::size_t n = input.num_ticks();
  for (std::size_t k = 1;; ++k) {
    const double u_prev = k - 1 <= n ? input.velocity_m_s[k - 1] : 0.0;
    const double u = k <= n ? input.velocity_m_s[k] : 0.0;
    const double y_prev = y;
    y = beta * y_prev + (1.0 - beta) * u_prev + (u - u_prev) * ramp_gain;
    remaining_m += 0.5 * (u_prev + u) * dt - 0.5 * (y_prev + y) * dt;
    if (k > n && std::abs(remaining_m) + std::abs(y) * time_constant_s <= tail_tolerance_m) {
      // The tail is below tolerance: land on rest. What is left of the decay (< tolerance)
      // is the only motion lost.
      output.velocity_m_s.push_back(0.0);
      break;
    }
    output.velocity_m_s.push_back(y);
  }
  return output;
}

}  // namespace shapebench::controller
