#include "controller/pulse_filter.h"

#include <cmath>

#include "controller/exponential_acc_dec.h"

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

}  // namespace

std::vector<double> PulseFilter::Apply(const std::vector<double>& pulses, double period_s) const {
  std::vector<double> out = pulses;
  if (!table.empty()) out = Fir(table, out);
  if (time_constant_s > 0.0) out = ExponentialAccDecPulses(out, time_constant_s, period_s);
  return out;
}

}  // namespace shapebench::controller
