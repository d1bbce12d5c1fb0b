#include "controller/pulse_filter.h"

#include <cmath>

namespace shapebench::controller {
namespace {

std::vector<double> Fir(const std::vector<double>& table, const std::vector<double>& in) {
  if (in.empty()) return in;
  std::vector<double> out(in.size() + table.size() - 1, 0.0);
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in[k] == 0.0) continue;
    for (std::size_t j = 0; j < table.size(); ++j) out[k + j] += table[j] * in[k];
  }
  return out;
}

// The first-order lag y' = (u - y) / tau on the pulse rate u = pulse / period, with u
// linear between ticks (the drive's view): exact at the ticks (the same discretization
// as ApplyExponentialAccDec).
std::vector<double> Exponential(double tau, double dt, const std::vector<double>& in) {
  const double beta = std::exp(-dt / tau);
  const double ramp_gain = 1.0 - tau * (1.0 - beta) / dt;
  std::vector<double> out;
  out.reserve(in.size() + static_cast<std::size_t>(30.0 * tau / dt));
  double y = 0.0;
  double u_prev = 0.0;
  double input_sum = 0.0;
  double output_sum = 0.0;
  constexpr double kTailM = 1e-12;
  for (std::size_t k = 0;; ++k) {
    const double u = k < in.size() ? in[k] / dt : 0.0;
    y = beta * y + (1.0 - beta) * u_prev + (u - u_prev) * ramp_gain;
    u_prev = u;
    if (k < in.size()) input_sum += in[k];
    const double remaining = input_sum - output_sum;
    if (k >= in.size() && std::abs(remaining - y * dt) + std::abs(y) * tau <= kTailM) {
      out.push_back(remaining);  // the sub-picometre rest of the decay, so nothing is lost
      break;
    }
    out.push_back(y * dt);
    output_sum += y * dt;
  }
  return out;
}

}  // namespace

std::vector<double> PulseFilter::Apply(const std::vector<double>& pulses, double period_s) const {
  std::vector<double> out = pulses;
  if (!table.empty()) out = Fir(table, out);
  if (time_constant_s > 0.0) out = Exponential(time_constant_s, period_s, out);
  return out;
}

}  // namespace shapebench::controller
