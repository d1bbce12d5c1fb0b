#include "bench/run/command_samples.h"

#include <algorithm>
#include <cmath>

namespace shapebench::bench {
namespace {

// One axis' column of the samples, as MultiAxisCommand's velocity_m_s, accel_m_s2 and
// Positions compute them. (Plain pointers and a local count: the stores are doubles, and
// a double member reached through `s` could alias them for all the compiler knows.)
void SampleAxis(const controller::MultiAxisCommand& command, int axis, CommandSamples* s) {
  const controller::CommandTrajectory& trajectory = command.axes[axis];
  const std::vector<double>& v = trajectory.velocity_m_s;
  const std::size_t n = s->n;
  Eigen::Vector3d* velocity = s->velocity.data();
  Eigen::Vector3d* accel = s->accel.data();
  Eigen::Vector3d* positions = s->positions.data();
  velocity[0](axis) = v[0];
  double position = command.start_m(axis);
  if (std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0 && !std::signbit(x); })) {
    // An axis that does not move: the same sums, of zeros (the first turns -0 into +0).
    position += 0.0;
    for (std::size_t k = 1; k <= n; ++k) {
      velocity[k](axis) = 0.0;
      positions[k](axis) = position;
    }
    return;
  }
  for (std::size_t k = 1; k <= n; ++k) {
    velocity[k](axis) = v[k];
    accel[k](axis) = trajectory.accel_m_s2(k);
    position += trajectory.increment_m(k);
    positions[k](axis) = position;
  }
}

}  // namespace

CommandSamples SampleCommand(const controller::MultiAxisCommand& command) {
  CommandSamples s;
  s.n = command.num_ticks();
  s.velocity.resize(s.n + 1);
  s.accel.assign(s.n + 1, Eigen::Vector3d::Zero());
  s.positions.assign(s.n + 1, command.start_m);
  for (int axis = 0; axis < controller::kNumAxes; ++axis) {
    SampleAxis(command, axis, &s);
    const std::vector<double>& v = command.axes[axis].velocity_m_s;
    s.axis_moves[axis] = std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  }
  // Largest squared norms, their roots below: the root of the largest square is the
  // largest norm (norm() is the root of squaredNorm(), the root is monotone).
  double max_accel_sq = 0.0;
  double max_speed_sq = 0.0;
  for (std::size_t k = 1; k <= s.n; ++k) {
    max_accel_sq = std::max(max_accel_sq, s.accel[k].squaredNorm());
    max_speed_sq = std::max(max_speed_sq, s.velocity[k].squaredNorm());
  }
  for (int axis = 0; axis < controller::kNumAxes; ++axis) {
    double l1 = 0.0;
    bool up = true;
    bool down = true;
    for (std::size_t k = 1; k <= s.n; ++k) {
      l1 += std::abs(s.accel[k](axis));
      up = up && s.positions[k](axis) >= s.positions[k - 1](axis);
      down = down && s.positions[k](axis) <= s.positions[k - 1](axis);
    }
    s.accel_l1_m_s[axis] = l1 * command.period_s;
    s.monotone[axis] = up ? 1 : down ? -1 : 0;
  }
  s.max_accel_m_s2 = std::sqrt(max_accel_sq);
  s.max_speed_m_s = std::sqrt(max_speed_sq);
  std::size_t last_moving = 0;
  for (std::size_t k = s.n + 1; k-- > 0;) {
    const Eigen::Vector3d& v = s.velocity[k];
    if (v(0) != 0.0 || v(1) != 0.0 || v(2) != 0.0) {
      last_moving = k;
      break;
    }
  }
  s.motion_ticks = std::min(last_moving + 1, s.n);
  for (std::size_t k = 1; k <= s.n; ++k) {
    const Eigen::Vector3d& a = s.accel[k];
    const Eigen::Vector3d& before = s.accel[k - 1];
    if (k == 1 || a(0) != before(0) || a(1) != before(1) || a(2) != before(2)) s.accel_changes.push_back(k);
  }
  for (std::size_t k = 1, run_start = 1; k <= s.n + 1; ++k) {
    const bool steady =
        k <= s.n && (s.velocity[k](0) != 0.0 || s.velocity[k](1) != 0.0 || s.velocity[k](2) != 0.0) &&
        (s.accel[k].squaredNorm() == 0.0 || s.accel[k].norm() <= 1e-9 * s.max_accel_m_s2);
    if (steady) continue;
    if (k > run_start) s.steady_runs.emplace_back(run_start, k);
    run_start = k + 1;
  }
  return s;
}

}  // namespace shapebench::bench
