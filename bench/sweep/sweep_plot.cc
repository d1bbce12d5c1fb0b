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
#include "common/fd_stream.h"
#include "bench/output/gnuplot.h"
#include "bench/output/report.h"

namespace shapebench::bench {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A line plot marks its points up to this many along x.
constexpr std::size_t kMaxMarkedPoints = 300;

const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};


bool ParseNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

// Metrics in metres are plotted in um (micrometres).
double MetricScale(const std::string& metric) { return MetricUnit(metric) == "m" ? 1e6 : 1.0; }

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

// The values of one plotted key along its axis: numbers when every one is a number.
struct AxisValues {
  std::vector<std::string> texts;
  std::vector<double> numbers;
  bool numeric = true;
  bool log = false;

  // The coordinate of the i-th value: the number, or the index for text values.
  double Coordinate(std::size_t i) const { return numeric ? numbers[i] : static_cast<double>(i); }
  // Evenly spaced numbers (a heat map draws them at their values; otherwise by index).
  bool Uniform() const {
    if (!numeric || log || numbers.size() < 2) return numeric && !log;
    const double step = (numbers.back() - numbers.front()) / static_cast<double>(numbers.size() - 1);
    if (step == 0.0) return false;
    for (std::size_t i = 1; i < numbers.size(); ++i) {
      if (std::abs(numbers[i] - numbers[i - 1] - step) > 1e-9 * std::abs(step)) return false;
    }
    return true;
  }
  void Finish() {
    numbers.assign(texts.size(), kNaN);
    for (std::size_t i = 0; i < texts.size(); ++i) numeric = numeric && ParseNumber(texts[i], &numbers[i]);
  }
};

// Explicit tic labels for a key shown by index: at most about ten, evenly picked.
std::string IndexTics(const AxisValues& values) {
  const std::size_t n = values.texts.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + 9) / 10);
  std::string tics = "(";
  for (std::size_t i = 0; i < n; i += stride) {
    tics += (i == 0 ? "" : ", ") + GnuplotQuoted(values.texts[i]) + " " + std::to_string(i);
  }
  return tics + ")";
}

// One plot's slice of results.csv: the rows whose other axes are at their first value.
struct Slice {
  AxisValues x;
  AxisValues y;  // series (line plot) or the heat map's y key; one empty value if none
  std::vector<double> z;  // [iy * nx + ix], NaN where undefined or failed
  std::string fixed;      // "k=v, ..." of the keys held at their first value
};

