// What the controller hands the drive: the commanded velocity at every tick
// t_k = k * period_s (k = 0..N). Between ticks the velocity is linear, so the commanded
// acceleration is constant over each interpolation period and the position is the exact
// integral (trapezoids). Every filter of the pipeline is linear and time-invariant on the
// tick grid, so applying it to the velocity samples keeps the three consistent.
#pragma once

#include <cstddef>
#include <vector>

namespace shapebench::controller {

struct CommandTrajectory {
  double period_s = 0.001;
  std::vector<double> velocity_m_s;  // v_0 .. v_N; v_0 = 0 and v_N = 0

  std::size_t num_ticks() const { return velocity_m_s.empty() ? 0 : velocity_m_s.size() - 1; }
  double tick_time_s(std::size_t k) const { return static_cast<double>(k) * period_s; }
  // Acceleration held over period k, i.e. from t_{k-1} to t_k (k = 1..N).
  double accel_m_s2(std::size_t k) const {
    return (velocity_m_s[k] - velocity_m_s[k - 1]) / period_s;
  }
  // Distance covered in period k (the "move pulses" of the patent's para. 60).
  double increment_m(std::size_t k) const {
    return 0.5 * (velocity_m_s[k - 1] + velocity_m_s[k]) * period_s;
  }
  // Positions p_0 .. p_N, summed in tick order (deterministic).
  std::vector<double> Positions() const;
  double MaxAbsAccel() const;
};

}  // namespace shapebench::controller
