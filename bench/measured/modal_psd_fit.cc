// The modal model's fit to a PSD (see the header).
#include "bench/measured/modal_psd_fit.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Dense>

#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

constexpr double kMinDamping = 1e-4;
constexpr double kMaxDamping = 0.5;
constexpr int kMaxIterations = 2000;

// The expected bins of the parameters theta = [f_i, log zeta_i, g_i per mode, log E, c,
// log B] over the bins first .. first + count - 1.
class ExpectedBins {
 public:
  ExpectedBins(const ModalPsdInput& input, std::size_t first, std::size_t count, int modes)
      : input_(input), first_(first), count_(count), modes_(modes) {
    bin_hz_ = input.frequency_hz[1] - input.frequency_hz[0];
    half_taps_ = static_cast<int>(input.kernel.size() / 2);
    centre_hz_ = 0.5 * (input.frequency_hz[first] + input.frequency_hz[first + count - 1]);
    fine_.resize((count - 1) * static_cast<std::size_t>(input.kernel_sub) + input.kernel.size());
  }

  int parameters() const { return 3 * modes_ + 3; }
  double frequency(std::size_t k) const { return input_.frequency_hz[first_ + k]; }
  double measured(std::size_t k) const { return input_.psd[first_ + k]; }
  std::size_t count() const { return count_; }

  // The model's PSD at f (the header's S).
  double Density(const Eigen::VectorXd& theta, double f) const {
    const std::complex<double> s(0.0, kTwoPi * f);
    std::complex<double> t = 1.0;
    for (int i = 0; i < modes_; ++i) {
      const double w = kTwoPi * theta[3 * i];
      const double zeta = std::exp(theta[3 * i + 1]);
      t -= theta[3 * i + 2] * s * s / (s * s + 2.0 * zeta * w * s + w * w);
    }
    const int m = 3 * modes_;
    return std::exp(theta[m] + theta[m + 1] * (f - centre_hz_) / centre_hz_) * std::norm(t) + std::exp(theta[m + 2]);
  }

  // The bins as the window reads the model: the kernel over a grid `kernel_sub` times finer.
  Eigen::VectorXd Evaluate(const Eigen::VectorXd& theta) {
    const double step = bin_hz_ / input_.kernel_sub;
    const double start = frequency(0) - half_taps_ * step;
    for (std::size_t j = 0; j < fine_.size(); ++j) fine_[j] = Density(theta, start + static_cast<double>(j) * step);
    Eigen::VectorXd bins(static_cast<Eigen::Index>(count_));
    for (std::size_t k = 0; k < count_; ++k) {
      double sum = 0.0;
      const std::size_t base = k * static_cast<std::size_t>(input_.kernel_sub);
      for (std::size_t t = 0; t < input_.kernel.size(); ++t) sum += input_.kernel[t] * fine_[base + t];
      bins[static_cast<Eigen::Index>(k)] = sum;
    }
    return bins;
  }

  // d bins / d theta by central differences.
  Eigen::MatrixXd Jacobian(const Eigen::VectorXd& theta) {
    Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(count_), parameters());
    for (int p = 0; p < parameters(); ++p) {
      double h = 1e-5;
      if (p < 3 * modes_ && p % 3 == 0) h = 1e-5 * theta[p];
      if (p < 3 * modes_ && p % 3 == 2) h = 1e-5 * std::max(std::abs(theta[p]), 1e-3);
      Eigen::VectorXd up = theta;
      Eigen::VectorXd down = theta;
      up[p] += h;
      down[p] -= h;
      jacobian.col(p) = (Evaluate(up) - Evaluate(down)) / (2.0 * h);
    }
    return jacobian;
  }

  // The Whittle likelihood's negative log, +infinity for an invalid model.
  double Whittle(const Eigen::VectorXd& expected) const {
    double sum = 0.0;
    for (std::size_t k = 0; k < count_; ++k) {
      const double e = expected[static_cast<Eigen::Index>(k)];
      if (!(e > 0.0) || !std::isfinite(e)) return std::numeric_limits<double>::infinity();
      sum += std::log(e) + measured(k) / e;
    }
    return sum;
  }

 private:
  const ModalPsdInput& input_;
  std::size_t first_;
  std::size_t count_;
  int modes_;
  double bin_hz_ = 0.0;
  int half_taps_ = 0;
  double centre_hz_ = 0.0;
  std::vector<double> fine_;
};

