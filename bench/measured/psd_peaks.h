// PSD peak picking: the peaks of an accelerometer log's PSD, where `recommend --validate`'s
// modes start (bench/measured/log_modes.h then measures each by a modal fit; the machine
// they make: bench/run/recommend_validation.h). A peak's frequency and half-power width
// only: on Klipper's 1.56 Hz bins a narrow mode reads wide.
//
// Modes: every local maximum of the PSD in the fit band (5-200 Hz) at or above P_max / 20
// (the fit's threshold) that stands apart: walking away from it on each side, the PSD
// falls below half its height before it rises above it (a shoulder of a higher peak, or
// noise on its flank, is not a mode). Its frequency: the parabola through the log of the
// three bins around it (exact for a Gaussian peak, within a few percent of a bin for the
// window's); its damping ratio: the half-power width, zeta = (f_high - f_low) / (2 f),
// the crossings of P / 2 interpolated linearly between bins (one side missing, at the
// band's edge or a valley above half: twice the other side's). The window widens every
// peak by about 1.44 bins (Hann's half-power width), so a damping below about
// 0.7 x bin width / f reads high.
//
// Gains: the mode's share of the static deflection follows the PSD. Under an excitation
// flat across the modes (a chirp, white noise), the acceleration PSD peaks at P_i ~
// (g_i / (2 zeta_i))^2 for a mode of modal gain g_i (model/machine.h's modal form: the
// deflection per base acceleration peaks at 1 / (2 zeta) times its static value
// g_i / w_i^2, times w_i^2 as an acceleration); so g_i ~ 2 zeta_i sqrt(P_i), and the
// static shares s_i = g_i / w_i^2 are scaled to sum to the scenario machine's static
// deflection per acceleration of its driven axis (the machine keeps its stiffness, the
// log gives the modes and their mix).
#pragma once

#include <cmath>
#include <vector>

#include "model/machine.h"

namespace shapebench::bench {

struct LogMode {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double peak_psd = 0.0;  // the PSD at the peak, (mm/s^2)^2/Hz
  double share = 0.0;     // of the static deflection, summing to 1 over the modes
  // One standard deviation of each, from the modal fit (bench/measured/log_modes.h);
  // NaN for a peak as picked here.
  double frequency_uncertainty_hz = NAN;
  double damping_uncertainty = NAN;
};

// The log's modes (above), ascending frequency; gains not yet known (share set).
std::vector<LogMode> PickPsdPeaks(const std::vector<double>& frequency_hz, const std::vector<double>& psd);

// The modal machine of `modes` whose static deflection per acceleration is
// `static_deflection_per_accel_s2` (m per m/s^2), shared as `share` says.
model::ModalMachineConfig ModesMachine(const std::vector<LogMode>& modes, double static_deflection_per_accel_s2);

}  // namespace shapebench::bench
