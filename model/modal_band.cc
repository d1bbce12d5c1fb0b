// ChooseBand (model/modal_band.h).
#include "model/modal_band.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::model {
namespace {

bool LineFinite(const std::vector<std::vector<std::complex<double>>>& frfs, std::size_t k) {
  for (const auto& frf : frfs) {
    if (!std::isfinite(frf[k].real()) || !std::isfinite(frf[k].imag())) return false;
  }
  return true;
}

// [begin, end): the longest stretch of lines above 0 Hz where every FRF is finite.
std::pair<std::size_t, std::size_t> FiniteRun(const std::vector<double>& frequency_hz,
                                              const std::vector<std::vector<std::complex<double>>>& frfs) {
  std::size_t best_begin = 0, best_end = 0, begin = 0;
  bool open = false;
  for (std::size_t k = 0; k <= frequency_hz.size(); ++k) {
    const bool usable = k < frequency_hz.size() && frequency_hz[k] > 0.0 && LineFinite(frfs, k);
    if (usable && !open) begin = k, open = true;
    if (!usable && open) {
      if (k - begin > best_end - best_begin) best_begin = begin, best_end = k;
      open = false;
    }
  }
  return {best_begin, best_end};
}

}  // namespace

AutoBand ChooseBand(const std::vector<double>& frequency_hz,
                    const std::vector<std::vector<std::complex<double>>>& frfs) {
  const auto [begin, end] = FiniteRun(frequency_hz, frfs);
  if (end - begin < 4) {
    throw ValidationError("band", "--band auto: the longest run of lines above 0 Hz where every record is a finite "
                                  "number has " + std::to_string(end - begin) + " lines, at least 4 are needed");
  }
  AutoBand band;
  band.run_min_hz = frequency_hz[begin];
  band.run_max_hz = frequency_hz[end - 1];
  std::vector<double> sum(end - begin, 0.0);
  for (std::size_t k = begin; k < end; ++k) {
    for (const auto& frf : frfs) sum[k - begin] += std::abs(frf[k]);
  }
  std::vector<double> sorted = sum;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  const std::size_t w = kPeakHalfWidthLines;
  double first_window_hz = 0.0, last_window_hz = 0.0;
  for (std::size_t i = w; i + w < sum.size(); ++i) {
    if (!(sum[i] >= kPeakOverMedian * median)) continue;
    const auto window = sum.begin() + static_cast<std::ptrdiff_t>(i - w);
    // The first largest of the window: a flat top counts once.
    if (std::max_element(window, window + static_cast<std::ptrdiff_t>(2 * w + 1)) - window == static_cast<std::ptrdiff_t>(w)) {
      band.peaks_hz.push_back(frequency_hz[begin + i]);
      if (band.peaks_hz.size() == 1) first_window_hz = frequency_hz[begin + i - w];
      last_window_hz = frequency_hz[begin + i + w];
    }
  }
  const std::string run = FormatNumber(band.run_min_hz, 6) + " to " + FormatNumber(band.run_max_hz, 6) + " Hz";
  if (band.peaks_hz.empty()) {
    band.min_frequency_hz = band.run_min_hz;
    band.max_frequency_hz = band.run_max_hz;
    band.rule = "no peak stands out (the sum of |H| over the records at " + FormatNumber(kPeakOverMedian, 3) +
                " x its median, the largest of " + std::to_string(kPeakHalfWidthLines) + " lines either side): "
                "every finite line, " + run;
    return band;
  }
  // At least the peaks' windows, on coarse lines.
  band.min_frequency_hz = std::min(std::max(band.run_min_hz, 0.5 * band.peaks_hz.front()), first_window_hz);
  band.max_frequency_hz = std::max(std::min(band.run_max_hz, 1.5 * band.peaks_hz.back()), last_window_hz);
  band.rule = "from half the lowest to 1.5 x the highest of " + std::to_string(band.peaks_hz.size()) +
              " peak" + (band.peaks_hz.size() == 1 ? "" : "s") + " (the sum of |H| over the records at " +
              FormatNumber(kPeakOverMedian, 3) + " x its median or more, the largest of " +
              std::to_string(kPeakHalfWidthLines) + " lines either side) within the finite lines, " + run;
  return band;
}

}  // namespace shapebench::model
