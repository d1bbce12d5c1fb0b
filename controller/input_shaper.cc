// The shaper library (zv, zvd, zvdd, mzv, ei, um_zv, custom; several modes convolved);
// the designs and their sources are in the header.
#include "controller/input_shaper.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::controller {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Impulses of a convolution closer than this are one impulse.
constexpr double kSameTimeS = 1e-12;

std::string Num(double v) { return FormatNumber(v); }

bool Finite(double v) { return std::isfinite(v); }

// Normalises amplitudes to sum 1.
std::vector<Impulse> Normalised(std::vector<Impulse> impulses) {
  double total = 0.0;
  for (const Impulse& i : impulses) total += i.amplitude;
  for (Impulse& i : impulses) i.amplitude /= total;
  return impulses;
}

// The damped EI (header): Singhose et al.'s curve fit; {A1, A2, A3, t2 / T_d}.
struct EiFit {
  double a1, a2, a3, t2_over_td;
};
EiFit DampedEiFit(double v, double z) {
  EiFit fit{};
  fit.a1 = 0.24968 + 0.24961 * v + (0.80008 + 1.23328 * v) * z + (0.49599 + 3.17316 * v) * z * z;
  fit.a3 = 0.25149 + 0.21474 * v + (-0.83249 + 1.41498 * v) * z + (0.85181 - 4.90094 * v) * z * z;
  fit.a2 = 1.0 - fit.a1 - fit.a3;
  fit.t2_over_td = 0.49990 + (0.46159 * v + 8.57843 * v * v) * z +
                   (4.26169 * v - 108.644 * v * v) * z * z +
                   (1.75601 * v + 336.989 * v * v) * z * z * z;
  return fit;
}

// Every shaper the library designs for one mode (validated inputs).
std::vector<Impulse> ConvolvedPerMode(const PatternConfig& config) {
  std::vector<Impulse> result = {{0.0, 1.0}};
  for (const double f : config.DesignFrequencies()) {
    std::vector<Impulse> one;
    if (IsPatentMethod(config.method)) {
      PatternConfig single = config;
      single.frequencies_hz.clear();
      single.frequency_hz = f;
      single.mode = PatternMode::kBoth;
      one = PatternImpulses(MakeStepPattern(single));
    } else {
      one = SingleModeShaper(config.method, f, config.design_damping_ratio, config.vibration_tolerance);
    }
    result = ConvolveImpulses(result, one);
  }
  return result;
}

}  // namespace

std::string MethodName(PatternMethod method) {
  switch (method) {
    case PatternMethod::kNone: return "none";
    case PatternMethod::kMethod1: return "1";
    case PatternMethod::kMethod2: return "2";
    case PatternMethod::kMethod3: return "3";
    case PatternMethod::kMethod4: return "4";
    case PatternMethod::kZv: return "zv";
    case PatternMethod::kZvd: return "zvd";
    case PatternMethod::kZvdd: return "zvdd";
    case PatternMethod::kMzv: return "mzv";
    case PatternMethod::kEi: return "ei";
    case PatternMethod::kUmZv: return "um_zv";
    case PatternMethod::kCustom: return "custom";
  }
  return "?";
}

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

