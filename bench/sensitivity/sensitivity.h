// `shapebench sensitivity FILE.yaml [--set ...] [--out DIR]`: residual vibration of
// shapers against the plant's natural frequency, in percent of the vibration an unshaped
// step leaves, and the width of the band where it stays low (the robustness a shaper buys
// with its duration).
//
// The sensitivity file (every key optional except `shapers`):
//   shapers:                   # each a pattern mapping as in controller.pattern, plus an
//     - {method: zv, frequency_hz: 25}               # optional `label` for table and plot
//     - {method: ei, frequency_hz: 25, vibration_tolerance: 0.05, label: EI 5%}
//     - {method: zvd, frequencies_hz: [25, 60], design_damping_ratio: 0.05}
//   ratio: {from: 0.5, to: 1.5, steps: 401}   # plant frequency / design frequency
//   damping_ratios: [0.0]      # the plant's damping; one curve per shaper and value
//   level: 0.05                # a band level (fraction); the 5% band is always reported
//   period_s: 0.001            # also evaluate each shaper's realized profile table on
//                              # this grid (grid_realization.h), one more curve each
// The design frequency of a shaper with several (frequencies_hz) is its first one. A
// curve is V(r) = ResidualVibration(impulses, r f_design, zeta_plant): the residual
// after the shaped step of a mode at r times the design frequency (its undamped natural
// frequency) with the plant's damping, as a fraction of an unshaped step's.
//
// Band: the contiguous interval of r around the design point where V <= level. It
// starts at r = 1 (or, when V(1) > level, at the sample nearest 1 with V <= level),
// extends outward in steps of at most 1e-3 in r (beyond the plotted range if need be,
// from r -> 0 up to 10 x max(1, to)), and each edge is bisected to 1e-12; its width is
// high - low. Values within 1e-9 relative of the level count as inside (EI touches its
// tolerance at r = 1 by design). A local maximum of the steps' samples is refined by
// golden-section (common/interval_search.h, the search band checks use): a hump that
// touches the level (its peak within 1e-6 relative of it: EI's design hump, also when
// realized on a grid) stays inside, one that rises above it between two samples ends the
// band at its rising crossing.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/config/override.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::bench {

struct SensitivityShaper {
  controller::PatternConfig pattern;
  std::string label;
};

struct SensitivitySpec {
  std::vector<SensitivityShaper> shapers;
  double ratio_from = 0.5;
  double ratio_to = 1.5;
  long ratio_steps = 401;
  std::vector<double> damping_ratios = {0.0};
  double level = 0.05;
  std::optional<double> period_s;
  std::string source_file;
};

// Reads, overrides and validates a sensitivity file; every error is a ConfigError at
// FILE:LINE:COL (or --set:N:1) with its key path, e.g. "shapers[1].design_damping_ratio".
SensitivitySpec LoadSensitivity(const std::string& path, const std::vector<Override>& overrides);

struct Band {
  bool found = false;  // false: V > level everywhere sampled
  double low = 0.0;
  double high = 0.0;
  bool open_low = false;   // still inside at r -> 0
  bool open_high = false;  // still inside at the search's upper end
  double width() const { return found ? high - low : 0.0; }
};

// The band of `residual` (a fraction, as a function of the ratio) below `level` around
// r = 1 (see above); `from`/`to` bound where a start point is looked for.
Band BandAroundDesign(const std::function<double(double)>& residual, double level, double from,
                      double to);

struct SensitivityCurve {
  std::string label;           // the shaper's
  std::size_t shaper = 0;      // index into SensitivitySpec::shapers
  double damping_ratio = 0.0;  // the plant's
  bool realized = false;       // the profile table on period_s rather than the impulses
  std::vector<double> residual_percent;  // at SensitivityResult::ratio
  double at_design_percent = 0.0;        // V(1)
  Band band_5;      // V <= 5%
  Band band_level;  // V <= level
};

struct SensitivityResult {
  std::vector<double> ratio;
  double level = 0.05;
  std::optional<double> period_s;
  std::vector<SensitivityCurve> curves;
};

// Residual in percent of the unshaped at plant frequency / design frequency `ratio`.
double ResidualPercent(const std::vector<controller::Impulse>& impulses, double design_hz,
                       double ratio, double plant_damping_ratio);

SensitivityResult ComputeSensitivity(const SensitivitySpec& spec);

// One line per curve: label, plant damping, grid, V(1), the 5% band and the level band.
void PrintSensitivityTable(std::ostream& out, const SensitivityResult& result);

// ratio, then one column per curve (percent), named "<label> zeta=<plant damping>" and
// " table <period> s" for realized tables; %.10g.
void WriteSensitivityCsv(const std::string& path, const SensitivityResult& result);

// The curves over the ratio with labelled axes, a legend and the 5% level (and `level`)
// marked; realized tables dashed. pngcairo via gnuplot.
void WriteSensitivityPlot(const std::string& path_png, const SensitivityResult& result,
                          const std::string& title);

// The column name of a curve in the CSV and its legend entry.
std::string CurveName(const SensitivityCurve& curve, const SensitivityResult& result);

}  // namespace shapebench::bench
