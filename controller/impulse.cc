// Impulse sequences; see the header.
#include "controller/impulse.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace shapebench::controller {
namespace {

// Impulses of a convolution closer than this are one impulse.
constexpr double kSameTimeS = 1e-12;

}  // namespace

std::vector<Impulse> ConvolveImpulses(const std::vector<Impulse>& a, const std::vector<Impulse>& b) {
  std::vector<Impulse> all;
  for (const Impulse& x : a) {
    for (const Impulse& y : b) all.push_back({x.time_s + y.time_s, x.amplitude * y.amplitude});
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const Impulse& x, const Impulse& y) { return x.time_s < y.time_s; });
  std::vector<Impulse> merged;
  for (const Impulse& i : all) {
    if (!merged.empty() && i.time_s - merged.back().time_s <= kSameTimeS) {
      merged.back().amplitude += i.amplitude;
    } else {
      merged.push_back(i);
    }
  }
  std::vector<Impulse> nonzero;
  for (const Impulse& i : merged) {
    if (i.amplitude != 0.0) nonzero.push_back(i);
  }
  return nonzero;
}

std::vector<Impulse> NormalisedImpulses(std::vector<Impulse> impulses) {
  double total = 0.0;
  for (const Impulse& i : impulses) total += i.amplitude;
  for (Impulse& i : impulses) i.amplitude /= total;
  return impulses;
}

double ResidualVibration(const std::vector<Impulse>& impulses, double frequency_hz,
                         double damping_ratio) {
  if (impulses.empty()) return 0.0;
  const double w = 2.0 * kPi * frequency_hz;
  const double wd = w * std::sqrt(1.0 - damping_ratio * damping_ratio);
  const double t_last = impulses.back().time_s;
  double c = 0.0;
  double s = 0.0;
  double total = 0.0;
  for (const Impulse& impulse : impulses) {
    // Decay measured from the last impulse keeps the exponentials <= 1.
    const double decay = std::exp(-damping_ratio * w * (t_last - impulse.time_s));
    c += impulse.amplitude * decay * std::cos(wd * impulse.time_s);
    s += impulse.amplitude * decay * std::sin(wd * impulse.time_s);
    total += impulse.amplitude;
  }
  return std::hypot(c, s) / std::abs(total);
}

std::vector<Impulse> TableImpulses(const std::vector<double>& table, double period_s) {
  std::vector<Impulse> impulses;
  for (std::size_t n = 0; n < table.size(); ++n) {
    impulses.push_back({static_cast<double>(n) * period_s, table[n]});
  }
  return impulses;
}

double ShaperDuration(const std::vector<Impulse>& impulses) {
  return impulses.empty() ? 0.0 : impulses.back().time_s;
}

double ShaperMeanTime(const std::vector<Impulse>& impulses) {
  double mean = 0.0;
  for (const Impulse& i : impulses) mean += i.amplitude * i.time_s;
  return mean;
}

double ShaperVariance(const std::vector<Impulse>& impulses) {
  const double mean = ShaperMeanTime(impulses);
  double variance = 0.0;
  for (const Impulse& i : impulses) variance += i.amplitude * (i.time_s - mean) * (i.time_s - mean);
  return variance;
}

}  // namespace shapebench::controller
