// The log's modes by the modal fit (see the header).
#include "bench/measured/log_modes.h"

#include <algorithm>
#include <cmath>

#include "bench/measured/modal_psd_fit.h"
#include "bench/measured/welch_psd.h"
#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

constexpr double kHalfWidthsEachWay = 2.0;
constexpr double kMinReachHz = 5.0;
constexpr int kKernelSub = 2;
constexpr int kKernelBins = 8;

// The rectangular window's power kernel, sinc^2 of the offset in bins, sampled
// kKernelSub times a bin over +/- kKernelBins bins, summing to 1.
std::vector<double> SincSquaredKernel() {
  std::vector<double> kernel;
  double sum = 0.0;
  for (int t = -kKernelBins * kKernelSub; t <= kKernelBins * kKernelSub; ++t) {
    const double x = kPi * t / kKernelSub;
    const double value = t == 0 ? 1.0 : std::pow(std::sin(x) / x, 2);
    kernel.push_back(value);
    sum += value;
  }
  for (double& value : kernel) value /= sum;
  return kernel;
}

bool SmallFactors(int n) {
  for (const int p : {2, 3, 5, 7}) {
    while (n % p == 0) n /= p;
  }
  return n == 1;
}

// The bins of the fit: one range per group of peaks, [from, to] Hz, and the peaks in it.
struct PeakGroup {
  double from_hz = 0.0;
  double to_hz = 0.0;
  std::vector<std::size_t> peaks;
};

std::vector<PeakGroup> GroupPeaks(const std::vector<LogMode>& found) {
  std::vector<PeakGroup> groups;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const double reach = std::max(kHalfWidthsEachWay * 2.0 * found[i].damping_ratio * found[i].frequency_hz, kMinReachHz);
    PeakGroup group{std::max(found[i].frequency_hz - reach, kFitMinHz), std::min(found[i].frequency_hz + reach, kFitMaxHz),
                    {i}};
    if (!groups.empty()) {
      PeakGroup& last = groups.back();
      const double narrower = std::min(last.to_hz - last.from_hz, group.to_hz - group.from_hz);
      if (group.from_hz - last.to_hz < narrower) {
        last.to_hz = std::max(last.to_hz, group.to_hz);
        last.peaks.push_back(i);
        continue;
      }
    }
    groups.push_back(group);
  }
  return groups;
}

// Why the fit of `group` is not to be trusted, or "": the fit's own trouble, or a damping
// ratio above kMaxWidening x the peak's half-power one (an upper bound where the window
// widens the peak: the model does not describe the spectrum there, e.g. an excitation that
// ends inside the range).
std::string Untrusted(const ModalPsdFit& fit, const PeakGroup& group, const std::vector<LogMode>& found) {
  constexpr double kMaxWidening = 1.5;
  if (!fit.trouble.empty()) return fit.trouble;
  if (fit.modes.size() != group.peaks.size()) return "no result";
  for (std::size_t j = 0; j < group.peaks.size(); ++j) {
    const LogMode& peak = found[group.peaks[j]];
    if (fit.modes[j].damping_ratio > kMaxWidening * peak.damping_ratio) {
      return "damping ratio " + FormatNumber(fit.modes[j].damping_ratio) + " at " +
             FormatNumber(fit.modes[j].frequency_hz) + " Hz, above " + FormatNumber(kMaxWidening) +
             " x the peak's half-power " + FormatNumber(peak.damping_ratio) + ": the model does not fit there";
    }
  }
  return "";
}

// Fits `group`'s peaks into out->modes; a group of several whose joint fit is not trusted
// is fitted peak by peak; a peak whose fit is not trusted keeps its half-power values,
// warned.
void FitGroup(const ModalPsdInput& input, const std::vector<LogMode>& found, const PeakGroup& group, LogModes* out) {
  std::vector<ModalPsdGuess> guesses;
  for (const std::size_t i : group.peaks) guesses.push_back({found[i].frequency_hz, found[i].damping_ratio});
  const ModalPsdFit fit = FitModalPsd(input, guesses, group.from_hz, group.to_hz);
  const std::string why = Untrusted(fit, group, found);
  if (why.empty()) {
    for (std::size_t j = 0; j < group.peaks.size(); ++j) {
      LogMode& mode = out->modes[group.peaks[j]];
      mode.frequency_hz = fit.modes[j].frequency_hz;
      mode.damping_ratio = fit.modes[j].damping_ratio;
      mode.frequency_uncertainty_hz = fit.modes[j].frequency_uncertainty_hz;
      mode.damping_uncertainty = fit.modes[j].damping_uncertainty;
    }
    return;
  }
  if (group.peaks.size() > 1) {
    for (const std::size_t i : group.peaks) {
      const std::vector<PeakGroup> alone = GroupPeaks({found[i]});
      FitGroup(input, found, {alone[0].from_hz, alone[0].to_hz, {i}}, out);
    }
    return;
  }
  out->warnings.push_back("the modal fit of the peak at " + FormatNumber(found[group.peaks[0]].frequency_hz) +
                          " Hz over " + FormatNumber(group.from_hz) + "-" + FormatNumber(group.to_hz) + " Hz failed (" +
                          why + "): its half-power values kept");
}

