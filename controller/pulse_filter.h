// The linear, time-invariant part of post-interpolation acc/dec, acting on a sequence of
// per-period move pulses: a profile table (FIR, paras. 52-61) and/or the exponential
// acc/dec of paras. 26-32, in cascade (they commute). Unit DC gain: the output pulses
// add up to the input ones exactly.
#pragma once

#include <vector>

namespace shapebench::controller {

struct PulseFilter {
  std::vector<double> table;     // FIR coefficients summing to 1; empty: none
  double time_constant_s = 0.0;  // exponential; 0: none

  bool is_identity() const { return table.empty() && time_constant_s == 0.0; }

  // pulses[k] is the distance of period k (pulses[0] is period 1). The output is longer
  // by the filter's tail (the table's length - 1; the exponential's decay down to
  // 1e-12 m, whose remainder is put in the last pulse so nothing is lost).
  std::vector<double> Apply(const std::vector<double>& pulses, double period_s) const;
};

}  // namespace shapebench::controller
