// The shaper library beyond the patent's methods 1-4 (`controller.pattern.method`): zv,
// zvd, zvdd, mzv, ei, um_zv and custom impulse sequences, designed for a mode of damping
// `design_damping_ratio`, and for several modes at once (`frequencies_hz`: one shaper per
// frequency, convolved). Every shaper is an impulse sequence (times >= 0, amplitudes
// summing to 1) that the controller applies like the patent's patterns: convolved with
// the steady acceleration of each acc/dec phase (stepped, linear_acc_dec.h) or as a
// post-interpolation profile table (profile_table.h), in both cases put on the period
// grid without losing its zeros (grid_realization.h).
//
// Designs (omega_d = omega sqrt(1 - zeta^2), T_d = 2 pi / omega_d,
// K = exp(-zeta pi / sqrt(1 - zeta^2))):
// - zv    [1, K] / (1 + K) at [0, T_d/2]   (Smith's posicast; Singer & Seering 1990)
// - zvd   [1, 2K, K^2] / (1 + K)^2 at [0, T_d/2, T_d]   (Singer & Seering 1990)
// - zvdd  [1, 3K, 3K^2, K^3] / (1 + K)^3 at [0, T_d/2, T_d, 3T_d/2] (ZV convolved thrice)
// - mzv   three positive impulses 3 T_d / 8 apart, c = [1 - 1/sqrt(2), sqrt(2) - 1,
//         1 - 1/sqrt(2)] scaled by K_m^j, K_m = exp(-0.75 zeta pi / sqrt(1 - zeta^2)), and
//         normalised (the vector-diagram construction of Singhose, Seering & Singer,
//         "Residual vibration reduction using vector diagrams to generate shaping inputs",
//         ASME J. Mech. Design 116, 1994, in the form commonly implemented, e.g. by
//         Klipper; not checked here against the paper's own table). Its zero at the
//         design point is exact for any zeta (the K_m^j scaling cancels the decay).
// - ei    zeta = 0: [(1 + V)/4, (1 - V)/2, (1 + V)/4] at [0, T/2, T], V =
//         vibration_tolerance (Singhose, Seering & Singer, "Shaping inputs to reduce
//         vibration: a vector diagram approach", IEEE ICRA 1990; Singhose, Derezinski &
//         Singer, "Extra-insensitive input shapers for controlling flexible spacecraft",
//         J. Guidance, Control & Dynamics 19, 1996): V at the design frequency, zero on
//         either side. zeta > 0: the published curve fit (Singhose, Porter, Tuttle &
//         Singer, "Vibration reduction using multi-hump input shapers", ASME J. Dyn. Sys.
//         Meas. Control 119, 1997) A1 = 0.24968 + 0.24961 V + (0.80008 + 1.23328 V) z +
//         (0.49599 + 3.17316 V) z^2, A3 = 0.25149 + 0.21474 V + (-0.83249 + 1.41498 V) z +
//         (0.85181 - 4.90094 V) z^2, A2 = 1 - A1 - A3, t2 = (0.49990 + 0.46159 V z +
//         4.26169 V z^2 + 1.75601 V z^3 + 8.57843 V^2 z - 108.644 V^2 z^2 + 336.989 V^2
//         z^3) T_d, t3 = T_d (z = zeta; coefficients as widely implemented, e.g. by
//         Klipper): a fit, so the damped EI's residual at the design point is V only
//         approximately (limitation; the undamped one is exact): within 0.01 absolute
//         for V <= 0.2 and zeta <= 0.3, the range allowed (ValidateShaperKeys), and
//         within about 5% of V for zeta <= 0.1, V >= 0.02.
// - um_zv unity magnitude, negative: [1, -1, 1]. zeta = 0: at [0, T/6, T/3], the same
//         impulses as the patent's method 2 (a for T/6, 0 for T/6, then a). zeta > 0:
//         the times solve 1 - e^{s t2} + e^{s t3} = 0 with s = zeta omega + i omega_d
//         exactly (Newton from the undamped times, to 1e-14), which is the damped UM-ZV
//         of Singhose, Seering & Singer ("Time-optimal negative input shapers", ASME
//         J. Dyn. Sys. Meas. Control 119, 1997, who give a curve fit of these times).
//         The continuation finds solutions up to zeta of about 0.6; beyond, an error.
// - custom `impulses: [{amplitude, time_s}, ...]` as given (amplitudes summing to 1,
//         times >= 0 strictly ascending); frequency_hz / frequencies_hz and
//         design_damping_ratio then only say which vibration the grid realization keeps.
// The patent's methods 1-4 are PatternImpulses(MakeStepPattern(...)), unchanged; with
// several frequencies they are convolved like the others (and lose para. 50's steps).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "controller/grid_realization.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

// The shaper's impulse sequence for a shaped phase start (per unit step; mode is
// ignored): times ascending from the first impulse, amplitudes summing to 1. Method
// none: the unshaped step {0, 1}. `config` must be valid (PatternConfig::validate).
std::vector<Impulse> ShaperImpulses(const PatternConfig& config);

// One library shaper for one mode (method zv .. um_zv; not custom or 1-4).
std::vector<Impulse> SingleModeShaper(PatternMethod method, double frequency_hz,
                                      double damping_ratio, double vibration_tolerance);

// The convolution of two impulse sequences (impulses closer than 1e-12 s merged).
std::vector<Impulse> ConvolveImpulses(const std::vector<Impulse>& a, const std::vector<Impulse>& b);

// The design point(s) the grid realization keeps for this pattern: its design
// frequencies with design_damping_ratio (methods 1-4: undamped).
GridDesign ShaperGridDesign(const PatternConfig& config);

// The damped UM-ZV times (t2, t3) for a mode of `frequency_hz` and `damping_ratio`;
// throws ValidationError("design_damping_ratio") when Newton finds no solution.
std::pair<double, double> UnityMagnitudeZvTimes(double frequency_hz, double damping_ratio);

// Checks the library's keys of `config` (frequencies_hz, design_damping_ratio,
// vibration_tolerance, impulses); throws ValidationError naming the field, e.g.
// "impulses[2].time_s". Called by PatternConfig::validate().
void ValidateShaperKeys(const PatternConfig& config);

// The YAML name of a method: "none", "1".."4", "zv", ..., "custom".
std::string MethodName(PatternMethod method);

// The impulses of a profile table (alpha_n at t = n period_s).
std::vector<Impulse> TableImpulses(const std::vector<double>& table, double period_s);

// Duration (last impulse time), mean time sum A_j t_j and variance sum A_j (t_j - mean)^2
// of an impulse sequence with amplitudes summing to 1.
double ShaperDuration(const std::vector<Impulse>& impulses);
double ShaperMeanTime(const std::vector<Impulse>& impulses);
double ShaperVariance(const std::vector<Impulse>& impulses);

}  // namespace shapebench::controller
