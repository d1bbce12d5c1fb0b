#include "bench/sweep/sweep_plot.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "common/csv.h"
#include "common/ends_with.h"
#include "common/atomic_file.h"
#include "bench/output/gnuplot.h"
#include "bench/output/plot_labels.h"
#include "bench/output/report.h"
#include "bench/sweep/robust_band.h"
#include "bench/sweep/sweep_slice.h"

namespace shapebench::bench {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A line plot marks its points up to this many along x.
constexpr std::size_t kMaxMarkedPoints = 300;

const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};




std::string MetricLabel(const std::string& metric) {
  const std::string unit = MetricUnit(metric);
  if (unit == "m") return metric + " [um]";
  if (!unit.empty()) return metric + " [" + unit + "]";
  if (EndsWith(metric, "_ratio")) return metric + " [× static deflection]";
  return metric;
}

std::string KeyLabel(const std::string& key) {
  const std::string unit = KeyUnit(key);
  return unit.empty() ? key : key + " [" + unit + "]";
}


// Explicit tic labels for a key shown by index: at most about ten, evenly picked; each
// value named by what differs between them (whole pattern mappings: "method: zvd"), long
// ones cut and written whole into `caption`.
std::string IndexTics(const AxisValues& values, std::vector<std::string>* caption = nullptr) {
  const std::size_t n = values.texts.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + 9) / 10);
  std::vector<std::string> names;
  std::vector<std::string> full;
  const std::vector<std::string> parts = DifferingParts(values.texts);
  for (std::size_t i = 0; i < n; i += stride) {
    names.push_back(parts[i]);
    full.push_back(values.texts[i]);
  }
  const FittedLegend legend = FitLegend(names, full, 24);
  if (caption != nullptr) caption->insert(caption->end(), legend.caption.begin(), legend.caption.end());
  std::string tics = "(";
  for (std::size_t i = 0, k = 0; i < n; i += stride, ++k) {
    tics += (i == 0 ? "" : ", ") + GnuplotQuoted(legend.titles[k]) + " " + std::to_string(i);
  }
  return tics + ")";
}


std::string Title(const SweepLayout& layout, const std::string& what, const Slice& slice) {
  std::string title = layout.name + ": " + what;
  if (!slice.fixed.empty()) title += " (at " + slice.fixed + ")";
  return title;
}

// In log, a slice's non-positive values cannot be drawn: they become gaps. Returns
// whether the metric's axis is in log (LogMetricAxis, and some value left to draw).
bool ApplyLog(const SweepPlot& plot, Slice* slice) {
  if (!LogMetricAxis(plot, slice->z)) return false;
  bool any = false;
  for (double& z : slice->z) {
    if (!(z > 0.0)) z = kNaN;
    any = any || std::isfinite(z);
  }
  return any;
}

// A range around one value: +/-10% (a decade each way in log), [-1, 1] around 0.
std::pair<double, double> PaddedRange(double value, bool log) {
  if (log) return {value / 10.0, value * 10.0};
  const double pad = value == 0.0 ? 1.0 : 0.1 * std::abs(value);
  return {value - pad, value + pad};
}

