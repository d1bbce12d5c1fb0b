// Klipper's calibrate_shaper rule (see the header).
#include "bench/measured/klipper_calibrate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "common/math_constants.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

constexpr double kVibrationReduction = 20.0;  // SHAPER_VIBRATION_REDUCTION
constexpr double kMaxShaperFreqHz = 150.0;    // MAX_SHAPER_FREQ
constexpr double kFreqStepHz = 0.2;
constexpr double kSmoothingAccelMmS2 = 5000.0;

KlipperShaper ZvShaper(double f, double zeta) {
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double k = std::exp(-zeta * kPi / df);
  const double td = 1.0 / (f * df);
  return {{1.0, k}, {0.0, 0.5 * td}};
}

// The generalised MZV of n = 3 impulses over t = 0.75 of a period: amplitudes summing
// to 1 with zeros at 1 and 1 + 1 / tau times the frequency, tau = t (n - 2) / (n - 2t - 1);
// the least-squares solution of the (consistent) 5 x 3 system by its normal equations.
KlipperShaper MzvShaper(double f, double zeta) {
  constexpr int n = 3;
  constexpr double t = 0.75;
  const double tau = t * (n - 2.0) / (n - 2.0 * t - 1.0);
  std::array<double, n> times{};
  for (int i = 0; i < n; ++i) times[i] = i * t / (n - 1.0);
  std::vector<std::array<double, n>> rows = {{1.0, 1.0, 1.0}};
  std::vector<double> rhs = {1.0};
  for (int i = 0; i < n - 1; ++i) {
    std::array<double, n> c{}, s{};
    for (int j = 0; j < n; ++j) {
      const double w = 2.0 * kPi * (1.0 + i / tau) * times[j];
      c[j] = std::cos(w);
      s[j] = std::sin(w);
    }
    rows.push_back(c);
    rows.push_back(s);
    rhs.push_back(0.0);
    rhs.push_back(0.0);
  }
  double a[n][n + 1] = {};
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) a[i][j] += rows[r][i] * rows[r][j];
      a[i][n] += rows[r][i] * rhs[r];
    }
  }
  for (int col = 0; col < n; ++col) {  // Gauss-Jordan with partial pivoting
    int pivot = col;
    for (int r = col + 1; r < n; ++r) {
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    }
    for (int j = 0; j <= n; ++j) std::swap(a[col][j], a[pivot][j]);
    for (int r = 0; r < n; ++r) {
      if (r == col) continue;
      const double factor = a[r][col] / a[col][col];
      for (int j = col; j <= n; ++j) a[r][j] -= factor * a[col][j];
    }
  }
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double k = std::exp(-2.0 * t * zeta * kPi / ((n - 1.0) * df));
  const double td = 1.0 / (f * df);
  KlipperShaper shaper;
  double kp = 1.0;  // k^i on the i-th impulse
  for (int i = 0; i < n; ++i) {
    shaper.amplitude.push_back(a[i][n] / a[i][i] * kp);
    shaper.time_s.push_back(times[i] * td);
    kp *= k;
  }
  return shaper;
}

KlipperShaper EiShaper(double f, double zeta) {
  const double v = 1.0 / kVibrationReduction;
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double td = 1.0 / (f * df);
  const double a1 = (0.24968 + 0.24961 * v) + ((0.80008 + 1.23328 * v) + (0.49599 + 3.17316 * v) * zeta) * zeta;
  const double a3 = (0.25149 + 0.21474 * v) + ((-0.83249 + 1.41498 * v) + (0.85181 - 4.90094 * v) * zeta) * zeta;
  const double t2 = 0.4999 + (((0.46159 + 8.57843 * v) * v) +
                              (((4.26169 - 108.644 * v) * v) + ((1.75601 + 336.989 * v) * v) * zeta) * zeta) *
                                 zeta;
  return {{a1, 1.0 - a1 - a3, a3}, {0.0, t2 * td, td}};
}

