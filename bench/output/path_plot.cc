// WritePathPlot (bench/output/report.h): programmed and actual XY path, the deviation magnified.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/output/gnuplot.h"
#include "bench/output/report.h"
#include "bench/run/path_tallies.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {
namespace {

// The largest 1-2-5 step not above `value` (at least 1).
double RoundGain(double value) {
  if (!(value > 1.0) || !std::isfinite(value)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= value) return step * decade;
  }
  return decade;
}

// The programmed path, finely sampled, and the box around it.
struct SampledPath {
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3d lo;
  Eigen::Vector3d hi;
};

SampledPath SampleProgrammedPath(const controller::PathGeometry& path) {
  // The programmed path, finely sampled (arcs every degree or better). The short pi is
  // kept, not kPi: kPi could round a piece count, hence the plotted points, differently.
  std::vector<Eigen::Vector3d> programmed{path.start_m()};
  Eigen::Vector3d lo = path.start_m(), hi = path.start_m();
  for (const controller::PathElement& e : path.elements()) {
    const int pieces = e.is_arc() ? std::max(8, static_cast<int>(std::abs(e.sweep_rad) * 180.0 / 3.14159265358979)) : 1;
    for (int i = 1; i <= pieces; ++i) {
      programmed.push_back(e.PointAtFraction(static_cast<double>(i) / pieces));
      lo = lo.cwiseMin(programmed.back());
      hi = hi.cwiseMax(programmed.back());
    }
  }
  return SampledPath{std::move(programmed), lo, hi};
}

// Blocks whose feed the short-block clamp lowered, as pieces of the programmed path.
std::vector<std::vector<Eigen::Vector3d>> ClampedPieces(const controller::PathGeometry& path,
                                                        const RunResult& result) {
  std::vector<std::vector<Eigen::Vector3d>> clamped;
  for (const controller::PathElement& e : path.elements()) {
    const auto block = static_cast<std::size_t>(e.block);
    if (block >= result.command.block_clamped.size() || !result.command.block_clamped[block]) continue;
    const int pieces = e.is_arc() ? 16 : 1;
    clamped.emplace_back();
    for (int i = 0; i <= pieces; ++i) clamped.back().push_back(e.PointAtFraction(static_cast<double>(i) / pieces));
  }
  return clamped;
}

// What the plot draws: the programmed path, the actual one (each trace point's nearest
// point on the path plus the deviation times `gain`), the clamped blocks.
struct PathPlotData {
  SampledPath programmed;
  std::vector<std::vector<Eigen::Vector3d>> clamped;
  const std::vector<Eigen::Vector3d>* actual = nullptr;  // the trace's actual points
  std::vector<Eigen::Vector3d> nearest;
  double max_error = 0.0;
  double extent = 0.0;
  double gain = 1.0;
  std::size_t stride = 1;
};

