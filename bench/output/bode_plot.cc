// WriteBodePlots, BodePlotsSvg (bench/output/bode.h): gnuplot scripts with the data inline.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bench/output/bode.h"
#include "bench/output/gnuplot.h"
#include "common/format.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

const char* const kAxisColours[] = {"#1f77b4", "#2ca02c", "#9467bd"};

// One datablock: frequency, |values|, unwrapped phase in degrees.
void WriteCurve(std::FILE* gnuplot, const std::string& name, const std::vector<double>& frequency_hz,
                const std::vector<std::complex<double>>& values) {
  const std::vector<double> phase = UnwrappedPhaseDeg(values);
  std::fprintf(gnuplot, "$%s << EOD\n", name.c_str());
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::fprintf(gnuplot, "%.10g %.10g %.10g\n", frequency_hz[i], std::abs(values[i]), phase[i]);
  }
  if (values.empty()) std::fprintf(gnuplot, "NaN NaN NaN\n");
  std::fprintf(gnuplot, "EOD\n");
}

// Magnitude over phase: the model per axis (left, log) and V(f) (right, linear).
void BodeScript(std::FILE* gnuplot, const BodeData& data, const std::string& title) {
  for (const AxisResponse& axis : data.axes) {
    WriteCurve(gnuplot, std::string("axis") + model::AxisName(axis.axis), data.frequency_hz, axis.response);
  }
  std::fprintf(gnuplot, "$pattern << EOD\n");
  for (std::size_t i = 0; i < data.frequency_hz.size(); ++i) {
    std::fprintf(gnuplot, "%.10g %.10g %.10g\n", data.frequency_hz[i], data.pattern.residual[i],
                 data.pattern.phase_deg[i]);
  }
  std::fprintf(gnuplot, "EOD\n");
  std::fprintf(gnuplot, "set multiplot title %s\n", GnuplotQuoted(title).c_str());
  std::fprintf(gnuplot, "set logscale x\nset grid xtics ytics mxtics\nset key top left box opaque\n");
  std::fprintf(gnuplot, "set format y '%%g'\nset xrange [%.10g:%.10g]\n", data.frequency_hz.front(),
               data.frequency_hz.back());
  std::fprintf(gnuplot, "set size 1,0.55\nset origin 0,0.42\nset lmargin 12\nset rmargin 12\n");
  std::fprintf(gnuplot, "set ylabel '|H| deflection per acceleration [m/(m/s2)]'\nset logscale y\n");
  std::fprintf(gnuplot, "set y2label %s\nset y2tics\nset ytics nomirror\nset y2range [0:*]\nunset xlabel\n",
               GnuplotQuoted("pattern V(f), zeta " + FormatNumber(data.pattern.damping_ratio, 3)).c_str());
  std::string plot = "plot ";
  for (const AxisResponse& axis : data.axes) {
    const char* name = model::AxisName(axis.axis);
    plot += std::string("$axis") + name + " using 1:2 with lines lw 2 lc rgb '" + kAxisColours[axis.axis] +
            "' title '|H| axis " + name + "', ";
  }
  plot += "$pattern using 1:2 axes x1y2 with lines lw 2 dt 2 lc rgb '#d62728' title " +
          GnuplotQuoted("V(f) pattern " + data.pattern.method) + "\n";
  std::fprintf(gnuplot, "%s", plot.c_str());
  std::fprintf(gnuplot, "set size 1,0.42\nset origin 0,0\nunset logscale y\nunset y2tics\nunset y2label\n");
  std::fprintf(gnuplot, "set ytics mirror\nset ylabel 'phase [deg]'\nset xlabel 'frequency [Hz]'\n");
  plot = "plot ";
  for (const AxisResponse& axis : data.axes) {
    const char* name = model::AxisName(axis.axis);
    plot += std::string("$axis") + name + " using 1:3 with lines lw 2 lc rgb '" + kAxisColours[axis.axis] +
            "' title 'phase axis " + name + "', ";
  }
  plot += "$pattern using 1:3 with lines lw 2 dt 2 lc rgb '#d62728' title 'phase pattern'\n";
  std::fprintf(gnuplot, "%s", plot.c_str());
  std::fprintf(gnuplot, "unset multiplot\n");
}