// Times (in periods of the design frequency) and amplitudes as cubics in the damping.
template <std::size_t N>
KlipperShaper ExpansionShaper(double f, double zeta, const std::array<std::array<double, 4>, N>& t,
                              const std::array<std::array<double, 4>, N>& a) {
  KlipperShaper shaper;
  for (std::size_t i = 0; i < N; ++i) {
    shaper.time_s.push_back((((t[i][3] * zeta + t[i][2]) * zeta + t[i][1]) * zeta + t[i][0]) / f);
    shaper.amplitude.push_back(((a[i][3] * zeta + a[i][2]) * zeta + a[i][1]) * zeta + a[i][0]);
  }
  return shaper;
}

KlipperShaper TwoHumpEiShaper(double f, double zeta) {
  static const std::array<std::array<double, 4>, 4> t = {{{0.0, 0.0, 0.0, 0.0},
                                                           {0.49890, 0.16270, -0.54262, 6.16180},
                                                           {0.99748, 0.18382, -1.58270, 8.17120},
                                                           {1.49920, -0.09297, -0.28338, 1.85710}}};
  static const std::array<std::array<double, 4>, 4> a = {{{0.16054, 0.76699, 2.26560, -1.22750},
                                                           {0.33911, 0.45081, -2.58080, 1.73650},
                                                           {0.34089, -0.61533, -0.68765, 0.42261},
                                                           {0.15997, -0.60246, 1.00280, -0.93145}}};
  return ExpansionShaper(f, zeta, t, a);
}

KlipperShaper ThreeHumpEiShaper(double f, double zeta) {
  static const std::array<std::array<double, 4>, 5> t = {{{0.0, 0.0, 0.0, 0.0},
                                                           {0.49974, 0.23834, 0.44559, 12.4720},
                                                           {0.99849, 0.29808, -2.36460, 23.3990},
                                                           {1.49870, 0.10306, -2.01390, 17.0320},
                                                           {1.99960, -0.28231, 0.61536, 5.40450}}};
  static const std::array<std::array<double, 4>, 5> a = {{{0.11275, 0.76632, 3.29160, -1.44380},
                                                           {0.23698, 0.61164, -2.57850, 4.85220},
                                                           {0.30008, -0.19062, -2.14560, 0.13744},
                                                           {0.23775, -0.73297, 0.46885, -2.08650},
                                                           {0.11244, -0.45439, 0.96382, -1.46000}}};
  return ExpansionShaper(f, zeta, t, a);
}

// numpy.arange(start, stop, step): ceil((stop - start) / step) values start + i delta,
// delta = (start + step) - start as numpy fills them.
std::vector<double> Arange(double start, double stop, double step) {
  const auto count = static_cast<std::size_t>(std::max(0.0, std::ceil((stop - start) / step)));
  const double delta = (start + step) - start;
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = start + static_cast<double>(i) * delta;
  return values;
}

// The remaining vibrations of `shaper` worst over the data sets and test dampings; the
// response worst over the dampings on the first data set's bins into `vibration`.
double ShaperVibrations(const KlipperShaper& shaper, const std::vector<KlipperFitInput>& data,
                        const KlipperFitOptions& options, std::vector<double>* vibration) {
  double worst = 0.0;
  for (std::size_t d = 0; d < data.size(); ++d) {
    std::vector<double> bins, psd;
    for (std::size_t k = 0; k < data[d].frequency_hz.size(); ++k) {
      if (data[d].frequency_hz[k] > options.max_freq_hz) continue;
      bins.push_back(data[d].frequency_hz[k]);
      psd.push_back(data[d].psd[k]);
    }
    const double threshold = *std::max_element(psd.begin(), psd.end()) / kVibrationReduction;
    double all = 0.0;
    for (const double p : psd) all += std::max(p - threshold, 0.0);
    if (d == 0) vibration->assign(bins.size(), 0.0);
    for (const double zeta : options.test_damping_ratios) {
      const std::vector<double> vals = KlipperShaperResponse(shaper, zeta, bins);
      double remaining = 0.0;
      for (std::size_t k = 0; k < bins.size(); ++k) remaining += std::max(vals[k] * psd[k] - threshold, 0.0);
      if (d == 0) {
        for (std::size_t k = 0; k < bins.size(); ++k) (*vibration)[k] = std::max((*vibration)[k], vals[k]);
      }
      worst = std::max(worst, remaining / all);
    }
  }
  return worst;
}

}  // namespace

