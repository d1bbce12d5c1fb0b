// The plots of a sweep, drawn from results.csv (so `merge` draws the same ones): a metric
// against one swept key, one line per value of a second key, or a heat map over two
// keys. Axes carry the keys' and metrics' units; ratios get their 5% level (residual
// ratios at 0.05, peak_ratio at 1.05: 5% above the static deflection). Keys of the other
// axes are held at their first value (the title says which).
#pragma once

#include <string>
#include <vector>

#include "bench/sweep/sweep_layout.h"

namespace shapebench::bench {

// Whether the metric's axis (a heat map's colour scale) is drawn in log: the plot's
// `log:` when given; else for a ratio metric whose positive `values` span more than two
// decades (a residual ratio from 1e-4 to 2 would leave everything under 5% flat).
// Non-positive values are then left out (gaps).
bool LogMetricAxis(const SweepPlot& plot, const std::vector<double>& values);

// Draws every plot of `layout` from `results_csv` into `out_dir`, the robust bands on
// the line plots, and writes bands.csv and bands.json when the layout has bands; returns the paths
// written. Throws std::runtime_error when gnuplot is missing or fails.
std::vector<std::string> WriteSweepPlots(const std::string& out_dir, const SweepLayout& layout,
                                         const std::string& results_csv);

// One plot of `layout` as an SVG element (the HTML report, tests): the PNG's drawing.
std::string SweepPlotSvg(const SweepLayout& layout, const SweepPlot& plot, const std::string& results_csv);

}  // namespace shapebench::bench
