// What the `recommend` tests check against, written here independently of bench/measure:
// synthetic accelerometer logs of known modes, a Welch PSD by the plain DFT, and Klipper's
// shaper_calibrate.py / shaper_defs.py formulas (its impulse definitions, _estimate_shaper,
// _estimate_remaining_vibrations) as Klipper states them.
#pragma once

#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace shapebench::bench::testing {

constexpr double kOraclePi = 3.14159265358979323846;

struct SyntheticMode {
  double frequency_hz = 37.0;
  double damping_ratio = 0.05;
  double share = 1.0;  // of the static deflection
};

struct SyntheticLogSpec {
  std::vector<SyntheticMode> modes = {SyntheticMode{}};
  double seconds = 20.0;
  double rate_hz = 3200.0;
  double chirp_from_hz = 5.0;
  double chirp_to_hz = 200.0;
  double chirp_mm_s2 = 2000.0;  // the base acceleration's chirp amplitude
  double noise_mm_s2 = 300.0;   // the base acceleration's white noise (standard deviation)
  double sensor_noise_mm_s2 = 30.0;
  double jitter_periods = 0.0;  // each time stamp moved by up to +/- this many periods
  unsigned seed = 1;
};

// The samples: time and the X accelerometer (the base's acceleration a plus the modes'
// q_i'' g_i, q_i'' + 2 zeta w q_i' + w^2 q_i = -a exactly under a held a: zero-order
// hold by the matrix exponential; g_i = share_i (w_i / w_1)^2), Y sensor noise, Z
// gravity and noise.
struct SyntheticSamples {
  std::vector<double> time_s;
  std::vector<double> x, y, z;
};