KlipperShaperResult KlipperFitShaper(const std::string& name, const std::vector<KlipperFitInput>& data,
                                     const KlipperFitOptions& options, std::vector<KlipperShaperResult>* scanned) {
  const double start = std::min(KlipperShaperMinFreqHz(name), kMaxShaperFreqHz - 1e-7);
  const std::vector<double> freqs = Arange(start, kMaxShaperFreqHz, kFreqStepHz);
  std::vector<KlipperShaperResult> results;  // from the highest frequency down
  std::size_t best = 0;
  bool stopped = false;  // by --max-smoothing: Klipper then returns the best, unselected
  for (auto f = freqs.rbegin(); f != freqs.rend(); ++f) {
    KlipperShaperResult r;
    r.name = name;
    r.frequency_hz = *f;
    r.shaper = KlipperInitShaper(name, *f, options.damping_ratio);
    r.smoothing_mm = KlipperSmoothingMm(r.shaper, kSmoothingAccelMmS2, options.scv_mm_s);
    if (options.max_smoothing_mm && r.smoothing_mm > *options.max_smoothing_mm && !results.empty()) {
      stopped = true;
      break;
    }
    r.max_accel_mm_s2 = KlipperMaxAccelMmS2(r.shaper, options.scv_mm_s);
    r.remaining_vibration = ShaperVibrations(r.shaper, data, options, &r.vibration);
    const double v = r.remaining_vibration;
    r.score = r.smoothing_mm * (std::pow(v, 1.5) + v * 0.2 + 0.01);
    results.push_back(std::move(r));
    if (results[best].remaining_vibration > results.back().remaining_vibration) best = results.size() - 1;
  }
  // Not much worse than the best, much less smoothing: walked up from the lowest frequency.
  std::size_t selected = best;
  const double limit = results[best].remaining_vibration * 1.1 + 0.0005;
  for (auto r = results.rbegin(); r != results.rend() && !stopped; ++r) {
    if (r->remaining_vibration < limit && r->score < results[selected].score) {
      selected = static_cast<std::size_t>(results.rend() - r) - 1;
    }
  }
  KlipperShaperResult chosen = results[selected];
  if (scanned) *scanned = std::move(results);
  return chosen;
}

KlipperRecommendation KlipperFindBestShaper(const std::vector<KlipperFitInput>& data,
                                            const KlipperFitOptions& options) {
  options.validate();
  KlipperRecommendation out;
  std::optional<KlipperShaperResult> best;
  for (const std::string& name : KlipperAutotuneShapers()) {
    std::vector<KlipperShaperResult> scanned;
    KlipperShaperResult shaper = KlipperFitShaper(name, data, options, &scanned);
    if (!best || shaper.score * 1.2 < best->score ||
        (shaper.score * 1.05 < best->score && shaper.smoothing_mm * 1.1 < best->smoothing_mm)) {
      best = shaper;
    }
    for (auto s = scanned.rbegin(); s != scanned.rend(); ++s) {
      if (s->remaining_vibration < best->remaining_vibration && s->smoothing_mm < best->smoothing_mm) {
        best = *s;
        shaper = *s;
      }
    }
    out.shapers.push_back(std::move(shaper));
  }
  if (out.shapers.empty()) throw std::runtime_error("no Klipper shaper could be fitted");
  // best is one of the reported results: the last reported one equal to it.
  for (std::size_t i = 0; i < out.shapers.size(); ++i) {
    if (out.shapers[i].name == best->name && out.shapers[i].frequency_hz == best->frequency_hz) out.recommended = i;
  }
  if (best->name == "zv") {
    for (std::size_t i = 0; i < out.shapers.size(); ++i) {
      if (out.shapers[i].name != "zv" && out.shapers[i].remaining_vibration * 1.1 < best->remaining_vibration) {
        out.recommended = i;
        break;
      }
    }
  }
  return out;
}

const std::vector<std::string>& KlipperAutotuneShapers() {
  static const std::vector<std::string> names = {"zv", "mzv", "ei", "2hump_ei", "3hump_ei"};
  return names;
}