// Fits every group of `input` (above); the shares from the dampings found.
void FitGroups(const ModalPsdInput& input, const std::vector<LogMode>& found, LogModes* out) {
  out->modes = found;
  for (const PeakGroup& group : GroupPeaks(found)) FitGroup(input, found, group, out);
  double total = 0.0;
  for (LogMode& mode : out->modes) {
    const double w = kTwoPi * mode.frequency_hz;
    mode.share = 2.0 * mode.damping_ratio * std::sqrt(mode.peak_psd) / (w * w);
    total += mode.share;
  }
  for (LogMode& mode : out->modes) mode.share /= total;
}

// The segment length for `resolution_hz` (0: the whole log).
int FitSegmentSamples(std::size_t samples, double rate_hz, double resolution_hz) {
  if (resolution_hz <= 0.0) {
    int m = static_cast<int>(samples - 1) & ~1;
    while (m > 2 && !SmallFactors(m)) m -= 2;
    return m;
  }
  const int m = 2 * static_cast<int>(std::lround(rate_hz / (2.0 * resolution_hz)));
  if (m < 2 || static_cast<std::size_t>(m) >= samples) {
    throw ValidationError("--resolution-hz", "finer than the log allows: " + std::to_string(samples) +
                                                 " samples at " + FormatNumber(rate_hz) + " Hz resolve at best " +
                                                 FormatNumber(rate_hz / static_cast<double>(samples - 1)) + " Hz (got " +
                                                 FormatNumber(resolution_hz) + ")");
  }
  return m;
}

}  // namespace

LogModes FitLogModes(const UniformAccel& samples, AccelAxis axis, const std::vector<LogMode>& found,
                     double resolution_hz) {
  const std::size_t n = samples.accel_mm_s2[0].size();
  const int m = FitSegmentSamples(n, samples.sample_rate_hz, resolution_hz);
  const std::vector<double> window(static_cast<std::size_t>(m), 1.0);
  ModalPsdInput input;
  Psd psd;
  for (int a = 0; a < 3; ++a) {
    if (axis != AccelAxis::kAll && static_cast<int>(axis) != a) continue;
    const Psd one = WelchPsdWindowed(samples.accel_mm_s2[static_cast<std::size_t>(a)], samples.sample_rate_hz, window);
    if (psd.density.empty()) {
      psd = one;
    } else {
      for (std::size_t k = 0; k < psd.density.size(); ++k) psd.density[k] += one.density[k];
    }
  }
  input.frequency_hz = psd.frequency_hz;
  input.psd = psd.density;
  input.kernel = SincSquaredKernel();
  input.kernel_sub = kKernelSub;
  const double k = psd.segments;
  input.relative_variance = (1.0 + (k - 1.0) / (2.0 * k)) / k;
  LogModes out;
  out.spectrum = psd.segments == 1 ? "periodogram" : "welch";
  out.resolution_hz = samples.sample_rate_hz / m;
  out.segment_samples = m;
  out.segments = psd.segments;
  out.uncertainty = "the Whittle fit's inverse information times a bin's relative variance from its " +
                    std::to_string(psd.segments) + " segment(s)";
  FitGroups(input, found, &out);
  return out;
}

LogModes FitPsdModes(const std::vector<double>& frequency_hz, const std::vector<double>& psd,
                     const std::vector<LogMode>& found) {
  ModalPsdInput input;
  input.frequency_hz = frequency_hz;
  input.psd = psd;
  LogModes out;
  out.spectrum = "psd file";
  out.resolution_hz = frequency_hz.size() > 1 ? frequency_hz[1] - frequency_hz[0] : 0.0;
  out.uncertainty = "the Whittle fit's inverse information times the residuals' relative variance";
  FitGroups(input, found, &out);
  return out;
}

}  // namespace shapebench::bench
