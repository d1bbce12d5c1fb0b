// The command per tick, computed once before the plant runs: velocity v_k (k = 0..n), the
// acceleration a_k held over period k (k = 1..n; a_0 = 0, also the tail's), position p_k.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "controller/controller.h"

namespace shapebench::bench {

struct CommandSamples {
  std::size_t n = 0;  // ticks of the command
  std::vector<Eigen::Vector3d> velocity;
  std::vector<Eigen::Vector3d> accel;
  std::vector<Eigen::Vector3d> positions;
  double max_accel_m_s2 = 0.0;  // largest |a_k|
  double max_speed_m_s = 0.0;   // largest |v_k|, k >= 1
  // Motion ends at the tick after the last one whose commanded velocity is not zero.
  std::size_t motion_ticks = 0;

  // The acceleration held over period k; after the command, none.
  const Eigen::Vector3d& AccelAt(std::size_t k) const { return k <= n ? accel[k] : accel[0]; }
};

CommandSamples SampleCommand(const controller::MultiAxisCommand& command);

}  // namespace shapebench::bench
