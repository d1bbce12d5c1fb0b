// Welch's PSD with FFTW's real-to-complex transform (see the header).
#include "bench/measured/welch_psd.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fftw3.h>

#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

// FFTW's planner is not thread-safe (its execution is): plans are made and destroyed
// under this lock. FFTW_ESTIMATE: the same algorithm, hence the same bits, on every run.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};

class RealFft {
 public:
  explicit RealFft(int n)
      : in_(static_cast<double*>(fftw_malloc(sizeof(double) * static_cast<std::size_t>(n)))),
        out_(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * static_cast<std::size_t>(n / 2 + 1)))) {
    if (!in_ || !out_) throw std::bad_alloc();
    const std::lock_guard<std::mutex> lock(PlannerMutex());
    plan_ = fftw_plan_dft_r2c_1d(n, in_.get(), out_.get(), FFTW_ESTIMATE);
    if (plan_ == nullptr) throw std::runtime_error("FFTW could not plan a transform of " + std::to_string(n));
  }
  ~RealFft() {
    const std::lock_guard<std::mutex> lock(PlannerMutex());
    fftw_destroy_plan(plan_);
  }
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  double* input() { return in_.get(); }
  void Execute() { fftw_execute(plan_); }
  // |X_k|^2
  double Power(int k) const { return out_.get()[k][0] * out_.get()[k][0] + out_.get()[k][1] * out_.get()[k][1]; }

 private:
  std::unique_ptr<double, FftwFree> in_;
  std::unique_ptr<fftw_complex, FftwFree> out_;
  fftw_plan plan_ = nullptr;
};

}  // namespace

int WelchSegmentLength(double sample_rate_hz) {
  // Klipper: M = 1 << int(fs * WINDOW_T_SEC - 1).bit_length(), WINDOW_T_SEC = 0.5.
  const double half_second = std::floor(sample_rate_hz * 0.5 - 1.0);
  // Capped at 2^30 (a rate of a gigahertz): more samples than any log holds.
  int segment = 1;
  for (double m = half_second; m >= 1.0 && segment < (1 << 30); m = std::floor(m / 2.0)) segment *= 2;
  return std::max(2, segment);
}

Psd WelchPsd(const std::vector<double>& samples, double sample_rate_hz, int segment_samples) {
  const int m = segment_samples;
  if (m < 2 || m % 2 != 0) throw std::invalid_argument("Welch segment length must be even and >= 2");
  std::vector<double> window(static_cast<std::size_t>(m));
  for (int n = 0; n < m; ++n) window[n] = 0.5 - 0.5 * std::cos(2.0 * kPi * n / m);
  return WelchPsdWindowed(samples, sample_rate_hz, window);
}

Psd WelchPsdWindowed(const std::vector<double>& samples, double sample_rate_hz, const std::vector<double>& window) {
  const int m = static_cast<int>(window.size());
  if (m < 2 || m % 2 != 0) throw std::invalid_argument("Welch segment length must be even and >= 2");
  if (samples.size() <= static_cast<std::size_t>(m)) {
    throw std::invalid_argument("Welch PSD: " + std::to_string(samples.size()) + " samples, not more than one segment of " +
                                std::to_string(m));
  }
  const int step = m / 2;
  Psd psd;
  psd.sample_rate_hz = sample_rate_hz;
  psd.segment_samples = m;
  psd.segments = static_cast<int>((samples.size() - static_cast<std::size_t>(step)) / static_cast<std::size_t>(step));
  double window_power = 0.0;
  for (int n = 0; n < m; ++n) window_power += window[n] * window[n];
  const double scale = 1.0 / (sample_rate_hz * window_power);
  psd.density.assign(static_cast<std::size_t>(m / 2 + 1), 0.0);
  RealFft fft(m);
  for (int s = 0; s < psd.segments; ++s) {
    const double* segment = samples.data() + static_cast<std::size_t>(s) * step;
    double mean = 0.0;
    for (int n = 0; n < m; ++n) mean += segment[n];
    mean /= m;
    for (int n = 0; n < m; ++n) fft.input()[n] = (segment[n] - mean) * window[n];
    fft.Execute();
    for (int k = 0; k <= m / 2; ++k) {
      const double one_sided = (k == 0 || k == m / 2) ? 1.0 : 2.0;
      psd.density[k] += one_sided * scale * fft.Power(k);
    }
  }
  for (double& value : psd.density) value /= psd.segments;
  for (int k = 0; k <= m / 2; ++k) psd.frequency_hz.push_back(k * sample_rate_hz / m);
  return psd;
}

}  // namespace shapebench::bench
