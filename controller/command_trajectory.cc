#include "controller/command_trajectory.h"

#include <algorithm>
#include <cmath>

namespace shapebench::controller {

std::vector<double> CommandTrajectory::Positions() const {
  std::vector<double> positions(velocity_m_s.size(), 0.0);
  for (std::size_t k = 1; k < velocity_m_s.size(); ++k) {
    positions[k] = positions[k - 1] + increment_m(k);
  }
  return positions;
}

double CommandTrajectory::MaxAbsAccel() const {
  double max_accel = 0.0;
  for (std::size_t k = 1; k < velocity_m_s.size(); ++k) {
    max_accel = std::max(max_accel, std::abs(accel_m_s2(k)));
  }
  return max_accel;
}

}  // namespace shapebench::controller