// Tics of a log axis from `low` to `high` (> 0) that always show several values: 1, 2
// and 5 of each decade, every digit when that gives fewer than three, decades only over
// more than four decades.
std::string LogTics(double low, double high) {
  const int first = static_cast<int>(std::floor(std::log10(low)));
  const int last = static_cast<int>(std::ceil(std::log10(high)));
  static const std::vector<std::vector<int>> kDigits = {{1}, {1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
  for (const std::vector<int>& digits : kDigits) {
    std::vector<double> tics;
    for (int decade = first; decade <= last; ++decade) {
      for (const int digit : digits) {
        const double tic = digit * std::pow(10.0, decade);
        if (tic >= low * (1 - 1e-12) && tic <= high * (1 + 1e-12)) tics.push_back(tic);
      }
    }
    if (tics.size() >= 3 || digits.size() == 9) {
      if (digits.size() == 1 && last - first <= 4) continue;
      std::string list = "(";
      for (std::size_t i = 0; i < tics.size() && tics.size() <= 40; ++i) {
        list += (i == 0 ? "" : ", ") + ShortestDouble(tics[i]);
      }
      return list.size() > 1 ? list + ")" : "autofreq";
    }
  }
  return "autofreq";
}

// The page's height in pixels (the caption's rows are placed by it).
constexpr int kPageHeight = 640;

// The plot's target: the PNG, or an SVG for the HTML report and tests.
struct Target {
  std::string output_path;
  bool svg = false;
};

void Preamble(std::FILE* gnuplot, const Target& target, const std::string& title) {
  std::fprintf(gnuplot, target.svg ? "set terminal svg size 1000,%d noenhanced font 'sans,10' background '#ffffff'\n"
                                   : "set terminal pngcairo size 1000,%d noenhanced font 'sans,10'\n",
               kPageHeight);
  const std::string& output_path = target.output_path;
  std::fprintf(gnuplot, "set encoding utf8\n");
  std::fprintf(gnuplot, "set output %s\n", GnuplotQuoted(output_path).c_str());
  std::fprintf(gnuplot, "set title %s\n", GnuplotQuoted(title).c_str());
  std::fprintf(gnuplot, "set grid\n");
}

// The line plot's ranges gnuplot cannot derive without warning (no defined value, one
// value only; in log, values a million times under the largest), and the x range.
void SetLineRanges(std::FILE* gnuplot, const Slice& slice, double level, bool log) {
  const std::size_t nx = slice.x.texts.size();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const double z : slice.z) {
    if (std::isfinite(z)) low = std::min(low, z), high = std::max(high, z);
  }
  if (std::isfinite(level)) low = std::min(low, level), high = std::max(high, level);
  // In log, values a million times under the largest are numerical zeros (a shaper's
  // exact notch): the axis stops there rather than spend decades on them.
  if (log && std::isfinite(low) && low < 1e-6 * high) {
    std::fprintf(gnuplot, "set yrange [%.17g:*]\n", 1e-6 * high);
  }
  if (!std::isfinite(low)) {
    std::fprintf(gnuplot, "set yrange [0:1]\nset label 'no defined values' at graph 0.5, 0.5 center\n");
  } else if (low == high) {
    const auto range = PaddedRange(low, log);
    std::fprintf(gnuplot, "set yrange [%.17g:%.17g]\n", range.first, range.second);
  }
  // The x range spans every value of the key, defined or not (no empty range warnings).
  double x_low = slice.x.Coordinate(0);
  double x_high = x_low;
  for (std::size_t i = 0; i < nx; ++i) {
    x_low = std::min(x_low, slice.x.Coordinate(i));
    x_high = std::max(x_high, slice.x.Coordinate(i));
  }
  if (!slice.x.numeric) {
    x_low -= 0.5;
    x_high += 0.5;
  } else if (x_low == x_high) {
    const double pad = x_low == 0.0 ? 1.0 : 0.1 * std::abs(x_low);
    x_low -= pad;
    x_high += pad;
  }
  std::fprintf(gnuplot, "set xrange [%.17g:%.17g]\n", x_low, x_high);
}

// The series' legend: each named by what differs between the values (a whole pattern
// mapping per series reads "method: zvd"), long names cut, the full ones in the caption.
FittedLegend SeriesLegend(const SweepLayout& layout, const SweepPlot& plot, const Slice& slice) {
  if (plot.series.empty()) return FitLegend(std::vector<std::string>(slice.y.texts.size(), plot.metric), {});
  const std::string key = ShortKey(plot.series, layout.keys);
  const std::vector<std::string> parts = DifferingParts(slice.y.texts);
  std::vector<std::string> names;
  std::vector<std::string> full;
  for (std::size_t s = 0; s < slice.y.texts.size(); ++s) {
    const bool mapping = parts[s] != slice.y.texts[s];
    names.push_back(mapping ? parts[s] : key + " = " + slice.y.texts[s]);
    full.push_back(mapping ? plot.series + " = " + slice.y.texts[s] : names.back());
  }
  return FitLegend(names, full);
}

// The legend in rows under the plot (short samples, so the plot keeps the page's
// width), the caption under it; `entries` titles at most kMaxLegendChars wide.
void PlaceLegend(std::FILE* gnuplot, std::size_t entries, const std::vector<std::string>& caption) {
  const std::size_t columns = 3;
  const std::size_t rows = WriteCaption(gnuplot, caption, kPageHeight);
  std::fprintf(gnuplot,
               "set bmargin %zu\nset key at screen 0.5, screen %.6f center bottom horizontal maxcols %zu "
               "box samplen 2\n",
               5 + (entries + columns - 1) / columns + rows, CaptionHeight(rows, kPageHeight) + 0.01, columns);
  if (entries == 0) std::fprintf(gnuplot, "unset key\n");  // an empty box says nothing
}

// Each series' robust bands of this plot (robust_band.h) as a strip of its colour at the
// bottom of the plot, one strip per series; returns the legend's title for them or "".
std::string DrawBands(std::FILE* gnuplot, const SweepPlot& plot, const Slice& slice,
                      const std::vector<SeriesBands>& bands) {
  double threshold = kNaN;
  for (const SeriesBands& series : bands) {
    if (series.spec.metric != plot.metric || series.spec.x != plot.x || series.spec.series != plot.series) continue;
    std::size_t s = 0;
    while (s < slice.y.texts.size() && slice.y.texts[s] != series.series_value) ++s;
    const double low = 0.005 + 0.03 * static_cast<double>(s);
    for (const RobustBand& band : series.bands) {
      // A band of one point still shows: half a step each side.
      const double pad = slice.x.texts.size() > 1 ? 0.5 * std::abs(slice.x.numbers[1] - slice.x.numbers[0]) : 0.5;
      std::fprintf(gnuplot,
                   "set object rect from %.17g, graph %.4f to %.17g, graph %.4f fc rgb '%s' fs solid 0.45 "
                   "noborder front\n",
                   band.from - (band.from == band.to && !slice.x.log ? pad : 0.0), low,
                   band.to + (band.from == band.to && !slice.x.log ? pad : 0.0), low + 0.022,
                   kColors[s % (sizeof kColors / sizeof kColors[0])]);
    }
    threshold = series.spec.threshold;
  }
  if (std::isnan(threshold)) return "";
  return "robust bands <= " + ShortestDouble(threshold) + " (strips)";
}

// One data block and plot term per series value with a defined point.
std::vector<std::string> LineSeriesTerms(std::FILE* gnuplot, const FittedLegend& legend, const Slice& slice) {
  const std::size_t nx = slice.x.texts.size();
  std::vector<std::string> terms;
  for (std::size_t s = 0; s < slice.y.texts.size(); ++s) {
    bool any = false;
    std::fprintf(gnuplot, "$s%zu << EOD\n", s);
    for (std::size_t i = 0; i < nx; ++i) {
      const double z = slice.z[s * nx + i];
      if (std::isfinite(z)) {
        std::fprintf(gnuplot, "%.17g %.17g\n", slice.x.Coordinate(i), z);
        any = true;
      } else {
        std::fprintf(gnuplot, "\n");  // a gap: the line breaks at an undefined point
      }
    }
    std::fprintf(gnuplot, "EOD\n");
    if (!any) continue;
    const std::string& title = legend.titles[s];
    // Markers while they stay apart; beyond a few hundred points they merge into a ribbon.
    char term[256];
    std::snprintf(term, sizeof term, "$s%zu using 1:2 with %s lw 1.5 lc rgb '%s' title ", s,
                  nx > kMaxMarkedPoints ? "lines" : "linespoints pt 7 ps 0.4",
                  kColors[s % (sizeof kColors / sizeof kColors[0])]);
    terms.push_back(term + GnuplotQuoted(title));
  }
  return terms;
}

void LinePlotScript(std::FILE* gnuplot, const Target& target, const SweepLayout& layout, const SweepPlot& plot,
                    Slice slice, const std::vector<SeriesBands>& bands) {
  const double level = FivePercentLevel(plot.metric);
  const bool log = ApplyLog(plot, &slice);
  Preamble(gnuplot, target,
           Title(layout, plot.metric + " vs " + plot.x +
                             (plot.series.empty() ? "" : ", one line per " + plot.series),
                 slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(KeyLabel(plot.x)).c_str());
  std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  if (slice.x.numeric && slice.x.log) std::fprintf(gnuplot, "set logscale x\n");
  if (log) std::fprintf(gnuplot, "set logscale y\nset format y '%%g'\n");
  if (!slice.x.numeric) std::fprintf(gnuplot, "set xtics %s\n", IndexTics(slice.x).c_str());
  SetLineRanges(gnuplot, slice, level, log);
  const FittedLegend legend = SeriesLegend(layout, plot, slice);
  std::vector<std::string> terms = LineSeriesTerms(gnuplot, legend, slice);
  const auto add_level = [&](double value, const std::string& title, const char* dash) {
    char term[128];
    std::snprintf(term, sizeof term, "%.17g with lines dt %s lw 1.5 lc rgb '#444444' title ", value, dash);
    terms.push_back(term + GnuplotQuoted(title));
  };
  if (std::isfinite(level)) add_level(level, level > 1.0 ? "5% above static" : "5% level", "2");
  const std::string bands_title = slice.x.numeric ? DrawBands(gnuplot, plot, slice, bands) : "";
  for (const SeriesBands& series : bands) {  // a threshold of its own (a check, band_threshold:)
    if (series.spec.metric != plot.metric || series.spec.threshold == level) continue;
    add_level(series.spec.threshold, "threshold " + ShortestDouble(series.spec.threshold), "4");
    break;
  }
  if (!bands_title.empty()) terms.push_back("NaN with boxes fs solid 0.45 lc rgb '#888888' title " + GnuplotQuoted(bands_title));
  PlaceLegend(gnuplot, terms.size(), legend.caption);
  if (terms.empty()) terms.push_back("NaN notitle");
  std::fprintf(gnuplot, "plot ");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    std::fprintf(gnuplot, "%s%s", i == 0 ? "" : ", \\\n     ", terms[i].c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

// The empirical CDF of the metric over the samples (the slice's x axis), one step curve
// per series value, the checks' bounds as dashed vertical lines.
void CdfPlotScript(std::FILE* gnuplot, const Target& target, const SweepLayout& layout,
                   const SweepPlot& plot, const Slice& slice) {
  const std::size_t nx = slice.x.texts.size();
  Preamble(gnuplot, target,
           Title(layout, "empirical CDF of " + plot.metric + " over " + std::to_string(nx) + " samples" +
                             (plot.series.empty() ? "" : ", one line per " + plot.series),
                 slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  std::fprintf(gnuplot, "set ylabel 'fraction of samples at or below'\nset yrange [0:1.02]\n");
  const FittedLegend legend = SeriesLegend(layout, plot, slice);
  std::vector<std::string> terms;
  for (std::size_t s = 0; s < slice.y.texts.size(); ++s) {
    std::vector<double> values(slice.z.begin() + static_cast<std::ptrdiff_t>(s * nx),
                               slice.z.begin() + static_cast<std::ptrdiff_t>((s + 1) * nx));
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
                 values.end());
    if (values.empty()) continue;
    std::sort(values.begin(), values.end());
    std::fprintf(gnuplot, "$s%zu << EOD\n", s);
    // Fractions of all nx samples: an undefined value never counts as at or below.
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::fprintf(gnuplot, "%.17g %.17g\n", values[i], static_cast<double>(i + 1) / static_cast<double>(nx));
    }
    std::fprintf(gnuplot, "EOD\n");
    const std::string& title = legend.titles[s];
    char term[256];
    std::snprintf(term, sizeof term, "$s%zu using 1:2 with steps lw 1.5 lc rgb '%s' title ", s,
                  kColors[s % (sizeof kColors / sizeof kColors[0])]);
    terms.push_back(term + GnuplotQuoted(title));
  }
  for (const double limit : plot.limits) {
    std::fprintf(gnuplot, "set arrow from %.17g, graph 0 to %.17g, graph 1 nohead dt 2 lw 1.5 lc rgb '#444444'\n",
                 limit * MetricScale(plot.metric), limit * MetricScale(plot.metric));
    char term[128];
    std::snprintf(term, sizeof term, "NaN with lines dt 2 lw 1.5 lc rgb '#444444' title ");
    terms.push_back(term + GnuplotQuoted("limit " + ShortestDouble(limit)));
  }
  PlaceLegend(gnuplot, terms.size(), legend.caption);
  if (terms.empty()) terms.push_back("NaN notitle");
  std::fprintf(gnuplot, "plot ");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    std::fprintf(gnuplot, "%s%s", i == 0 ? "" : ", \\\n     ", terms[i].c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

void HeatMapScript(std::FILE* gnuplot, const Target& target, const SweepLayout& layout,
                   const SweepPlot& plot, Slice slice) {
  const double level = FivePercentLevel(plot.metric);
  const bool log = ApplyLog(plot, &slice);
  Preamble(gnuplot, target,
           Title(layout, plot.metric + " over " + plot.heatmap_x + " and " + plot.heatmap_y, slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(KeyLabel(plot.heatmap_x)).c_str());
  std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted(KeyLabel(plot.heatmap_y)).c_str());
  std::fprintf(gnuplot, "set cblabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  std::fprintf(gnuplot,
               "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21908d', "
               "0.75 '#5dc963', 1 '#fde725')\n");
  // Legend (the 5% contour) in its own strip under the x label.

  std::fprintf(gnuplot, "set autoscale fix\n");
  if (log) std::fprintf(gnuplot, "set logscale cb\nset format cb '%%g'\n");
  // Keys drawn at their values when evenly spaced numbers, else by index with labels.
  const bool x_values = slice.x.Uniform();
  const bool y_values = slice.y.Uniform();
  auto coordinate = [](const AxisValues& values, bool at_values, std::size_t i) {
    return at_values ? values.numbers[i] : static_cast<double>(i);
  };
  std::vector<std::string> caption;
  if (!x_values) std::fprintf(gnuplot, "set xtics %s\n", IndexTics(slice.x, &caption).c_str());
  if (!y_values) std::fprintf(gnuplot, "set ytics %s\n", IndexTics(slice.y, &caption).c_str());
  const std::size_t caption_rows = WriteCaption(gnuplot, caption, kPageHeight);
  std::fprintf(gnuplot, "set bmargin %zu\nset key at screen 0.5, screen %.6f center bottom horizontal box\n",
               6 + caption_rows, CaptionHeight(caption_rows, kPageHeight) + 0.02);
  std::fprintf(gnuplot, "set rmargin 14\n");  // the colour bar's label clear of the page's edge
  const std::size_t nx = slice.x.texts.size();
  const std::size_t ny = slice.y.texts.size();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  std::fprintf(gnuplot, "$heat << EOD\n");
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      const double z = slice.z[iy * nx + ix];
      if (std::isfinite(z)) low = std::min(low, z), high = std::max(high, z);
      std::fprintf(gnuplot, "%.17g %.17g %s\n", coordinate(slice.x, x_values, ix),
                   coordinate(slice.y, y_values, iy),
                   std::isfinite(z) ? ExactDouble(z).c_str() : "NaN");
    }
    std::fprintf(gnuplot, "\n");
  }
  std::fprintf(gnuplot, "EOD\n");
  if (log && std::isfinite(low) && low < 1e-6 * high) {  // numerical zeros, as in a line plot
    std::fprintf(gnuplot, "set cbrange [%.17g:*]\n", 1e-6 * high);
    low = 1e-6 * high;
  }
  if (log && std::isfinite(low) && low < high) std::fprintf(gnuplot, "set cbtics %s\n", LogTics(low, high).c_str());
  if (!std::isfinite(low)) {
    std::fprintf(gnuplot, "set cbrange [0:1]\nset label 'no defined values' at graph 0.5, 0.5 center front\n");
  } else if (low == high) {
    const auto range = PaddedRange(low, log);
    std::fprintf(gnuplot, "set cbrange [%.17g:%.17g]\n", range.first, range.second);
  }
  // The 5% level as a contour line, when the map crosses it.
  const bool contour = std::isfinite(level) && low < level && level < high && nx > 1 && ny > 1;
  if (contour) {
    std::fprintf(gnuplot,
                 "set contour base\nset cntrparam levels discrete %.17g\nunset surface\n"
                 "set table $contour\nsplot $heat using 1:2:3 with lines notitle\nunset table\n"
                 "unset contour\nset surface\n",
                 level);
  }
  if (!contour) std::fprintf(gnuplot, "unset key\n");  // nothing to name: no empty box
  std::fprintf(gnuplot, "plot $heat using 1:2:3 with image notitle");
  if (contour) {
    std::fprintf(gnuplot, ", \\\n     $contour using 1:2 with lines lw 2 lc rgb '#e31a1c' title %s",
                 GnuplotQuoted(level > 1.0 ? "5% above static" : "5% level").c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

}  // namespace

bool LogMetricAxis(const SweepPlot& plot, const std::vector<double>& values) {
  if (plot.log) return *plot.log;
  if (!EndsWith(plot.metric, "_ratio")) return false;
  double low = std::numeric_limits<double>::infinity();
  double high = 0.0;
  for (const double value : values) {
    if (std::isfinite(value) && value > 0.0) low = std::min(low, value), high = std::max(high, value);
  }
  return high > 0.0 && high > 100.0 * low;
}

namespace {

// One plot's script: `bands` drawn on a line plot.
void PlotScript(std::FILE* gnuplot, const Target& target, const SweepLayout& layout, const SweepPlot& plot,
                const std::string& results_csv, const std::vector<SeriesBands>& bands) {
  const Slice slice = plot.heatmap() ? ReadSlice(layout, results_csv, plot.metric, plot.heatmap_x, plot.heatmap_y)
                                     : ReadSlice(layout, results_csv, plot.metric, plot.x, plot.series);
  if (plot.heatmap()) {
    HeatMapScript(gnuplot, target, layout, plot, slice);
  } else if (plot.cdf) {
    CdfPlotScript(gnuplot, target, layout, plot, slice);
  } else {
    // Bands in the plot's units (a ratio's are its own).
    LinePlotScript(gnuplot, target, layout, plot, slice, bands);
  }
}

}  // namespace

std::vector<std::string> WriteSweepPlots(const std::string& out_dir, const SweepLayout& layout,
                                         const std::string& results_csv) {
  const std::vector<SeriesBands> bands = SweepBands(layout, results_csv);
  std::vector<std::string> written;
  for (const SweepPlot& plot : layout.plots) {
    const std::string path = (std::filesystem::path(out_dir) / SweepPlotFileName(plot, layout.keys)).string();
    RunGnuplot(path, [&](std::FILE* gnuplot, const std::string& output_path) {
      PlotScript(gnuplot, Target{output_path, false}, layout, plot, results_csv, bands);
    });
    written.push_back(path);
  }
  if (!layout.bands.empty()) {
    const std::string path = (std::filesystem::path(out_dir) / "bands.csv").string();
    const std::string csv = BandsCsv(bands);
    WriteFileAtomically(path, [&](std::ostream& out) { out << csv; });
    written.push_back(path);
    const std::string json_path = (std::filesystem::path(out_dir) / "bands.json").string();
    const std::string json = BandsJson(bands);
    WriteFileAtomically(json_path, [&](std::ostream& out) { out << json; });
    written.push_back(json_path);
  }
  return written;
}

std::string SweepPlotSvg(const SweepLayout& layout, const SweepPlot& plot, const std::string& results_csv) {
  const std::vector<SeriesBands> bands = SweepBands(layout, results_csv);
  return RunGnuplotSvg("the plot of " + plot.metric, [&](std::FILE* gnuplot, const std::string& output_path) {
    PlotScript(gnuplot, Target{output_path, true}, layout, plot, results_csv, bands);
  });
}

}  // namespace shapebench::bench
