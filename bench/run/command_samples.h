// The command per tick, computed once before the plant runs: velocity v_k (k = 0..n), the
// acceleration a_k held over period k (k = 1..n; a_0 = 0, also the tail's), position p_k.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
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
  // The ticks k (1..n) whose acceleration differs from a_{k-1} (1 always): a run reads
  // what depends on a_k alone once per held acceleration, not once per tick.
  std::vector<std::size_t> accel_changes;
  // The runs [first, end) of steady ticks: moving, the acceleration 0 or within 1e-9 of
  // the largest (the cruise probes, run_window.cc).
  std::vector<std::pair<std::size_t, std::size_t>> steady_runs;
  // Per axis: whether any of the command's velocities (velocity_m_s) is not 0.
  std::array<bool, controller::kNumAxes> axis_moves{};
  // Per axis: sum over k of |a_k| times the period (m/s): a mode starting at rest never
  // deflects by more than its gain / w_d times this (|impulse response| <= 1 / w_d), which
  // tells a run where the tool cannot reach a line's ends (closed_form_sampler.cc).
  std::array<double, controller::kNumAxes> accel_l1_m_s{};
  // Per axis: the positions never decrease (+1) or never increase (-1) from tick to tick;
  // 0 when they do both.
  std::array<int, controller::kNumAxes> monotone{};

  // The acceleration held over period k; after the command, none.
  const Eigen::Vector3d& AccelAt(std::size_t k) const { return k <= n ? accel[k] : accel[0]; }
};

CommandSamples SampleCommand(const controller::MultiAxisCommand& command);

}  // namespace shapebench::bench
