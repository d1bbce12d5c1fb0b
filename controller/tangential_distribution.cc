#include "controller/tangential_distribution.h"

#include <algorithm>

namespace shapebench::controller {

void TangentialQueue::Push(const MinuteDisplacement& input) {
  queue_.push_back({input, input});
}

double TangentialQueue::queued_tangential_m() const {
  double total = 0.0;
  for (const Entry& e : queue_) total += e.remaining.tangential_m;
  return total;
}

Eigen::Vector3d TangentialQueue::Release(double so_m) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  double so = so_m;  // what is left of SO this period
  // Decision 1: SO = 0 ends the cycle.
  while (so > 0.0 && !queue_.empty()) {
    Entry& front = queue_.front();
    // Decision 2: a segment for output with nothing tangential left is done; the next
    // one becomes the segment for output (output constant specifying means 4). Its axis
    // remainder (zero but for rounding) goes out with it, so nothing is lost.
    if (front.remaining.tangential_m <= 0.0) {
      out += front.remaining.axes_m;
      queue_.pop_front();
      continue;
    }
    // Decision 3.
    if (front.remaining.tangential_m <= so) {
      // First output means 5: the whole segment for output goes out.
      out += front.remaining.axes_m;
      so -= front.remaining.tangential_m;
      queue_.pop_front();
    } else {
      // Second output means 6: W = SO * K_axis / K_S, subtracted from the segment.
      const Eigen::Vector3d w = so * front.constants.axes_m / front.constants.tangential_m;
      out += w;
      front.remaining.axes_m -= w;
      front.remaining.tangential_m -= so;
      so = 0.0;
    }
  }
  return out;
}

Eigen::Vector3d TangentialQueue::Flush() {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (const Entry& e : queue_) out += e.remaining.axes_m;
  queue_.clear();
  return out;
}

std::vector<Eigen::Vector3d> DistributeTangentially(
    const std::vector<Eigen::Vector3d>& axis_pulses, const std::vector<double>& tangential_pulses,
    const PulseFilter& filter, double period_s) {
  const std::vector<double> so = filter.Apply(tangential_pulses, period_s);
  TangentialQueue queue;
  std::vector<Eigen::Vector3d> out;
  out.reserve(so.size());
  for (std::size_t k = 0; k < so.size(); ++k) {
    if (k < axis_pulses.size()) queue.Push({axis_pulses[k], tangential_pulses[k]});
    out.push_back(queue.Release(so[k]));
  }
  if (!out.empty()) out.back() += queue.Flush();
  return out;
}

}  // namespace shapebench::controller