Slice ReadSlice(const SweepLayout& layout, const std::string& results_csv, const std::string& metric,
                const std::string& x_key, const std::string& y_key) {
  auto key_index = [&](const std::string& key) {
    for (std::size_t i = 0; i < layout.keys.size(); ++i) {
      if (layout.keys[i] == key) return i;
    }
    throw std::runtime_error("plot key '" + key + "' is not a column of " + results_csv);
  };
  const std::size_t kx = key_index(x_key);
  const std::size_t ax = layout.key_axis[kx];
  const bool has_y = !y_key.empty();
  const std::size_t ky = has_y ? key_index(y_key) : 0;
  const std::size_t ay = has_y ? layout.key_axis[ky] : layout.axis_sizes.size();
  const std::size_t nx = layout.axis_sizes[ax];
  const std::size_t ny = has_y ? layout.axis_sizes[ay] : 1;

  std::size_t metric_column = 0;
  for (std::size_t i = 0; i < layout.metrics.size(); ++i) {
    if (layout.metrics[i] == metric) metric_column = 1 + layout.keys.size() + i;
  }
  if (metric_column == 0) throw std::runtime_error("metric '" + metric + "' is not a column of " + results_csv);

  Slice slice;
  slice.x.texts.assign(nx, "");
  slice.y.texts.assign(ny, "");
  slice.x.log = layout.key_log[kx];
  slice.y.log = has_y && layout.key_log[ky];
  slice.z.assign(nx * ny, kNaN);

  InputFile in(results_csv);
  CsvReader reader(in.stream());
  std::vector<std::string> fields;
  reader.Next(&fields);  // header
  const double scale = MetricScale(metric);
  bool fixed_done = false;
  while (reader.Next(&fields)) {
    if (fields.size() != 3 + layout.keys.size() + layout.metrics.size()) continue;
    std::uint64_t point = std::strtoull(fields[0].c_str(), nullptr, 10);
    std::vector<std::uint64_t> digits(layout.axis_sizes.size(), 0);
    for (std::size_t a = layout.axis_sizes.size(); a-- > 0;) {
      digits[a] = point % layout.axis_sizes[a];
      point /= layout.axis_sizes[a];
    }
    bool in_slice = true;
    for (std::size_t a = 0; a < digits.size(); ++a) {
      if (a != ax && a != ay && digits[a] != 0) in_slice = false;
    }
    if (!in_slice) continue;
    const std::size_t ix = digits[ax];
    const std::size_t iy = has_y ? digits[ay] : 0;
    slice.x.texts[ix] = fields[1 + kx];
    if (has_y) slice.y.texts[iy] = fields[1 + ky];
    double value = kNaN;
    if (ParseNumber(fields[metric_column], &value)) slice.z[iy * nx + ix] = value * scale;
    if (!fixed_done) {
      for (std::size_t k = 0; k < layout.keys.size(); ++k) {
        const std::size_t a = layout.key_axis[k];
        if (a == ax || a == ay) continue;
        slice.fixed += (slice.fixed.empty() ? "" : ", ") + layout.keys[k] + "=" + fields[1 + k];
      }
      fixed_done = true;
    }
  }
  in.ThrowIfFailed();
  slice.x.Finish();
  slice.y.Finish();
  return slice;
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

void Preamble(std::FILE* gnuplot, const std::string& output_path, const std::string& title) {
  std::fprintf(gnuplot, "set terminal pngcairo size 1000,640 noenhanced font 'sans,10'\n");
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

// One data block and plot term per series value with a defined point.
std::vector<std::string> LineSeriesTerms(std::FILE* gnuplot, const SweepLayout& layout,
                                         const SweepPlot& plot, const Slice& slice) {
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
    const std::string title =
        plot.series.empty() ? plot.metric : ShortKey(plot.series, layout.keys) + " = " + slice.y.texts[s];
    // Markers while they stay apart; beyond a few hundred points they merge into a ribbon.
    char term[256];
    std::snprintf(term, sizeof term, "$s%zu using 1:2 with %s lw 1.5 lc rgb '%s' title ", s,
                  nx > kMaxMarkedPoints ? "lines" : "linespoints pt 7 ps 0.4",
                  kColors[s % (sizeof kColors / sizeof kColors[0])]);
    terms.push_back(term + GnuplotQuoted(title));
  }
  return terms;
}

void LinePlotScript(std::FILE* gnuplot, const std::string& output_path, const SweepLayout& layout,
                    const SweepPlot& plot, Slice slice) {
  const double level = FivePercentLevel(plot.metric);
  const bool log = ApplyLog(plot, &slice);
  Preamble(gnuplot, output_path,
           Title(layout, plot.metric + " vs " + plot.x +
                             (plot.series.empty() ? "" : ", one line per " + plot.series),
                 slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(KeyLabel(plot.x)).c_str());
  std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  // The legend in rows under the plot, short samples: the plot keeps the page's width.
  const std::size_t entries = slice.y.texts.size() + (std::isfinite(level) ? 1 : 0);
  std::fprintf(gnuplot,
               "set bmargin %zu\nset key at screen 0.5, screen 0.01 center bottom horizontal maxcols 4 "
               "box samplen 2\n",
               5 + (entries + 3) / 4);
  if (slice.x.numeric && slice.x.log) std::fprintf(gnuplot, "set logscale x\n");
  if (log) std::fprintf(gnuplot, "set logscale y\nset format y '%%g'\n");
  if (!slice.x.numeric) std::fprintf(gnuplot, "set xtics %s\n", IndexTics(slice.x).c_str());
  SetLineRanges(gnuplot, slice, level, log);
  std::vector<std::string> terms = LineSeriesTerms(gnuplot, layout, plot, slice);
  if (std::isfinite(level)) {
    char term[128];
    std::snprintf(term, sizeof term, "%.17g with lines dt 2 lw 1.5 lc rgb '#444444' title ", level);
    terms.push_back(term + GnuplotQuoted(level > 1.0 ? "5% above static" : "5% level"));
  }
  if (terms.empty()) terms.push_back("NaN notitle");
  std::fprintf(gnuplot, "plot ");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    std::fprintf(gnuplot, "%s%s", i == 0 ? "" : ", \\\n     ", terms[i].c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

// The empirical CDF of the metric over the samples (the slice's x axis), one step curve
// per series value, the checks' bounds as dashed vertical lines.
void CdfPlotScript(std::FILE* gnuplot, const std::string& output_path, const SweepLayout& layout,
                   const SweepPlot& plot, const Slice& slice) {
  const std::size_t nx = slice.x.texts.size();
  Preamble(gnuplot, output_path,
           Title(layout, "empirical CDF of " + plot.metric + " over " + std::to_string(nx) + " samples" +
                             (plot.series.empty() ? "" : ", one line per " + plot.series),
                 slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  std::fprintf(gnuplot, "set ylabel 'fraction of samples at or below'\nset yrange [0:1.02]\n");
  std::fprintf(gnuplot, "set key bottom right box\n");
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
    const std::string title =
        plot.series.empty() ? plot.metric : ShortKey(plot.series, layout.keys) + " = " + slice.y.texts[s];
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
  if (terms.empty()) terms.push_back("NaN notitle");
  std::fprintf(gnuplot, "plot ");
  for (std::size_t i = 0; i < terms.size(); ++i) {
    std::fprintf(gnuplot, "%s%s", i == 0 ? "" : ", \\\n     ", terms[i].c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

void HeatMapScript(std::FILE* gnuplot, const std::string& output_path, const SweepLayout& layout,
                   const SweepPlot& plot, Slice slice) {
  const double level = FivePercentLevel(plot.metric);
  const bool log = ApplyLog(plot, &slice);
  Preamble(gnuplot, output_path,
           Title(layout, plot.metric + " over " + plot.heatmap_x + " and " + plot.heatmap_y, slice));
  std::fprintf(gnuplot, "set xlabel %s\n", GnuplotQuoted(KeyLabel(plot.heatmap_x)).c_str());
  std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted(KeyLabel(plot.heatmap_y)).c_str());
  std::fprintf(gnuplot, "set cblabel %s\n", GnuplotQuoted(MetricLabel(plot.metric)).c_str());
  std::fprintf(gnuplot,
               "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21908d', "
               "0.75 '#5dc963', 1 '#fde725')\n");
  // Legend (the 5% contour) in its own strip under the x label.
  std::fprintf(gnuplot, "set bmargin 6\nset key at screen 0.5, screen 0.02 center bottom horizontal box\n");
  std::fprintf(gnuplot, "set autoscale fix\n");
  if (log) std::fprintf(gnuplot, "set logscale cb\nset format cb '%%g'\n");
  // Keys drawn at their values when evenly spaced numbers, else by index with labels.
  const bool x_values = slice.x.Uniform();
  const bool y_values = slice.y.Uniform();
  auto coordinate = [](const AxisValues& values, bool at_values, std::size_t i) {
    return at_values ? values.numbers[i] : static_cast<double>(i);
  };
  if (!x_values) std::fprintf(gnuplot, "set xtics %s\n", IndexTics(slice.x).c_str());
  if (!y_values) std::fprintf(gnuplot, "set ytics %s\n", IndexTics(slice.y).c_str());
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
  }
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
  std::fprintf(gnuplot, "plot $heat using 1:2:3 with image notitle");
  if (contour) {
    std::fprintf(gnuplot, ", \\\n     $contour using 1:2 with lines lw 2 lc rgb '#e31a1c' title %s",
                 GnuplotQuoted(level > 1.0 ? "5% above static" : "5% level").c_str());
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

std::string SafeName(const std::string& text) {
  std::string name;
  for (const char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == '-';
    name += keep ? c : '_';
  }
  return name;
}

}  // namespace

double FivePercentLevel(const std::string& metric) {
  if (metric == "peak_ratio") return 1.05;
  if (metric == "residual_ratio" || metric == "residual_peak_ratio" || metric == "cruise_residual_ratio") {
    return 0.05;
  }
  return kNaN;
}

SweepLayout SweepLayout::Of(const Sweep& sweep) {
  SweepLayout layout;
  layout.name = sweep.name;
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    layout.axis_sizes.push_back(sweep.axes[a].size());
    for (const auto& values : sweep.axes[a].keys) {
      layout.keys.push_back(values.key);
      layout.key_axis.push_back(a);
      layout.key_log.push_back(values.log());
    }
  }
  layout.metrics = sweep.metrics;
  layout.plots = sweep.plots;
  return layout;
}

nlohmann::ordered_json SweepLayout::ToJson() const {
  nlohmann::ordered_json json;
  json["name"] = name;
  json["keys"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    json["keys"].push_back({{"key", keys[k]}, {"axis", key_axis[k]}, {"log", bool(key_log[k])}});
  }
  json["axis_sizes"] = axis_sizes;
  json["metrics"] = metrics;
  json["plots"] = nlohmann::ordered_json::array();
  for (const SweepPlot& plot : plots) {
    nlohmann::ordered_json entry;
    entry["metric"] = plot.metric;
    if (plot.heatmap()) {
      entry["heatmap"] = {plot.heatmap_x, plot.heatmap_y};
    } else {
      entry["x"] = plot.x;
      if (!plot.series.empty()) entry["series"] = plot.series;
    }
    if (plot.log) entry["log"] = *plot.log;
    if (plot.cdf) {
      entry["cdf"] = true;
      entry["limits"] = plot.limits;
    }
    json["plots"].push_back(entry);
  }
  return json;
}

SweepLayout SweepLayout::FromJson(const nlohmann::json& json) {
  // 1e30 or -1 as an axis or a size is no layout (and converting 1e30 is undefined).
  const auto whole = [](const nlohmann::json& value) {
    if (!value.is_number_unsigned()) throw std::runtime_error("malformed sweep layout: expected a whole number");
    return value.get<std::uint64_t>();
  };
  try {
    for (const char* list : {"keys", "axis_sizes", "plots"}) {
      if (!json.at(list).is_array()) {
        throw std::runtime_error(std::string("malformed sweep layout: ") + list + ": expected an array");
      }
    }
    SweepLayout layout;
    layout.name = json.at("name").get<std::string>();
    for (const auto& key : json.at("keys")) {
      layout.keys.push_back(key.at("key").get<std::string>());
      layout.key_axis.push_back(whole(key.at("axis")));
      layout.key_log.push_back(key.at("log").get<bool>());
    }
    for (const auto& size : json.at("axis_sizes")) layout.axis_sizes.push_back(whole(size));
    layout.metrics = json.at("metrics").get<std::vector<std::string>>();
    for (const auto& entry : json.at("plots")) {
      SweepPlot plot;
      plot.metric = entry.at("metric").get<std::string>();
      if (entry.contains("heatmap")) {
        if (entry.at("heatmap").size() != 2) throw std::runtime_error("malformed sweep layout: heatmap: expected two keys");
        plot.heatmap_x = entry.at("heatmap").at(0).get<std::string>();
        plot.heatmap_y = entry.at("heatmap").at(1).get<std::string>();
      } else {
        plot.x = entry.at("x").get<std::string>();
        if (entry.contains("series")) plot.series = entry.at("series").get<std::string>();
      }
      if (entry.contains("log")) plot.log = entry.at("log").get<bool>();
      if (entry.contains("cdf")) {
        plot.cdf = entry.at("cdf").get<bool>();
        plot.limits = entry.at("limits").get<std::vector<double>>();
      }
      layout.plots.push_back(plot);
    }
    for (const auto axis : layout.key_axis) {
      if (axis >= layout.axis_sizes.size()) throw std::runtime_error("a key's axis is out of range");
    }
    for (const auto size : layout.axis_sizes) {
      if (size == 0) throw std::runtime_error("an axis has no values");
    }
    return layout;
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error(std::string("malformed sweep layout: ") + error.what());
  }
}

std::string ShortKey(const std::string& key, const std::vector<std::string>& keys) {
  // Dotted components from the end: the first suffix no other key ends with.
  for (std::size_t dot = key.size(); dot != std::string::npos;) {
    dot = dot == 0 ? std::string::npos : key.rfind('.', dot - 1);
    const std::string suffix = dot == std::string::npos ? key : key.substr(dot + 1);
    bool unique = true;
    for (const std::string& other : keys) {
      if (other == key) continue;
      unique = unique && !(other == suffix || EndsWith(other, "." + suffix));
    }
    if (unique) return suffix;
  }
  return key;
}

std::string SweepPlotFileName(const SweepPlot& plot, const std::vector<std::string>& keys) {
  const auto key = [&](const std::string& name) { return ShortKey(name, keys); };
  if (plot.cdf) return SafeName(plot.metric + "-cdf" + (plot.series.empty() ? "" : "-by-" + key(plot.series))) + ".png";
  if (plot.heatmap()) {
    return SafeName(plot.metric + "-over-" + key(plot.heatmap_x) + "-and-" + key(plot.heatmap_y)) + ".png";
  }
  return SafeName(plot.metric + "-vs-" + key(plot.x) + (plot.series.empty() ? "" : "-by-" + key(plot.series))) +
         ".png";
}

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

std::vector<std::string> WriteSweepPlots(const std::string& out_dir, const SweepLayout& layout,
                                         const std::string& results_csv) {
  std::vector<std::string> written;
  for (const SweepPlot& plot : layout.plots) {
    const std::string path = (std::filesystem::path(out_dir) / SweepPlotFileName(plot, layout.keys)).string();
    const Slice slice = plot.heatmap()
                            ? ReadSlice(layout, results_csv, plot.metric, plot.heatmap_x, plot.heatmap_y)
                            : ReadSlice(layout, results_csv, plot.metric, plot.x, plot.series);
    RunGnuplot(path, [&](std::FILE* gnuplot, const std::string& output_path) {
      if (plot.heatmap()) {
        HeatMapScript(gnuplot, output_path, layout, plot, slice);
      } else if (plot.cdf) {
        CdfPlotScript(gnuplot, output_path, layout, plot, slice);
      } else {
        LinePlotScript(gnuplot, output_path, layout, plot, slice);
      }
    });
    written.push_back(path);
  }
  return written;
}

}  // namespace shapebench::bench