void PathPlotScript(std::FILE* gnuplot, const std::string& output_path, const std::string& plot_title,
                    const PathPlotData& data) {
  const std::vector<Eigen::Vector3d>& programmed = data.programmed.points;
  const Eigen::Vector3d& lo = data.programmed.lo;
  const Eigen::Vector3d& hi = data.programmed.hi;
  const std::vector<Eigen::Vector3d>& nearest = data.nearest;
  const std::vector<std::vector<Eigen::Vector3d>>& clamped = data.clamped;
  const double gain = data.gain;
  const double max_error = data.max_error;
  const double extent = data.extent;
  const std::size_t stride = data.stride;
  std::fprintf(gnuplot, "set terminal pngcairo size 800,800 noenhanced font 'sans,10'\n");
  std::fprintf(gnuplot, "set encoding utf8\n");
  std::fprintf(gnuplot, "set output %s\n", GnuplotQuoted(output_path).c_str());
  char title[160];
  std::snprintf(title, sizeof title, "XY path, deviation from the programmed path x%g (max %.4g um)",
                gain, max_error * 1e6);
  // Two lines (a gnuplot string expression): the run's title is long on an 800 px page.
  std::fprintf(gnuplot, "set title %s.\"\\n\".%s\n", GnuplotQuoted(plot_title).c_str(),
               GnuplotQuoted(title).c_str());
  std::fprintf(gnuplot, "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\n");
  std::fprintf(gnuplot, "set size ratio -1\nset grid\n");
  // A square window around the path: a move along one axis has no extent in the other
  // (gnuplot would warn of an empty range); the magnified deviation (about 5% of the
  // extent) stays inside.
  const Eigen::Vector3d center_mm = 0.5e3 * (lo + hi);
  const double half_mm = 0.6e3 * extent;
  std::fprintf(gnuplot, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n", center_mm.x() - half_mm,
               center_mm.x() + half_mm, center_mm.y() - half_mm, center_mm.y() + half_mm);
  std::fprintf(gnuplot, "set bmargin 6\nset key at screen 0.5, screen 0.02 center bottom horizontal box\n");
  std::fprintf(gnuplot, "$programmed << EOD\n");
  for (const Eigen::Vector3d& p : programmed) std::fprintf(gnuplot, "%.10g %.10g\n", p.x() * 1e3, p.y() * 1e3);
  std::fprintf(gnuplot, "EOD\n$actual << EOD\n");
  for (std::size_t i = 0; i < nearest.size(); i += stride) {
    const Eigen::Vector3d shown = nearest[i] + gain * ((*data.actual)[i] - nearest[i]);
    std::fprintf(gnuplot, "%.10g %.10g\n", shown.x() * 1e3, shown.y() * 1e3);
  }
  std::fprintf(gnuplot, "EOD\n$clamped << EOD\n");
  for (const auto& piece : clamped) {
    for (const Eigen::Vector3d& p : piece) std::fprintf(gnuplot, "%.10g %.10g\n", p.x() * 1e3, p.y() * 1e3);
    std::fprintf(gnuplot, "\n");
  }
  std::fprintf(gnuplot, "EOD\n");
  char actual_title[96];
  std::snprintf(actual_title, sizeof actual_title, "actual tool path (deviation x%g)", gain);
  std::fprintf(gnuplot,
               "plot $programmed using 1:2 with lines lw 1 dt 2 lc rgb '#444444' title 'programmed', \\\n"
               "     $actual using 1:2 with lines lw 1.5 lc rgb '#1f77b4' title %s",
               GnuplotQuoted(actual_title).c_str());
  if (!clamped.empty()) {
    std::fprintf(gnuplot, ", \\\n     $clamped using 1:2 with lines lw 3 lc rgb '#d62728' "
                          "title 'short-block clamp (feed lowered)'");
  }
  std::fprintf(gnuplot, "\n");
  std::fprintf(gnuplot, "unset output\nquit\n");
}

}  // namespace

void WritePathPlot(const std::string& path_png, const RunResult& result, const Scenario& scenario,
                   const std::string& plot_title) {
  const controller::PathGeometry path(result.program);
  PathPlotData data;
  data.programmed = SampleProgrammedPath(path);
  data.clamped = ClampedPieces(path, result);
  const Trace& trace = result.trace;
  data.actual = &trace.actual_m;
  data.nearest.resize(trace.actual_m.size());
  // The run's windowed search (bench/run/path_tallies.h): sample i lies in period
  // (i - 1) / substeps + 1. Without the command (a shared one), the whole path's.
  const std::vector<double>& positions = result.command.path_position_m;
  ContourGauge gauge(path, positions, result.command.period_s, ContourLag(result.command, scenario.drive));
  const long substeps = std::max(result.substeps, 1);
  for (std::size_t i = 0; i < trace.actual_m.size(); ++i) {
    if (positions.empty()) {
      data.nearest[i] = path.NearestPoint(trace.actual_m[i]);
    } else {
      gauge.MoveTo(i == 0 ? 0 : (i - 1) / static_cast<std::size_t>(substeps) + 1);
      data.nearest[i] = gauge.NearestPoint(trace.actual_m[i]);
    }
    data.max_error = std::max(data.max_error, (trace.actual_m[i] - data.nearest[i]).head<2>().norm());
  }
  const Eigen::Vector3d& lo = data.programmed.lo;
  const Eigen::Vector3d& hi = data.programmed.hi;
  data.extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-6});
  // Deviation drawn at about 5% of the path's extent.
  data.gain = data.max_error > 0.0 ? RoundGain(0.05 * data.extent / data.max_error) : 1.0;
  // At most limits.max_trace_rows points, as in trace.csv.
  data.stride = TraceStride(data.nearest.size(), scenario.limits.max_trace_rows);
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    PathPlotScript(gnuplot, output_path, plot_title, data);
  });
}

}  // namespace shapebench::bench