// The measured FRF against the identified model's synthesis, magnitude over phase.
void FrfScript(std::FILE* gnuplot, const BodeData& data, const std::string& title) {
  std::string header = title;
  for (std::size_t k = 0; k < data.measured.size(); ++k) {
    const MeasuredResponse& m = data.measured[k];
    WriteCurve(gnuplot, "measured" + std::to_string(k), m.frequency_hz, m.measured);
    WriteCurve(gnuplot, "identified" + std::to_string(k), m.frequency_hz, m.identified);
    header += "; axis " + std::string(model::AxisName(m.axis)) + ": fit error " +
              FormatNumber(m.fit_error_percent, 3) + " %";
  }
  const std::string units = data.measured.front().units;
  std::fprintf(gnuplot, "set multiplot title %s\n", GnuplotQuoted(header).c_str());
  std::fprintf(gnuplot, "set logscale x\nset grid xtics ytics mxtics\nset key top left box opaque\n");
  std::fprintf(gnuplot, "set format y '%%g'\nset lmargin 12\nset rmargin 4\n");
  std::fprintf(gnuplot, "set size 1,0.5\nset origin 0,0.42\nset logscale y\nunset xlabel\n");
  std::fprintf(gnuplot, "set ylabel %s\n", GnuplotQuoted("|H| [" + (units.empty() ? "as in the file" : units) + "]").c_str());
  for (const int column : {2, 3}) {
    std::string plot = "plot ";
    for (std::size_t k = 0; k < data.measured.size(); ++k) {
      const std::string axis = model::AxisName(data.measured[k].axis);
      plot += "$measured" + std::to_string(k) + " using 1:" + std::to_string(column) +
              " with lines lw 1 lc rgb '#777777' title 'measured " + axis + "', $identified" + std::to_string(k) +
              " using 1:" + std::to_string(column) + " with lines lw 2 dt 2 lc rgb '#d62728' title 'identified " +
              axis + "', ";
    }
    plot.resize(plot.size() - 2);
    std::fprintf(gnuplot, "%s\n", plot.c_str());
    std::fprintf(gnuplot, "set size 1,0.42\nset origin 0,0\nunset logscale y\nset ylabel 'phase [deg]'\n"
                          "set xlabel 'frequency [Hz]'\n");
  }
  std::fprintf(gnuplot, "unset multiplot\n");
}

}  // namespace

std::vector<std::string> WriteBodePlots(const std::string& dir, const BodeData& data, const std::string& title) {
  std::vector<std::string> written;
  const auto png = [&](const std::string& name, auto script) {
    RunGnuplot((std::filesystem::path(dir) / name).string(), [&](std::FILE* gnuplot, const std::string& output) {
      std::fprintf(gnuplot, "set terminal pngcairo size 1000,720 noenhanced font 'sans,10'\n");
      std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output).c_str());
      script(gnuplot);
      std::fprintf(gnuplot, "unset output\nquit\n");
    });
    written.push_back(name);
  };
  png("bode.png", [&](std::FILE* gnuplot) { BodeScript(gnuplot, data, title); });
  if (!data.measured.empty()) png("frf.png", [&](std::FILE* gnuplot) { FrfScript(gnuplot, data, title); });
  return written;
}

std::vector<std::pair<std::string, std::string>> BodePlotsSvg(const BodeData& data, const std::string& title) {
  std::vector<std::pair<std::string, std::string>> plots;
  const auto svg = [&](const std::string& name, auto script) {
    plots.emplace_back(name, RunGnuplotSvg(name, [&](std::FILE* gnuplot, const std::string& output) {
                         std::fprintf(gnuplot, "set terminal svg size 900,640 noenhanced font 'sans,10'\n");
                         std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output).c_str());
                         script(gnuplot);
                         std::fprintf(gnuplot, "unset output\nquit\n");
                       }));
  };
  svg("bode.svg", [&](std::FILE* gnuplot) { BodeScript(gnuplot, data, title); });
  if (!data.measured.empty()) svg("frf.svg", [&](std::FILE* gnuplot) { FrfScript(gnuplot, data, title); });
  return plots;
}

}  // namespace shapebench::bench