inline SyntheticSamples Synthesize(const SyntheticLogSpec& spec) {
  std::mt19937_64 random(spec.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const std::size_t n = static_cast<std::size_t>(spec.seconds * spec.rate_hz);
  const double dt = 1.0 / spec.rate_hz;
  SyntheticSamples s;
  std::vector<double> base(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt;
    const double phase = spec.chirp_from_hz * t + (spec.chirp_to_hz - spec.chirp_from_hz) / (2.0 * spec.seconds) * t * t;
    base[k] = spec.chirp_mm_s2 * std::sin(2.0 * kOraclePi * phase) + spec.noise_mm_s2 * normal(random);
  }
  s.x = base;
  const double w1 = 2.0 * kOraclePi * spec.modes.front().frequency_hz;
  for (const SyntheticMode& mode : spec.modes) {
    const double w = 2.0 * kOraclePi * mode.frequency_hz;
    const double gain = mode.share * (w / w1) * (w / w1);
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -w * w, -2.0 * mode.damping_ratio * w;
    const Eigen::Vector2d b(0.0, -1.0);
    const Eigen::Matrix2d phi = (a * dt).exp();
    const Eigen::Vector2d gamma = a.inverse() * (phi - Eigen::Matrix2d::Identity()) * b;
    Eigen::Vector2d state = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      s.x[k] += gain * (-base[k] - 2.0 * mode.damping_ratio * w * state(1) - w * w * state(0));
      state = phi * state + gamma * base[k];
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    s.time_s.push_back(static_cast<double>(k) * dt + spec.jitter_periods * dt * uniform(random));
    s.x[k] += spec.sensor_noise_mm_s2 * normal(random);
    s.y.push_back(spec.sensor_noise_mm_s2 * normal(random));
    s.z.push_back(9810.0 + spec.sensor_noise_mm_s2 * normal(random));
  }
  return s;
}

// Klipper's raw_data CSV of the samples.
inline std::string LogText(const SyntheticSamples& s) {
  std::string text = "#time,accel_x,accel_y,accel_z\n";
  char line[160];
  for (std::size_t k = 0; k < s.time_s.size(); ++k) {
    std::snprintf(line, sizeof line, "%.9f,%.6f,%.6f,%.6f\n", s.time_s[k], s.x[k], s.y[k], s.z[k]);
    text += line;
  }
  return text;
}

// Welch's PSD by the definition: segments of m samples, m / 2 apart, (N - m/2) / (m/2) of
// them, each less its mean, times the periodic Hann window, |DFT_k|^2 / (rate sum w^2),
// doubled but at 0 and rate / 2, averaged; only the bins k <= max_bin (a plain DFT each).
inline std::vector<double> DftWelch(const std::vector<double>& x, double rate_hz, int m, int max_bin) {
  std::vector<double> window(m);
  double power = 0.0;
  for (int n = 0; n < m; ++n) {
    window[n] = 0.5 * (1.0 - std::cos(2.0 * kOraclePi * n / m));
    power += window[n] * window[n];
  }
  const std::size_t step = static_cast<std::size_t>(m / 2);
  const std::size_t segments = (x.size() - step) / step;
  std::vector<double> psd(static_cast<std::size_t>(max_bin) + 1, 0.0);
  std::vector<double> segment(m);
  for (std::size_t s = 0; s < segments; ++s) {
    double mean = 0.0;
    for (int n = 0; n < m; ++n) mean += x[s * step + n];
    mean /= m;
    for (int n = 0; n < m; ++n) segment[n] = (x[s * step + n] - mean) * window[n];
    for (int k = 0; k <= max_bin; ++k) {
      std::complex<double> sum = 0.0;
      for (int n = 0; n < m; ++n) sum += segment[n] * std::polar(1.0, -2.0 * kOraclePi * ((static_cast<long>(k) * n) % m) / m);
      psd[k] += ((k == 0 || k == m / 2) ? 1.0 : 2.0) * std::norm(sum) / (rate_hz * power);
    }
  }
  for (double& value : psd) value /= static_cast<double>(segments);
  return psd;
}

// A Klipper shaper: amplitudes A (not normalised) at times T.
struct KlipperShaper {
  std::vector<double> a;
  std::vector<double> t;
};

// shaper_defs.py's definitions, for design frequency f and damping ratio zeta.
inline KlipperShaper KlipperZv(double f, double zeta) {
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double k = std::exp(-zeta * kOraclePi / df);
  const double td = 1.0 / (f * df);
  return {{1.0, k}, {0.0, 0.5 * td}};
}

inline KlipperShaper KlipperZvd(double f, double zeta) {
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double k = std::exp(-zeta * kOraclePi / df);
  const double td = 1.0 / (f * df);
  return {{1.0, 2.0 * k, k * k}, {0.0, 0.5 * td, td}};
}

// get_mzv_shaper with n = 3, t = 0.75: the undamped amplitudes that put zeros at 1 and
// 1 + 1/tau (tau = 1.5), i.e. 1 - 1/sqrt(2), sqrt(2) - 1, 1 - 1/sqrt(2) at 0, 3/8, 3/4
// damped periods, scaled by K^j with K = exp(-0.75 zeta pi / df).
inline KlipperShaper KlipperMzv(double f, double zeta) {
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double k = std::exp(-0.75 * zeta * kOraclePi / df);
  const double td = 1.0 / (f * df);
  const double outer = 1.0 - 1.0 / std::sqrt(2.0);
  return {{outer, (std::sqrt(2.0) - 1.0) * k, outer * k * k}, {0.0, 0.375 * td, 0.75 * td}};
}

// get_ei_shaper (the fit of Singhose et al.), v_tol = 1/20.
inline KlipperShaper KlipperEi(double f, double zeta) {
  const double v = 0.05;
  const double df = std::sqrt(1.0 - zeta * zeta);
  const double td = 1.0 / (f * df);
  const double z = zeta;
  const double a1 = (0.24968 + 0.24961 * v) + ((0.80008 + 1.23328 * v) + (0.49599 + 3.17316 * v) * z) * z;
  const double a3 = (0.25149 + 0.21474 * v) + ((-0.83249 + 1.41498 * v) + (0.85181 - 4.90094 * v) * z) * z;
  const double t2 = 0.4999 + (((0.46159 + 8.57843 * v) * v) +
                              (((4.26169 - 108.644 * v) * v) + ((1.75601 + 336.989 * v) * v) * z) * z) * z;
  return {{a1, 1.0 - a1 - a3, a3}, {0.0, t2 * td, td}};
}

// _get_shaper_from_expansion_coeffs: each time and amplitude a cubic in zeta, times in
// undamped periods 1 / f.
inline KlipperShaper KlipperExpansion(double f, double zeta, const std::vector<std::vector<double>>& t,
                                      const std::vector<std::vector<double>>& a) {
  KlipperShaper shaper;
  for (std::size_t i = 0; i < t.size(); ++i) {
    double u = 0.0;
    double w = 0.0;
    for (int j = 3; j >= 0; --j) {
      u = u * zeta + t[i][j];
      w = w * zeta + a[i][j];
    }
    shaper.t.push_back(u / f);
    shaper.a.push_back(w);
  }
  return shaper;
}

inline KlipperShaper Klipper2HumpEi(double f, double zeta) {
  return KlipperExpansion(f, zeta,
                          {{0, 0, 0, 0},
                           {0.49890, 0.16270, -0.54262, 6.16180},
                           {0.99748, 0.18382, -1.58270, 8.17120},
                           {1.49920, -0.09297, -0.28338, 1.85710}},
                          {{0.16054, 0.76699, 2.26560, -1.22750},
                           {0.33911, 0.45081, -2.58080, 1.73650},
                           {0.34089, -0.61533, -0.68765, 0.42261},
                           {0.15997, -0.60246, 1.00280, -0.93145}});
}

inline KlipperShaper Klipper3HumpEi(double f, double zeta) {
  return KlipperExpansion(f, zeta,
                          {{0, 0, 0, 0},
                           {0.49974, 0.23834, 0.44559, 12.4720},
                           {0.99849, 0.29808, -2.36460, 23.3990},
                           {1.49870, 0.10306, -2.01390, 17.0320},
                           {1.99960, -0.28231, 0.61536, 5.40450}},
                          {{0.11275, 0.76632, 3.29160, -1.44380},
                           {0.23698, 0.61164, -2.57850, 4.85220},
                           {0.30008, -0.19062, -2.14560, 0.13744},
                           {0.23775, -0.73297, 0.46885, -2.08650},
                           {0.11244, -0.45439, 0.96382, -1.46000}});
}

// _estimate_shaper: V at f for damping zeta, sqrt(S^2 + C^2) / sum A with
// W_j = A_j exp(-zeta w (T_n - T_j)), S = sum W_j sin(w_d T_j), C the same with cos.
inline double KlipperV(const KlipperShaper& shaper, double f, double zeta) {
  const double w = 2.0 * kOraclePi * f;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  double s = 0.0, c = 0.0, sum = 0.0;
  for (std::size_t j = 0; j < shaper.a.size(); ++j) {
    const double weight = shaper.a[j] * std::exp(-zeta * w * (shaper.t.back() - shaper.t[j]));
    s += weight * std::sin(wd * shaper.t[j]);
    c += weight * std::cos(wd * shaper.t[j]);
    sum += shaper.a[j];
  }
  return std::sqrt(s * s + c * c) / sum;
}

// fit_shaper's vibrations: the worst over the test damping ratios of
// _estimate_remaining_vibrations (threshold psd.max() / SHAPER_VIBRATION_REDUCTION, 20).
inline double KlipperRemainingVibration(const KlipperShaper& shaper, const std::vector<double>& f,
                                        const std::vector<double>& psd) {
  double peak = 0.0;
  for (const double p : psd) peak = std::max(peak, p);
  const double threshold = peak / 20.0;
  double all = 0.0;
  for (const double p : psd) all += std::max(p - threshold, 0.0);
  double worst = 0.0;
  for (const double zeta : {0.075, 0.1, 0.15}) {
    double left = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) left += std::max(KlipperV(shaper, f[k], zeta) * psd[k] - threshold, 0.0);
    worst = std::max(worst, left / all);
  }
  return worst;
}

}  // namespace shapebench::bench::testing