// The starting point: the guesses, E the mean of the lowest fifth of the bins, each g
// from its peak's height over E (|1 - g i / (2 zeta)| at resonance), B a thousandth of E.
Eigen::VectorXd StartingPoint(const ExpectedBins& bins, const std::vector<ModalPsdGuess>& guesses) {
  std::vector<double> sorted;
  for (std::size_t k = 0; k < bins.count(); ++k) sorted.push_back(bins.measured(k));
  std::sort(sorted.begin(), sorted.end());
  const std::size_t fifth = std::max<std::size_t>(1, sorted.size() / 5);
  double level = 0.0;
  for (std::size_t k = 0; k < fifth; ++k) level += sorted[k];
  level = std::max(level / static_cast<double>(fifth), std::numeric_limits<double>::min() * 1e6);
  const int m = static_cast<int>(guesses.size());
  Eigen::VectorXd theta(3 * m + 3);
  for (int i = 0; i < m; ++i) {
    double peak = 0.0;
    for (std::size_t k = 0; k < bins.count(); ++k) {
      if (std::abs(bins.frequency(k) - guesses[i].frequency_hz) <= guesses[i].damping_ratio * guesses[i].frequency_hz) {
        peak = std::max(peak, bins.measured(k));
      }
    }
    const double zeta = std::clamp(guesses[i].damping_ratio, 2.0 * kMinDamping, 0.5 * kMaxDamping);
    theta[3 * i] = guesses[i].frequency_hz;
    theta[3 * i + 1] = std::log(zeta);
    theta[3 * i + 2] = 2.0 * zeta * std::sqrt(std::max(peak / level - 1.0, 1.0));
  }
  theta[3 * m] = std::log(level);
  theta[3 * m + 1] = 0.0;
  theta[3 * m + 2] = std::log(level) - std::log(1e3);
  return theta;
}

bool Valid(const Eigen::VectorXd& theta, int modes, double from_hz, double to_hz) {
  if (!theta.allFinite()) return false;
  for (int i = 0; i < modes; ++i) {
    if (theta[3 * i] < from_hz || theta[3 * i] > to_hz) return false;
    if (theta[3 * i + 1] < std::log(kMinDamping) || theta[3 * i + 1] > std::log(kMaxDamping)) return false;
  }
  return true;
}

// The information matrix sum J^T J / P^^2 and the likelihood's gradient at theta.
void Scoring(ExpectedBins& bins, const Eigen::VectorXd& theta, const Eigen::VectorXd& expected, Eigen::MatrixXd* info,
             Eigen::VectorXd* gradient) {
  const Eigen::MatrixXd raw = bins.Jacobian(theta);
  Eigen::MatrixXd scaled = raw;
  Eigen::VectorXd residual(expected.size());
  for (Eigen::Index k = 0; k < expected.size(); ++k) {
    residual[k] = (expected[k] - bins.measured(static_cast<std::size_t>(k))) / (expected[k] * expected[k]);
    scaled.row(k) /= expected[k];
  }
  *info = scaled.transpose() * scaled;
  *gradient = raw.transpose() * residual;
}

