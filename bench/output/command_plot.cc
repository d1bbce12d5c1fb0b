// WriteCommandPlot (bench/output/command_plot.h).
#include "bench/output/command_plot.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "bench/output/gnuplot.h"
#include "bench/output/report.h"
#include "bench/run/run_scenario.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

// The axis that moves alone in the command, or -1 when several (or none) do.
int OnlyMovingAxis(const controller::MultiAxisCommand& command) {
  int moving = -1;
  for (int axis = 0; axis < controller::kNumAxes; ++axis) {
    bool moves = false;
    for (std::size_t k = 0; k <= command.num_ticks() && !moves; ++k) moves = command.axes[axis].velocity_m_s[k] != 0.0;
    if (!moves) continue;
    if (moving >= 0) return -1;
    moving = axis;
  }
  return moving;
}

// The command's acceleration (and jerk) per period as a datablock: t, a, j.
void WriteCommandData(std::FILE* gnuplot, const char* name, const controller::MultiAxisCommand& command, int axis) {
  const std::size_t ticks = command.num_ticks();
  // At most ~50,000 points for gnuplot: every stride-th period (the metrics use all).
  const std::size_t stride = TraceStride(ticks + 1, 50'000);
  const double period = command.period_s;
  const auto accel = [&](std::size_t k) {
    if (k == 0 || k > ticks) return 0.0;
    const Eigen::Vector3d a = command.accel_m_s2(k);
    return axis >= 0 ? a(axis) : a.norm();
  };
  std::fprintf(gnuplot, "$%s << EOD\n", name);
  for (std::size_t k = 1; k <= ticks + 1; k += stride) {
    // Held over period k, (k - 1) T to k T: drawn as steps from (k - 1) T.
    std::fprintf(gnuplot, "%.10g %.10g %.10g\n", static_cast<double>(k - 1) * period, accel(k),
                 (accel(k) - accel(k - 1)) / period);
  }
  std::fprintf(gnuplot, "EOD\n");
}

}  // namespace

void WriteCommandPlot(const std::string& path_png, const RunResult& result, const Scenario& scenario,
                      const std::string& title) {
  const controller::MultiAxisCommand& shaped = result.command;
  const int axis = OnlyMovingAxis(shaped);
  std::optional<controller::MultiAxisCommand> unshaped;
  std::string note;
  if (scenario.controller.pattern.method != controller::kNoShaping) {
    Scenario plain = scenario;
    plain.controller.pattern.method = controller::kNoShaping;
    try {
      unshaped = GenerateScenarioCommand(plain, result.program);
    } catch (const ValidationError& error) {
      note = " (unshaped: cannot be planned: " + std::string(error.what()) + ")";
    }
  }
  const std::string label = axis >= 0 ? std::string("along ") + static_cast<char>('X' + axis) : "magnitude";
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output) {
    std::fprintf(gnuplot, "set terminal pngcairo size 1000,700 noenhanced font 'sans,10'\n");
    std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output).c_str());
    WriteCommandData(gnuplot, "shaped", shaped, axis);
    if (unshaped) WriteCommandData(gnuplot, "unshaped", *unshaped, axis);
    std::fprintf(gnuplot, "set multiplot title %s\n", GnuplotQuoted(title + note).c_str());
    std::fprintf(gnuplot, "set grid\nset key top right box opaque\nset lmargin 12\n");
    std::fprintf(gnuplot, "set size 1,0.5\nset origin 0,0.46\nunset xlabel\n");
    std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted("commanded acceleration, " + label + " [m/s2]").c_str());
    const std::string shaped_title = GnuplotQuoted("shaped (" + scenario.controller.pattern.method + ")");
    for (const int column : {2, 3}) {
      if (unshaped) {
        std::fprintf(gnuplot, "plot $unshaped using 1:%d with steps lw 1 lc rgb '#999999' title 'unshaped', "
                              "$shaped using 1:%d with steps lw 2 lc rgb '#1f77b4' title %s\n",
                     column, column, shaped_title.c_str());
      } else {
        std::fprintf(gnuplot, "plot $shaped using 1:%d with steps lw 2 lc rgb '#1f77b4' title %s\n", column,
                     shaped_title.c_str());
      }
      std::fprintf(gnuplot, "set size 1,0.46\nset origin 0,0\nset xlabel 'time [s]'\nset ylabel %s\n",
                   GnuplotQuoted("commanded jerk, " + label + " [m/s3]").c_str());
    }
    std::fprintf(gnuplot, "unset multiplot\nunset output\nquit\n");
  });
}

}  // namespace shapebench::bench
