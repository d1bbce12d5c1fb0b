// The damping of a mode whose peak is narrower than a line, from its own neighbourhood
// (docs/measured-data.md, the identification's step 6b). Its half-power width 2 zeta f
// under the line spacing, no line sees its top: the lines either side fix its frequency
// and modal constant but barely its damping, and a fit of the whole band, weighted by the
// larger peaks elsewhere, leaves that damping where any of a range of values fits as well
// (pyuff's beam at 1 Hz lines: 0.000282 or 0.000543 at 51.5 Hz change the whole band's
// fit error by 0.005 points, its neighbourhood's by 0.9). Its neighbourhood does tell.
#pragma once

#include <complex>
#include <vector>

#include "model/modal_refinement.h"

namespace shapebench::model {

// The golden-section search's steps on one narrow peak's damping (its charge in the
// identification's work: two evaluations to start, one a step).
inline constexpr int kGoldenSectionSteps = 60;

// For each such mode of `model` (poles ascending in frequency): the damping ratio that
// fits best the lines between the midpoints to its neighbouring modes (the band's ends
// for the outer ones), by the mode alone with lower and upper residuals (LSFD at each
// trial), searched in [zeta / 5, 5 zeta]; its natural frequency kept. The new dampings are
// kept, and every linear term refitted on the whole band, when the whole band's squared
// error grows by at most `max_error_growth` (a fraction). Returns, per pole, whether its
// damping now comes from its neighbourhood.
std::vector<bool> LocalDampingOfNarrowPeaks(const std::vector<double>& x,
                                            const std::vector<std::vector<std::complex<double>>>& data, int d,
                                            double max_damping_ratio, double max_error_growth, ModalModel* model);

// The mode whose removal (the other poles' linear terms refitted by LSFD) raises the fit
// error 100 ||H_fit - H|| / ||H|| over the lines the least; that rise in points in
// `rise_percent`. `model` has one pole at least.
std::size_t LeastContribution(const std::vector<double>& x, const std::vector<std::vector<std::complex<double>>>& data,
                              int d, const ModalModel& model, double* rise_percent);

}  // namespace shapebench::model
