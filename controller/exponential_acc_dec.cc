// Post-interpolation exponential acc/dec (seed 004 paras. 26-32); see the header.
#include "controller/exponential_acc_dec.h"

#include <cmath>

namespace shapebench::controller {

std::vector<double> ExponentialAccDecPulses(const std::vector<double>& pulses,
                                            double time_constant_s, double period_s) {
  const double tau = time_constant_s;
  const double dt = period_s;
  // y' = (u - y) / tau with u linear between ticks:
  // y_k = beta y_{k-1} + (1 - beta) u_{k-1} + (u_k - u_{k-1}) (1 - tau (1 - beta) / dt).
  const double beta = std::exp(-dt / tau);
  const double ramp_gain = 1.0 - tau * (1.0 - beta) / dt;
  std::vector<double> out;
  out.reserve(pulses.size() + static_cast<std::size_t>(30.0 * tau / dt));
  double y = 0.0;
  double u_prev = 0.0;
  double input_sum = 0.0;
  double output_sum = 0.0;
  constexpr double kTailM = 1e-12;
  for (std::size_t k = 0;; ++k) {
    const double u = k < pulses.size() ? pulses[k] / dt : 0.0;
    y = beta * y + (1.0 - beta) * u_prev + (u - u_prev) * ramp_gain;
    u_prev = u;
    if (k < pulses.size()) input_sum += pulses[k];
    const double remaining = input_sum - output_sum;
    if (k >= pulses.size() && std::abs(remaining - y * dt) + std::abs(y) * tau <= kTailM) {
      out.push_back(remaining);  // the sub-picometre rest of the decay, so nothing is lost
      break;
    }
    out.push_back(y * dt);
    output_sum += y * dt;
  }
  return out;
}

CommandTrajectory ApplyExponentialAccDec(const CommandTrajectory& input, double time_constant_s) {
  const double dt = input.period_s;
  std::vector<double> pulses;
  for (std::size_t k = 1; k < input.velocity_m_s.size(); ++k) pulses.push_back(input.velocity_m_s[k] * dt);
  CommandTrajectory output;
  output.period_s = dt;
  output.velocity_m_s.push_back(0.0);
  for (double pulse : ExponentialAccDecPulses(pulses, time_constant_s, dt)) {
    output.velocity_m_s.push_back(pulse / dt);
  }
  if (output.velocity_m_s.back() != 0.0) output.velocity_m_s.push_back(0.0);
  return output;
}

}  // namespace shapebench::controller