double KlipperShaperMinFreqHz(const std::string& name) {
  if (name == "zv") return 21.0;
  if (name == "mzv") return 23.0;
  if (name == "ei") return 29.0;
  if (name == "2hump_ei") return 39.0;
  if (name == "3hump_ei") return 48.0;
  throw std::invalid_argument("unknown Klipper shaper '" + name + "'");
}

KlipperShaper KlipperInitShaper(const std::string& name, double frequency_hz, double damping_ratio) {
  if (name == "zv") return ZvShaper(frequency_hz, damping_ratio);
  if (name == "mzv") return MzvShaper(frequency_hz, damping_ratio);
  if (name == "ei") return EiShaper(frequency_hz, damping_ratio);
  if (name == "2hump_ei") return TwoHumpEiShaper(frequency_hz, damping_ratio);
  if (name == "3hump_ei") return ThreeHumpEiShaper(frequency_hz, damping_ratio);
  throw std::invalid_argument("unknown Klipper shaper '" + name + "'");
}

std::vector<double> KlipperShaperResponse(const KlipperShaper& shaper, double damping_ratio,
                                          const std::vector<double>& frequency_hz) {
  double sum = 0.0;
  for (const double a : shaper.amplitude) sum += a;
  const double last = shaper.time_s.back();
  std::vector<double> out(frequency_hz.size());
  for (std::size_t k = 0; k < frequency_hz.size(); ++k) {
    const double omega = 2.0 * kPi * frequency_hz[k];
    const double decay = damping_ratio * omega;
    const double omega_d = omega * std::sqrt(1.0 - damping_ratio * damping_ratio);
    double s = 0.0, c = 0.0;
    for (std::size_t j = 0; j < shaper.time_s.size(); ++j) {
      const double w = shaper.amplitude[j] * std::exp(-decay * (last - shaper.time_s[j]));
      s += w * std::sin(omega_d * shaper.time_s[j]);
      c += w * std::cos(omega_d * shaper.time_s[j]);
    }
    out[k] = std::sqrt(s * s + c * c) / sum;
  }
  return out;
}

double KlipperSmoothingMm(const KlipperShaper& shaper, double accel_mm_s2, double scv_mm_s) {
  const double half_accel = 0.5 * accel_mm_s2;
  double sum = 0.0, shift = 0.0;
  for (std::size_t i = 0; i < shaper.time_s.size(); ++i) {
    sum += shaper.amplitude[i];
    shift += shaper.amplitude[i] * shaper.time_s[i];
  }
  shift /= sum;
  double offset_90 = 0.0, offset_180 = 0.0;
  for (std::size_t i = 0; i < shaper.time_s.size(); ++i) {
    const double dt = shaper.time_s[i] - shift;
    if (shaper.time_s[i] >= shift) offset_90 += shaper.amplitude[i] * (scv_mm_s + half_accel * dt) * dt;
    offset_180 += shaper.amplitude[i] * half_accel * dt * dt;
  }
  return std::max(offset_90 / sum * std::sqrt(2.0), offset_180 / sum);
}

double KlipperMaxAccelMmS2(const KlipperShaper& shaper, double scv_mm_s) {
  constexpr double kTargetSmoothingMm = 0.12;
  auto ok = [&](double accel) { return KlipperSmoothingMm(shaper, accel, scv_mm_s) <= kTargetSmoothingMm; };
  double left = 1.0, right = 1.0;
  if (!ok(1e-9)) return 0.0;
  while (!ok(left)) {
    right = left;
    left *= 0.5;
  }
  if (right == left) {
    while (ok(right)) right *= 2.0;
  }
  while (right - left > 1e-8) {
    const double middle = (left + right) * 0.5;
    (ok(middle) ? left : right) = middle;
  }
  return left;
}

void KlipperFitOptions::validate() const {
  if (!(damping_ratio > 0.0 && damping_ratio < 1.0)) {
    throw ValidationError("--damping-ratio", "must be in (0, 1) (Klipper's --damping_ratio; it reads 0 as 0.1)");
  }
  if (max_smoothing_mm && !(*max_smoothing_mm >= 0.05 && std::isfinite(*max_smoothing_mm))) {
    throw ValidationError("--max-smoothing", "must be a finite smoothing of at least 0.05 mm, as Klipper's");
  }
}

}  // namespace shapebench::bench
