// WriteDeflectionPlot (bench/output/report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/output/gnuplot.h"
#include "bench/output/html_report.h"
#include "bench/output/plot_labels.h"
#include "bench/output/report.h"

namespace shapebench::bench {
namespace {


// The page, the title and the axes' labels both deflection plots share.
// `svg`: the HTML report's inline SVG (bench/output/html_report.h) instead of the PNG.
void WriteFrame(std::FILE* gnuplot, const std::string& output_path, const std::string& title,
                bool svg) {
  std::fprintf(gnuplot, svg ? "set terminal svg size 1000,600 noenhanced font 'sans,10' background '#ffffff'\n"
                            : "set terminal pngcairo size 1000,600 noenhanced font 'sans,10'\n");
  std::fprintf(gnuplot, "set encoding utf8\n");
  std::fprintf(gnuplot, "set output %s\n", GnuplotQuoted(output_path).c_str());
  std::fprintf(gnuplot, "set title %s\n", GnuplotQuoted(title).c_str());
  std::fprintf(gnuplot, "set xlabel 'time [s]'\n");
  std::fprintf(gnuplot, "set ylabel 'deflection [um]'\n");
}

bool AllZero(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double d) { return d == 0.0; });
}

// The peak |deflection| marked with its value (um, and peak_ratio: times the static
// deflection), the end of the commanded motion labelled and the residual amplitude
// (residual_ratio's numerator) written just after it.
void WriteMarks(std::FILE* gnuplot, const RunResult& result, double end_s) {
  const Trace& trace = result.trace;
  const Metrics& metrics = result.metrics;
  std::size_t peak = 0;
  for (std::size_t i = 1; i < trace.deflection_m.size() && i < trace.time_s.size(); ++i) {
    if (std::abs(trace.deflection_m[i]) > std::abs(trace.deflection_m[peak])) peak = i;
  }
  if (peak < trace.time_s.size() && peak < trace.deflection_m.size()) {
    char text[128];
    const double peak_um = trace.deflection_m[peak] * 1e6;
    if (std::isfinite(metrics.peak_ratio)) {
      std::snprintf(text, sizeof text, "peak %.4g um (%.3g× static)", peak_um, metrics.peak_ratio);
    } else {
      std::snprintf(text, sizeof text, "peak %.4g um", peak_um);
    }
    std::fprintf(gnuplot, "set label %s at %.10g, %.10g offset 1, %s front point pt 7 ps 1 lc rgb '#d62728'\n",
                 GnuplotQuoted(text).c_str(), trace.time_s[peak], peak_um, peak_um >= 0.0 ? "0.8" : "-0.8");
  }
  if (std::isfinite(metrics.motion_time_s)) {
    // On the side of the end line with the more room.
    const char* side = metrics.motion_time_s > 0.6 * end_s ? "right offset -0.5, 0" : "left offset 0.5, 0";
    char text[160];
    std::snprintf(text, sizeof text, "motion end %.4g s", metrics.motion_time_s);
    std::fprintf(gnuplot, "set label %s at %.17g, graph 0.97 %s front tc rgb '#555555'\n",
                 GnuplotQuoted(text).c_str(), metrics.motion_time_s, side);
    if (std::isfinite(metrics.residual_amplitude_m)) {
      if (std::isfinite(metrics.residual_ratio)) {
        std::snprintf(text, sizeof text, "residual %.3g um (ratio %.3g)", metrics.residual_amplitude_m * 1e6,
                      metrics.residual_ratio);
      } else {
        std::snprintf(text, sizeof text, "residual %.3g um", metrics.residual_amplitude_m * 1e6);
      }
      std::fprintf(gnuplot, "set label %s at %.17g, graph 0.92 %s front tc rgb '#1f77b4'\n",
                   GnuplotQuoted(text).c_str(), metrics.motion_time_s, side);
    }
  }
}

// The peak's likely cause (metric_sources.h): a dashed line at its time, labelled with its
// block and line, when it lies before the peak (a cause at the peak's own tick is no news).
void WriteCauseMark(std::FILE* gnuplot, const RunResult& result) {
  const MetricSource& source = result.sources.peak_deflection;
  if (!source.present || !(source.cause.time_s < source.at.time_s)) return;
  std::string text = "cause of the peak: block " + std::to_string(source.cause.block);
  if (!source.cause.file.empty()) text += " (line " + std::to_string(source.cause.line) + ")";
  std::fprintf(gnuplot, "set arrow from %.17g, graph 0 to %.17g, graph 1 nohead dt 3 lc rgb '#d62728' back\n",
               source.cause.time_s, source.cause.time_s);
  std::fprintf(gnuplot, "set label %s at %.17g, graph 0.04 right offset -0.5, 0 front tc rgb '#d62728'\n",
               GnuplotQuoted(text).c_str(), source.cause.time_s);
}