// The fit's modes, their uncertainties (the inverse information times a bin's relative
// variance, measured from the residuals when not given) and the excitation's terms.
void Report(const ExpectedBins& bins, const Eigen::VectorXd& theta, const Eigen::VectorXd& expected,
            const Eigen::MatrixXd& info, double variance, ModalPsdFit* fit) {
  const int modes = (bins.parameters() - 3) / 3;
  if (!(variance > 0.0)) {
    double sum = 0.0;
    for (std::size_t k = 0; k < bins.count(); ++k) {
      const double e = expected[static_cast<Eigen::Index>(k)];
      sum += std::pow((bins.measured(k) - e) / e, 2);
    }
    variance = sum / static_cast<double>(bins.count() - static_cast<std::size_t>(bins.parameters()));
  }
  const Eigen::MatrixXd covariance = info.completeOrthogonalDecomposition().pseudoInverse() * variance;
  for (int i = 0; i < modes; ++i) {
    ModalPsdMode mode;
    mode.frequency_hz = theta[3 * i];
    mode.damping_ratio = std::exp(theta[3 * i + 1]);
    mode.gain = theta[3 * i + 2];
    mode.frequency_uncertainty_hz = std::sqrt(std::max(covariance(3 * i, 3 * i), 0.0));
    mode.damping_uncertainty = mode.damping_ratio * std::sqrt(std::max(covariance(3 * i + 1, 3 * i + 1), 0.0));
    fit->modes.push_back(mode);
  }
  fit->excitation = std::exp(theta[3 * modes]);
  fit->tilt = theta[3 * modes + 1];
  fit->noise_floor = std::exp(theta[3 * modes + 2]);
}

}  // namespace

ModalPsdFit FitModalPsd(const ModalPsdInput& input, const std::vector<ModalPsdGuess>& guesses, double from_hz,
                        double to_hz) {
  ModalPsdFit fit;
  std::size_t first = input.frequency_hz.size();
  std::size_t last = 0;
  for (std::size_t k = 0; k < input.frequency_hz.size(); ++k) {
    if (input.frequency_hz[k] < from_hz || input.frequency_hz[k] > to_hz) continue;
    first = std::min(first, k);
    last = k;
  }
  const int modes = static_cast<int>(guesses.size());
  if (first >= input.frequency_hz.size() || last < first + static_cast<std::size_t>(3 * modes + 4) ||
      input.frequency_hz.size() < 2) {
    fit.trouble = "too few bins between " + std::to_string(from_hz) + " and " + std::to_string(to_hz) + " Hz";
    return fit;
  }
  ExpectedBins bins(input, first, last - first + 1, modes);
  fit.bins = static_cast<int>(bins.count());
  Eigen::VectorXd theta = StartingPoint(bins, guesses);
  Eigen::VectorXd expected = bins.Evaluate(theta);
  double value = bins.Whittle(expected);
  double lambda = 1e-3;
  Eigen::MatrixXd info;
  Eigen::VectorXd gradient;
  for (fit.iterations = 0; fit.iterations < kMaxIterations; ++fit.iterations) {
    Scoring(bins, theta, expected, &info, &gradient);
    // Newton's decrement: what a full scoring step would still gain. The likelihood's
    // noise is of order 1; a flat direction (a noise floor seen only in a dip) needs far
    // less to settle, down to rounding: stalled under 1e-6 is settled too.
    const double decrement = 0.5 * gradient.dot(info.completeOrthogonalDecomposition().solve(gradient));
    fit.converged = decrement < 1e-6;
    if (!(decrement > 1e-14)) break;
    bool accepted = false;
    while (!accepted && lambda < 1e12) {
      Eigen::MatrixXd damped = info;
      damped.diagonal() += lambda * info.diagonal().cwiseMax(1e-300);
      const Eigen::VectorXd next = theta - damped.ldlt().solve(gradient);
      const Eigen::VectorXd next_expected = Valid(next, modes, from_hz, to_hz) ? bins.Evaluate(next) : expected;
      const double next_value = Valid(next, modes, from_hz, to_hz) ? bins.Whittle(next_expected) : value;
      if (!(next_value < value)) {
        lambda *= 4.0;
        continue;
      }
      accepted = true;
      theta = next;
      expected = next_expected;
      value = next_value;
      lambda = std::max(lambda / 3.0, 1e-9);
    }
    if (!accepted) break;  // no step lowers the likelihood: rounding, or stalled
  }
  if (!fit.converged) {
    fit.trouble = "the fit did not settle (" + std::to_string(fit.iterations) + " iterations)";
  }
  Scoring(bins, theta, expected, &info, &gradient);
  Report(bins, theta, expected, info, input.relative_variance, &fit);
  return fit;
}

}  // namespace shapebench::bench