std::pair<double, double> UnityMagnitudeZvTimes(double frequency_hz, double damping_ratio) {
  const double root = std::sqrt(1.0 - damping_ratio * damping_ratio);
  const double wd = 2.0 * kPi * frequency_hz * root;
  // In theta = w_d t: 1 - e^{c theta2} + e^{c theta3} = 0, c = beta + i, beta = zeta / root.
  // Continuation in beta from the undamped solution (pi/3, 2pi/3), Newton at each step.
  const double beta_target = damping_ratio / root;
  double theta2 = kPi / 3.0;
  double theta3 = 2.0 * kPi / 3.0;
  const int stages = std::max(1, static_cast<int>(std::ceil(beta_target / 0.02)));
  for (int stage = 1; stage <= stages; ++stage) {
    const std::complex<double> c(beta_target * stage / stages, 1.0);
    bool converged = false;
    for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
      const std::complex<double> e2 = std::exp(c * theta2);
      const std::complex<double> e3 = std::exp(c * theta3);
      const std::complex<double> f = 1.0 - e2 + e3;
      const std::complex<double> d2 = -c * e2;  // dF / dtheta2
      const std::complex<double> d3 = c * e3;   // dF / dtheta3
      const double det = d2.real() * d3.imag() - d3.real() * d2.imag();
      if (!(std::abs(det) > 0.0)) break;
      const double step2 = (-f.real() * d3.imag() + d3.real() * f.imag()) / det;
      const double step3 = (-d2.real() * f.imag() + f.real() * d2.imag()) / det;
      theta2 += step2;
      theta3 += step3;
      converged = std::abs(step2) + std::abs(step3) < 1e-15 * (1.0 + theta3) ||
                  std::abs(1.0 - std::exp(c * theta2) + std::exp(c * theta3)) < 1e-15;
    }
    if (!converged || !(theta2 > 0.0 && theta3 > theta2 && theta3 < 2.0 * kPi)) {
      throw ValidationError("design_damping_ratio",
                            "no unity-magnitude ZV shaper found for damping ratio " +
                                Num(damping_ratio) + " (um_zv's damped times do not converge); "
                                "allowed: a smaller design_damping_ratio");
    }
  }
  return {theta2 / wd, theta3 / wd};
}

std::vector<Impulse> SingleModeShaper(PatternMethod method, double frequency_hz,
                                      double damping_ratio, double vibration_tolerance) {
  const double z = damping_ratio;
  const double root = std::sqrt(1.0 - z * z);
  const double td = 1.0 / (frequency_hz * root);  // damped period T_d
  const double k = std::exp(-z * kPi / root);
  switch (method) {
    case PatternMethod::kZv:
      return Normalised({{0.0, 1.0}, {0.5 * td, k}});
    case PatternMethod::kZvd:
      return Normalised({{0.0, 1.0}, {0.5 * td, 2.0 * k}, {td, k * k}});
    case PatternMethod::kZvdd:
      return Normalised({{0.0, 1.0}, {0.5 * td, 3.0 * k}, {td, 3.0 * k * k}, {1.5 * td, k * k * k}});
    case PatternMethod::kMzv: {
      const double km = std::exp(-0.75 * z * kPi / root);
      const double outer = 1.0 - 1.0 / std::sqrt(2.0);
      const double middle = std::sqrt(2.0) - 1.0;
      return Normalised({{0.0, outer}, {0.375 * td, middle * km}, {0.75 * td, outer * km * km}});
    }
    case PatternMethod::kEi: {
      const double v = vibration_tolerance;
      if (z == 0.0) return {{0.0, (1.0 + v) / 4.0}, {0.5 * td, (1.0 - v) / 2.0}, {td, (1.0 + v) / 4.0}};
      const EiFit fit = DampedEiFit(v, z);
      return {{0.0, fit.a1}, {fit.t2_over_td * td, fit.a2}, {td, fit.a3}};
    }
    case PatternMethod::kUmZv: {
      if (z == 0.0) return {{0.0, 1.0}, {td / 6.0, -1.0}, {td / 3.0, 1.0}};
      const auto [t2, t3] = UnityMagnitudeZvTimes(frequency_hz, z);
      return {{0.0, 1.0}, {t2, -1.0}, {t3, 1.0}};
    }
    default:
      break;
  }
  return {{0.0, 1.0}};
}

std::vector<Impulse> ShaperImpulses(const PatternConfig& config) {
  switch (config.method) {
    case PatternMethod::kNone:
      return {{0.0, 1.0}};
    case PatternMethod::kCustom:
      return config.impulses;
    default:
      return ConvolvedPerMode(config);
  }
}

