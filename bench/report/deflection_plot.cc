// WriteDeflectionPlot (bench/report/report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/report/gnuplot.h"
#include "bench/report/report.h"

namespace shapebench::bench {
namespace {

const auto& Quoted = GnuplotQuoted;

void WriteScript(std::FILE* gnuplot, const std::string& output_path, const RunResult& result,
                 const Scenario& scenario) {
  const Trace& trace = result.trace;
  const double static_um = result.metrics.static_displacement_m * 1e6;
  const double end_s = trace.time_s.empty() ? 1.0 : trace.time_s.back();
  std::fprintf(gnuplot, "set terminal pngcairo size 1000,600 noenhanced font 'sans,10'\n");
  std::fprintf(gnuplot, "set encoding utf8\n");
  std::fprintf(gnuplot, "set output %s\n", Quoted(output_path).c_str());
  std::fprintf(gnuplot, "set title %s\n", Quoted(scenario.name).c_str());
  std::fprintf(gnuplot, "set xlabel 'time [s]'\n");
  std::fprintf(gnuplot, "set ylabel 'deflection [µm]'\n");
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
  if (std::all_of(trace.deflection_m.begin(), trace.deflection_m.end(), [](double d) { return d == 0.0; })) {
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
               "title 'deflection [µm]', \\\n"
               "     $trace using 1:3 axes x1y2 with lines lw 1 lc rgb '#ff7f0e' "
               "title 'command acceleration [m/s²]'");
  if (std::isfinite(static_um) && static_um > 0.0) {
    char band[64];
    std::snprintf(band, sizeof band, "static band ±%.4g µm", static_um);
    std::fprintf(gnuplot,
                 ", \\\n     %.17g axes x1y1 with lines dt 2 lc rgb '#444444' title %s, \\\n"
                 "     %.17g axes x1y1 with lines dt 2 lc rgb '#444444' notitle",
                 static_um, Quoted(band).c_str(), -static_um);
  }
  std::fprintf(gnuplot, "\nunset output\nquit\n");
}

}  // namespace

void WriteDeflectionPlot(const std::string& path_png, const RunResult& result,
                         const Scenario& scenario) {
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    WriteScript(gnuplot, output_path, result, scenario);
  });
}

}  // namespace shapebench::bench
