// The identification's accuracy (model/modal_identification.h, model/modal_refinement.h) on
// seeded synthetic FRFs against the Cramér-Rao bound the test computes for each case, and
// its physical check of the modes (issue 34).
#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "model/modal_identification.h"

namespace shapebench::model {
namespace modal_accuracy_test {
namespace {

using Complex = std::complex<double>;

struct TrueMode {
  double frequency_hz;
  double damping_ratio;
  Complex constant;  // R_r of the receptance, 1/kg
};

struct Case {
  std::vector<TrueMode> modes;
  double noise = 0.0;  // complex Gaussian, this fraction of each line's magnitude
};

// The estimator's model with the residual terms the fit carries (LR, UR): parameters per
// mode f, zeta, Re R, Im R, then LR, UR; the accelerance (j w)^2 x receptance, where
// R / (w_r^2 - w^2 + 2 j zeta w_r w) generalises to the pole pair
// A / (j w - lambda) + conj(A) / (j w - conj(lambda)), R = 2 j w_d A.
Complex Accelerance(const std::vector<double>& theta, std::size_t modes, double f_hz) {
  const double w = 2.0 * M_PI * f_hz;
  const Complex jw(0.0, w);
  Complex h = -theta[4 * modes] / (w * w) + theta[4 * modes + 1];
  for (std::size_t r = 0; r < modes; ++r) {
    const double wr = 2.0 * M_PI * theta[4 * r];
    const double zeta = theta[4 * r + 1];
    const Complex lambda(-zeta * wr, wr * std::sqrt(1.0 - zeta * zeta));
    const Complex a = Complex(theta[4 * r + 2], theta[4 * r + 3]) / Complex(0.0, 2.0 * lambda.imag());
    h += a / (jw - lambda) + std::conj(a) / (jw - std::conj(lambda));
  }
  return jw * jw * h;
}

std::vector<double> Parameters(const Case& c) {
  std::vector<double> theta;
  for (const TrueMode& m : c.modes) {
    theta.insert(theta.end(), {m.frequency_hz, m.damping_ratio, m.constant.real(), m.constant.imag()});
  }
  theta.insert(theta.end(), {0.0, 0.0});
  return theta;
}

// Lines every 0.05 Hz up to 100 Hz (0 Hz left out: the lower residual is singular there).
std::vector<double> Grid() {
  std::vector<double> f;
  for (int k = 1; k <= 2000; ++k) f.push_back(0.05 * k);
  return f;
}

std::vector<Complex> Measure(const Case& c, const std::vector<double>& f, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, c.noise / std::sqrt(2.0));
  const std::vector<double> theta = Parameters(c);
  std::vector<Complex> h;
  for (double fk : f) {
    const Complex a = Accelerance(theta, c.modes.size(), fk);
    h.push_back(a + std::abs(a) * Complex(normal(generator), normal(generator)));
  }
  return h;
}

// The Cramér-Rao standard deviations of every parameter: the inverse of the Fisher
// information sum_k J_k^T J_k / s_k^2, s_k^2 = (noise |H_k|)^2 / 2 per real part, with the
// derivatives J_k by central differences (exact for LR, UR: the model is linear in them).
std::vector<double> CramerRao(const Case& c, const std::vector<double>& f) {
  const std::vector<double> theta = Parameters(c);
  const std::size_t n = theta.size(), m = c.modes.size();
  Eigen::MatrixXd jacobian(2 * f.size(), n);
  Eigen::VectorXd weight(2 * f.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double scale = i < 4 * m ? std::max(std::abs(theta[i]), std::abs(theta[4 * (i / 4) + 2])) : 1.0;
    const double step = i < 4 * m && i % 4 < 2 ? 1e-6 * std::abs(theta[i]) : 1e-6 * scale;
    std::vector<double> up = theta, down = theta;
    up[i] += step;
    down[i] -= step;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const Complex d = (Accelerance(up, m, f[k]) - Accelerance(down, m, f[k])) / (2.0 * step);
      jacobian(2 * k, i) = d.real();
      jacobian(2 * k + 1, i) = d.imag();
    }
  }
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double s2 = std::norm(c.noise * Accelerance(theta, m, f[k])) / 2.0;
    weight(2 * k) = weight(2 * k + 1) = 1.0 / s2;
  }
  const Eigen::MatrixXd fisher = jacobian.transpose() * weight.asDiagonal() * jacobian;
  const Eigen::VectorXd d = fisher.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd covariance = d.asDiagonal() * (d.asDiagonal() * fisher * d.asDiagonal()).inverse() * d.asDiagonal();
  std::vector<double> sigma;
  for (std::size_t i = 0; i < n; ++i) sigma.push_back(std::sqrt(covariance(i, i)));
  return sigma;
}

// 1-3 modes from 20 to 60 Hz, each 1-5 % of its frequency above the one before, damping
// 0.5-3 %, constants 0.005-0.02 1/kg of either sign, noise 1-2 % of each line.
Case SeededCase(unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Case c;
  const int modes = 1 + static_cast<int>(generator() % 3);
  double f = 20.0 + 40.0 * unit(generator);
  for (int r = 0; r < modes; ++r) {
    if (r > 0) f *= 1.0 + 0.01 + 0.04 * unit(generator);
    const double zeta = 0.005 + 0.025 * unit(generator);
    const double constant = (0.005 + 0.015 * unit(generator)) * (unit(generator) < 0.5 ? -1.0 : 1.0);
    c.modes.push_back({f, zeta, constant});
  }
  c.noise = 0.01 + 0.01 * unit(generator);
  return c;
}

