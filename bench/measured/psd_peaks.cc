// The log's modes (see the header).
#include "bench/measured/psd_peaks.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

// Walks from peak `i` in `direction` until the PSD falls below half the peak: the
// crossing's frequency (interpolated), or NaN at the band's edge; *higher when a bin
// above the peak came first (the peak is a shoulder of a higher one).
double HalfPowerCrossing(const std::vector<double>& f, const std::vector<double>& p, std::size_t i, int direction,
                         bool* higher) {
  const double half = p[i] / 2.0;
  for (std::size_t k = i;;) {
    if ((direction < 0 && k == 0) || (direction > 0 && k + 1 == p.size())) return NAN;
    const std::size_t next = direction < 0 ? k - 1 : k + 1;
    if (p[next] > p[i]) {
      *higher = true;
      return NAN;
    }
    if (p[next] < half) return f[k] + (f[next] - f[k]) * (p[k] - half) / (p[k] - p[next]);
    k = next;
  }
}

// The vertex of the parabola through the logs of the bins around `i`, in bins from i.
double LogParabolaOffset(const std::vector<double>& p, std::size_t i) {
  if (i == 0 || i + 1 == p.size() || !(p[i - 1] > 0.0) || !(p[i + 1] > 0.0)) return 0.0;
  const double a = std::log(p[i - 1]);
  const double b = std::log(p[i]);
  const double c = std::log(p[i + 1]);
  const double curvature = a - 2.0 * b + c;
  return curvature < 0.0 ? std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5) : 0.0;
}

}  // namespace

std::vector<LogMode> PickPsdPeaks(const std::vector<double>& f, const std::vector<double>& p) {
  const double threshold = *std::max_element(p.begin(), p.end()) / 20.0;
  std::vector<LogMode> modes;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool above_left = i == 0 || p[i] > p[i - 1];
    const bool above_right = i + 1 == p.size() || p[i] >= p[i + 1];
    if (!(p[i] >= threshold && above_left && above_right)) continue;
    bool higher = false;
    const double low = HalfPowerCrossing(f, p, i, -1, &higher);
    const double high = HalfPowerCrossing(f, p, i, +1, &higher);
    if (higher) continue;
    const double bin = f.size() > 1 ? f[1] - f[0] : 1.0;
    LogMode mode;
    mode.frequency_hz = f[i] + LogParabolaOffset(p, i) * bin;
    mode.peak_psd = p[i];
    double width = high - low;
    if (std::isnan(low) && std::isnan(high)) width = bin;  // a lone bin at both edges
    else if (std::isnan(low)) width = 2.0 * (high - mode.frequency_hz);
    else if (std::isnan(high)) width = 2.0 * (mode.frequency_hz - low);
    mode.damping_ratio = std::clamp(width / (2.0 * mode.frequency_hz), 1e-4, 0.99);
    modes.push_back(mode);
  }
  double total = 0.0;
  for (LogMode& mode : modes) {
    const double w = 2.0 * kPi * mode.frequency_hz;
    mode.share = 2.0 * mode.damping_ratio * std::sqrt(mode.peak_psd) / (w * w);
    total += mode.share;
  }
  for (LogMode& mode : modes) mode.share /= total;
  return modes;
}

model::ModalMachineConfig ModesMachine(const std::vector<LogMode>& modes, double static_deflection_per_accel_s2) {
  model::ModalMachineConfig machine;
  machine.modes.clear();
  for (const LogMode& mode : modes) {
    const double w = 2.0 * kPi * mode.frequency_hz;
    machine.modes.push_back({mode.frequency_hz, mode.damping_ratio, mode.share * static_deflection_per_accel_s2 * w * w});
  }
  return machine;
}

}  // namespace shapebench::bench