GridDesign ShaperGridDesign(const PatternConfig& config) {
  const double damping = IsPatentMethod(config.method) ? 0.0 : config.design_damping_ratio;
  return GridDesign(config.DesignFrequencies(), damping);
}

void ValidateShaperKeys(const PatternConfig& config) {
  for (std::size_t i = 0; i < config.frequencies_hz.size(); ++i) {
    const double f = config.frequencies_hz[i];
    if (!(Finite(f) && f > 0.0)) {
      throw ValidationError("frequencies_hz[" + std::to_string(i) + "]",
                            "must be a finite number > 0 (got " + Num(f) + ")");
    }
  }
  const double z = config.design_damping_ratio;
  if (!(Finite(z) && z >= 0.0 && z < 1.0)) {
    throw ValidationError("design_damping_ratio", "must be in [0, 1) (got " + Num(z) + ")");
  }
  if (z > 0.0 && IsPatentMethod(config.method)) {
    throw ValidationError("design_damping_ratio",
                          "applies to the library shapers (zv, zvd, zvdd, mzv, ei, um_zv, custom); "
                          "the patent's methods 1-4 are designed for an undamped mode (got " +
                              Num(z) + ")");
  }
  const double v = config.vibration_tolerance;
  if (!(Finite(v) && v > 0.0 && v < 1.0)) {
    throw ValidationError("vibration_tolerance", "must be in (0, 1) (a fraction of the unshaped "
                                                 "vibration; got " + Num(v) + ")");
  }
  if (config.method != PatternMethod::kCustom && !config.impulses.empty()) {
    throw ValidationError("impulses", "is for method custom only (method is " +
                                          MethodName(config.method) + ")");
  }
  if (config.method == PatternMethod::kCustom) {
    if (config.impulses.empty()) {
      throw ValidationError("impulses", "method custom needs at least one impulse, e.g. impulses: "
                                        "[{amplitude: 0.5, time_s: 0}, {amplitude: 0.5, time_s: 0.02}]");
    }
    double total = 0.0;
    for (std::size_t i = 0; i < config.impulses.size(); ++i) {
      const Impulse& impulse = config.impulses[i];
      const std::string at = "impulses[" + std::to_string(i) + "]";
      if (!Finite(impulse.amplitude)) {
        throw ValidationError(at + ".amplitude", "must be a finite number (got " + Num(impulse.amplitude) + ")");
      }
      if (!(Finite(impulse.time_s) && impulse.time_s >= 0.0)) {
        throw ValidationError(at + ".time_s", "must be >= 0 s (got " + Num(impulse.time_s) + ")");
      }
      if (i > 0 && !(impulse.time_s > config.impulses[i - 1].time_s)) {
        throw ValidationError(at + ".time_s", "must be after the previous impulse's (" +
                                                  Num(config.impulses[i - 1].time_s) +
                                                  " s): times strictly ascending (got " +
                                                  Num(impulse.time_s) + ")");
      }
      total += impulse.amplitude;
    }
    if (std::abs(total - 1.0) > 1e-9) {
      throw ValidationError("impulses", "the amplitudes must sum to 1 (unit DC gain; got " + Num(total) + ")");
    }
  }
  if (config.method == PatternMethod::kEi && z > 0.0) {
    // The damped EI is a curve fit (header); outside its range it is not an EI shaper.
    if (v > 0.2 || z > 0.3) {
      throw ValidationError(v > 0.2 ? "vibration_tolerance" : "design_damping_ratio",
                            "the damped EI is Singhose et al.'s curve fit, made for "
                            "vibration_tolerance <= 0.2 and design_damping_ratio <= 0.3 (got " +
                                Num(v) + ", " + Num(z) + "); allowed: design_damping_ratio 0 for "
                                "the exact undamped EI with any tolerance in (0, 1)");
    }
  }
  if (config.method == PatternMethod::kUmZv && z > 0.0) {
    for (const double f : config.DesignFrequencies()) UnityMagnitudeZvTimes(f, z);
  }
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