// Expects every true mode within the bounds (frequency 0.2 %, damping 10 %, modal
// constant 10 %) or four Cramér-Rao standard deviations where those are larger.
void ExpectWithinBounds(const Case& c, const ModalIdentification& id, const std::vector<double>& sigma) {
  std::string found = "found:";
  for (const IdentifiedMode& m : id.modes) found += " " + std::to_string(m.frequency_hz) + " Hz " + std::to_string(m.damping_ratio);
  for (const RejectedMode& m : id.rejected) found += "; rejected " + std::to_string(m.frequency_hz) + " Hz";
  std::string truth = "true:";
  for (const TrueMode& m : c.modes) truth += " " + std::to_string(m.frequency_hz) + " Hz " + std::to_string(m.damping_ratio);
  SCOPED_TRACE(truth + "; " + found);
  ASSERT_EQ(id.modes.size(), c.modes.size());
  for (std::size_t r = 0; r < c.modes.size(); ++r) {
    SCOPED_TRACE("mode " + std::to_string(r + 1) + " at " + std::to_string(c.modes[r].frequency_hz) + " Hz, zeta " +
                 std::to_string(c.modes[r].damping_ratio));
    const TrueMode& truth = c.modes[r];
    const IdentifiedMode& mode = id.modes[r];
    EXPECT_NEAR(mode.frequency_hz, truth.frequency_hz, std::max(0.002 * truth.frequency_hz, 4.0 * sigma[4 * r]));
    EXPECT_NEAR(mode.damping_ratio, truth.damping_ratio, std::max(0.1 * truth.damping_ratio, 4.0 * sigma[4 * r + 1]));
    const double constant_sigma = std::hypot(sigma[4 * r + 2], sigma[4 * r + 3]);
    EXPECT_LE(std::abs(mode.modal_constants[0] - truth.constant),
              std::max(0.1 * std::abs(truth.constant), 4.0 * constant_sigma));
  }
}

// The 20 seeds of issue 34's test (committed: the cases are SeededCase(seed), the noise
// seeded 1000 + seed).
constexpr unsigned kSeeds[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20};

// Tests that 20 seeded synthetic accelerances (1-3 modes 1-5 % apart, damping 0.5-3 %,
// 1-2 % complex noise on each 0.05 Hz line) give every mode within 0.2 % in frequency,
// 10 % in damping and modal constant, or four Cramér-Rao deviations where larger.
TEST(ModalAccuracy, SeededCasesWithinTheBounds) {
  const std::vector<double> f = Grid();
  for (unsigned seed : kSeeds) {
    const Case c = SeededCase(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ModalIdentification id = IdentifyModes(f, {Measure(c, f, 1000 + seed)}, 2, {});
    ExpectWithinBounds(c, id, CramerRao(c, f));
  }
}

// Tests that issue 34's close modes (22 Hz 2 %, 40 Hz 3 %, 41.2 Hz 1.5 %; 0.05 Hz lines,
// 2 % complex noise) keep the 40 Hz mode's damping within 10 % (it came out 14 % low).
TEST(ModalAccuracy, CloseModesKeepTheirDamping) {
  Case c;
  c.modes = {{22.0, 0.02, 1.0 / 80.0}, {40.0, 0.03, 1.0 / 120.0}, {41.2, 0.015, -1.0 / 150.0}};
  c.noise = 0.02;
  const std::vector<double> f = Grid();
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ModalIdentification id = IdentifyModes(f, {Measure(c, f, seed)}, 2, {});
    ASSERT_EQ(id.modes.size(), 3u);
    EXPECT_NEAR(id.modes[1].damping_ratio, 0.03, 0.003);
    EXPECT_TRUE(id.refined);
    ExpectWithinBounds(c, id, CramerRao(c, f));
  }
}

// Tests that a mode the data does not show (a 60 Hz mode whose constant is 1000 x smaller
// than its neighbours') is dropped and listed as rejected with its prominence, while the
// three that show stay, each with its prominence above the limit; and that without the
// prominence check it is still dropped, as explaining under 1 % of the data's norm
// (min_error_rise_percent), with the rise it would bring.
TEST(ModalAccuracy, HiddenModeIsDropped) {
  Case c;
  c.modes = {{22.0, 0.02, 1.0 / 80.0}, {40.0, 0.03, 1.0 / 120.0}, {41.2, 0.015, -1.0 / 150.0}, {60.0, 0.01, 1e-5}};
  c.noise = 1e-4;
  const std::vector<double> f = Grid();
  const ModalIdentification id = IdentifyModes(f, {Measure(c, f, 1)}, 2, {});
  ASSERT_EQ(id.modes.size(), 3u);
  for (const IdentifiedMode& mode : id.modes) EXPECT_GE(mode.prominence, IdentificationOptions{}.min_prominence);
  ASSERT_EQ(id.rejected.size(), 1u);
  EXPECT_NEAR(id.rejected[0].frequency_hz, 60.0, 0.1);
  EXPECT_LT(id.rejected[0].prominence, IdentificationOptions{}.min_prominence);
  IdentificationOptions keep;
  keep.min_prominence = 0.0;
  const ModalIdentification by_rise = IdentifyModes(f, {Measure(c, f, 1)}, 2, keep);
  ASSERT_EQ(by_rise.modes.size(), 3u);
  ASSERT_EQ(by_rise.rejected.size(), 1u);
  EXPECT_NEAR(by_rise.rejected[0].frequency_hz, 60.0, 0.1);
  EXPECT_GT(by_rise.rejected[0].error_rise_percent, 0.0);
  EXPECT_LT(by_rise.rejected[0].error_rise_percent, 1.0);
  keep.min_error_rise_percent = 0.0;
  EXPECT_EQ(IdentifyModes(f, {Measure(c, f, 1)}, 2, keep).modes.size(), 4u);
}

}  // namespace
}  // namespace modal_accuracy_test
}  // namespace shapebench::model