void WriteScript(std::FILE* gnuplot, const std::string& output_path, const RunResult& result,
                 const Scenario& scenario, const std::string& title, bool svg = false) {
  const Trace& trace = result.trace;
  const double static_um = result.metrics.static_displacement_m * 1e6;
  const double end_s = trace.time_s.empty() ? 1.0 : trace.time_s.back();
  WriteFrame(gnuplot, output_path, title, svg);
  WriteMarks(gnuplot, result, end_s);
  WriteCauseMark(gnuplot, result);
  std::fprintf(gnuplot, "set offsets 0, 0, graph 0.12, 0\n");  // headroom for the labels
  std::fprintf(gnuplot, "set y2label 'command acceleration [m/s²]'\n");
  std::fprintf(gnuplot, "set ytics nomirror\nset y2tics\nset grid\n");
  // Legend in its own strip under the x label, clear of the curves.
  std::fprintf(gnuplot, "set bmargin 6\nset key at screen 0.5, screen 0.02 center bottom horizontal box\n");
  std::fprintf(gnuplot, "set xrange [0:%.17g]\n", end_s > 0.0 ? end_s : 1.0);
  if (std::isfinite(result.metrics.motion_time_s)) {
    std::fprintf(gnuplot,
                 "set arrow from %.17g, graph 0 to %.17g, graph 1 nohead dt 3 lc rgb '#888888'\n",
                 result.metrics.motion_time_s, result.metrics.motion_time_s);
  }
  // A rigid machine has no deflection: give gnuplot a range rather than let it warn.
  if (AllZero(trace.deflection_m)) {
    std::fprintf(gnuplot, "set yrange [-1:1]\n");
  }
  std::fprintf(gnuplot, "$trace << EOD\n");
  const std::size_t rows = std::min({trace.time_s.size(), trace.deflection_m.size(),
                                     trace.command_accel_m_s2.size()});
  // At most limits.max_trace_rows points, as in trace.csv.
  const std::size_t stride = TraceStride(trace.time_s.size(), scenario.limits.max_trace_rows);
  for (std::size_t i = 0; i < rows; i += stride) {
    std::fprintf(gnuplot, "%.10g %.10g %.10g\n", trace.time_s[i], trace.deflection_m[i] * 1e6,
                 trace.command_accel_m_s2[i]);
  }
  std::fprintf(gnuplot, "EOD\n");
  std::fprintf(gnuplot,
               "plot $trace using 1:2 axes x1y1 with lines lw 1.5 lc rgb '#1f77b4' "
               "title 'deflection [um]', \\\n"
               "     $trace using 1:3 axes x1y2 with lines lw 1 lc rgb '#ff7f0e' "
               "title 'command acceleration [m/s²]'");
  if (std::isfinite(static_um) && static_um > 0.0) {
    char band[64];
    std::snprintf(band, sizeof band, "static band ±%.4g um", static_um);
    std::fprintf(gnuplot,
                 ", \\\n     %.17g axes x1y1 with lines dt 2 lc rgb '#444444' title %s, \\\n"
                 "     %.17g axes x1y1 with lines dt 2 lc rgb '#444444' notitle",
                 static_um, GnuplotQuoted(band).c_str(), -static_um);
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

// Each run's deflection (um) as its own inline data block, $run0, $run1, ...
void WriteOverlayData(std::FILE* gnuplot, const std::vector<OverlaidRun>& runs) {
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Trace& trace = runs[r].result->trace;
    std::fprintf(gnuplot, "$run%zu << EOD\n", r);
    const std::size_t rows = std::min(trace.time_s.size(), trace.deflection_m.size());
    const std::size_t stride = TraceStride(trace.time_s.size(), runs[r].scenario->limits.max_trace_rows);
    for (std::size_t i = 0; i < rows; i += stride) {
      std::fprintf(gnuplot, "%.10g %.10g\n", trace.time_s[i], trace.deflection_m[i] * 1e6);
    }
    std::fprintf(gnuplot, "EOD\n");
  }
}

void WriteOverlayScript(std::FILE* gnuplot, const std::string& output_path,
                        const std::vector<OverlaidRun>& runs, const std::string& title,
                        bool svg = false) {
  static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
  const auto colour = [](std::size_t r) { return kColours[r % 4]; };
  WriteFrame(gnuplot, output_path, title, svg);
  std::fprintf(gnuplot, "set grid\n");
  // The legend names files and --set options: one entry a line in a strip under the plot,
  // a long one cut there and written whole in the caption under it.
  std::vector<std::string> titles;
  for (const OverlaidRun& run : runs) titles.push_back(run.title);
  const FittedLegend legend = FitLegend(titles, titles, 110);
  const std::size_t caption_rows = WriteCaption(gnuplot, legend.caption, 600);
  std::fprintf(gnuplot,
               "set bmargin %zu\nset key at screen 0.5, screen %.6f center bottom vertical Left reverse box\n",
               5 + 2 * runs.size() + caption_rows, CaptionHeight(caption_rows, 600) + 0.02);
  double end_s = 0.0;
  bool rigid = true;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const RunResult& result = *runs[r].result;
    if (!result.trace.time_s.empty()) end_s = std::max(end_s, result.trace.time_s.back());
    rigid = rigid && AllZero(result.trace.deflection_m);
    const double motion_s = result.metrics.motion_time_s;
    if (std::isfinite(motion_s)) {  // where each run's commanded motion ends
      std::fprintf(gnuplot, "set arrow from %.17g, graph 0 to %.17g, graph 1 nohead dt 3 lc rgb '%s'\n",
                   motion_s, motion_s, colour(r));
    }
  }
  std::fprintf(gnuplot, "set xrange [0:%.17g]\n", end_s > 0.0 ? end_s : 1.0);
  if (rigid) std::fprintf(gnuplot, "set yrange [-1:1]\n");
  WriteOverlayData(gnuplot, runs);
  std::string plot;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    plot += (plot.empty() ? "plot " : ", \\\n     ") + std::string("$run") + std::to_string(r) +
            " using 1:2 with lines lw 1.5 lc rgb '" + colour(r) + "' title " + GnuplotQuoted(legend.titles[r]);
  }
  plot += ", \\\n     NaN with lines dt 3 lc rgb '#888888' "
          "title 'end of commanded motion (dotted, in the run''s colour)'";
  // The static band of each run, dashed in its colour; once, grey, when the runs' bands
  // read the same (two shapings' static solves differ by rounding only).
  const auto static_um = [&](std::size_t r) { return runs[r].result->metrics.static_displacement_m * 1e6; };
  const auto band = [&](std::size_t r) {
    char text[64];
    std::snprintf(text, sizeof text, "static band ±%.4g um", static_um(r));
    return std::string(text);
  };
  bool shared = true;
  for (std::size_t r = 1; r < runs.size(); ++r) shared = shared && band(r) == band(0);
  for (std::size_t r = 0; r < (shared ? std::min<std::size_t>(runs.size(), 1) : runs.size()); ++r) {
    if (!std::isfinite(static_um(r)) || !(static_um(r) > 0.0)) continue;
    const std::string title = shared ? band(r) : band(r) + " (" + runs[r].name + ")";
    const std::string style =
        std::string(" with lines dt 2 lw 1 lc rgb '") + (shared ? "#444444" : colour(r)) + "'";
    char line[128];
    std::snprintf(line, sizeof line, ", \\\n     %.17g", static_um(r));
    plot += line + style + " title " + GnuplotQuoted(title);
    std::snprintf(line, sizeof line, ", \\\n     %.17g", -static_um(r));
    plot += line + style + " notitle";
  }
  std::fprintf(gnuplot, "%s\nunset output\nquit\n", plot.c_str());
}

}  // namespace

void WriteDeflectionOverlayPlot(const std::string& path_png, const std::vector<OverlaidRun>& runs,
                                const std::string& title) {
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    WriteOverlayScript(gnuplot, output_path, runs, title);
  });
}

void WriteDeflectionPlot(const std::string& path_png, const RunResult& result,
                         const Scenario& scenario, const std::string& title) {
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    WriteScript(gnuplot, output_path, result, scenario, title);
  });
}

std::string DeflectionSvg(const RunResult& result, const Scenario& scenario) {
  return RunGnuplotSvg("the deflection plot", [&](std::FILE* gnuplot, const std::string& output_path) {
    WriteScript(gnuplot, output_path, result, scenario, scenario.name, /*svg=*/true);
  });
}

std::string DeflectionOverlaySvg(const std::vector<OverlaidRun>& runs, const std::string& title) {
  return RunGnuplotSvg("the deflection plot", [&](std::FILE* gnuplot, const std::string& output_path) {
    WriteOverlayScript(gnuplot, output_path, runs, title, /*svg=*/true);
  });
}

}  // namespace shapebench::bench
