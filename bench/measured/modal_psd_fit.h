// A modal model fitted to an acceleration PSD (`recommend --validate`'s modes,
// bench/measured/log_modes.h): a few modes at once, by the Whittle likelihood, with the
// standard uncertainties of their frequencies and damping ratios.
//
// The model is shapebench's modal form (model/machine.h) as an accelerometer on the tool
// sees it when the base is shaken by an acceleration a: the tool's acceleration is
// a (1 - sum_i g_i s^2 / (s^2 + 2 zeta_i w_i s + w_i^2)), so its PSD
//   S(f) = E exp(c (f - f_c) / f_c) |1 - sum_i g_i s^2 / (s^2 + 2 zeta_i w_i s + w_i^2)|^2 + B,
// s = 2 pi i f: E the excitation's level (flat but for a tilt c across the window, f_c its
// middle), B the sensor's noise floor. What a bin reads is S seen through the window:
// the expected bin k is sum_t kernel_t S(f_k + (t - T) df / sub), the window's power
// kernel sampled `sub` times a bin (sum 1), so a peak a few bins wide is not widened.
//
// Fit: the Whittle likelihood of the bins, sum_k log P^_k + P_k / P^_k (each bin an
// average of independent exponential periodograms around its expected value P^_k),
// minimised by Levenberg-Marquardt on Fisher's scoring (the information matrix
// sum_k J_k^T J_k / P^_k^2, J the expected bins' derivatives by central differences).
// Unlike a least-squares fit of the log of the PSD, it is efficient on a periodogram of
// one segment, and it has no half-power width on a few bins in it.
//
// Uncertainty: the inverse information times the relative variance of a bin
// (`relative_variance`, 1 / segments for independent segments; when 0, estimated from
// the residuals: mean ((P - P^) / P^)^2 with the parameters' degrees of freedom).
#pragma once

#include <string>
#include <vector>

namespace shapebench::bench {

struct ModalPsdGuess {
  double frequency_hz = 0.0;
  double damping_ratio = 0.05;
};

struct ModalPsdInput {
  std::vector<double> frequency_hz;  // evenly spaced bins
  std::vector<double> psd;
  std::vector<double> kernel = {1.0};  // odd size, centred, sum 1
  int kernel_sub = 1;                  // kernel samples per bin
  double relative_variance = 0.0;      // of a bin; 0: from the residuals
};

struct ModalPsdMode {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double gain = 0.0;  // g_i, per the excitation's level
  double frequency_uncertainty_hz = 0.0;  // one standard deviation
  double damping_uncertainty = 0.0;
};

struct ModalPsdFit {
  std::vector<ModalPsdMode> modes;
  double excitation = 0.0;  // E
  double tilt = 0.0;        // c
  double noise_floor = 0.0; // B
  int bins = 0;
  int iterations = 0;
  bool converged = false;
  std::string trouble;  // empty, or why the result is not to be trusted
};

// Fits the modes guessed in `guesses` (ascending, inside the bins' range) to the bins of
// `input` between from_hz and to_hz. Each frequency stays within that range and each
// damping ratio in [1e-4, 0.5].
ModalPsdFit FitModalPsd(const ModalPsdInput& input, const std::vector<ModalPsdGuess>& guesses, double from_hz,
                        double to_hz);

}  // namespace shapebench::bench
