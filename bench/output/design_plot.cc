// `design --out DIR`: the files (bench/output/design_report.h), V over each band plotted.
#include <cstdio>
#include <filesystem>
#include <string>
#include <typeinfo>
#include <vector>

#include "bench/output/design_report.h"
#include "bench/output/gnuplot.h"
#include "common/atomic_file.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

// V of the design over [0.8 lo, 1.2 hi] of each band at the band's middle damping, the
// band's edges and the tolerance marked.
void WriteDesignPlot(const std::string& path_png, const DesignReport& report) {
  static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  const std::vector<controller::Impulse> impulses = DesignImpulses(report.result);
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    std::fprintf(gnuplot, "set terminal pngcairo size 1000,560 noenhanced font 'sans,10'\n");
    std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output_path).c_str());
    const std::string title = "design: " + std::filesystem::path(report.file).filename().string() + ", " +
                              FormatNumber(report.result.duration_s) + " s; V over each band";
    std::fprintf(gnuplot, "set title %s\n", GnuplotQuoted(title).c_str());
    std::fprintf(gnuplot, "set xlabel 'frequency [Hz]'\nset ylabel 'residual vibration V [%%]'\nset grid\n");
    std::fprintf(gnuplot, "set key outside right top\nset yrange [0:*]\n");
    for (std::size_t b = 0; b < report.spec.bands.size(); ++b) {
      const controller::DesignBand& band = report.spec.bands[b];
      const double z = 0.5 * (band.damping_lo + band.damping_hi);
      std::fprintf(gnuplot, "$band%zu << EOD\n", b);
      const double lo = 0.8 * band.frequency_lo_hz;
      const double hi = 1.2 * band.frequency_hi_hz;
      for (int i = 0; i <= 800; ++i) {
        const double f = lo + (hi - lo) * i / 800.0;
        std::fprintf(gnuplot, "%.10g %.10g\n", f, 100.0 * controller::ResidualVibration(impulses, f, z));
      }
      std::fprintf(gnuplot, "EOD\n");
      for (double edge : {band.frequency_lo_hz, band.frequency_hi_hz}) {
        std::fprintf(gnuplot, "set arrow from %.10g, graph 0 to %.10g, graph 1 nohead dt 3 lc rgb '%s'\n", edge, edge,
                     kColours[b % 6]);
      }
    }
    std::fprintf(gnuplot, "plot %.10g with lines lw 1.5 dt 2 lc rgb '#000000' title %s", 100.0 * report.spec.tolerance,
                 GnuplotQuoted("tolerance " + FormatNumber(100.0 * report.spec.tolerance) + "%").c_str());
    for (std::size_t b = 0; b < report.spec.bands.size(); ++b) {
      const std::string name = "mode " + std::to_string(report.modes[b]) + " (" +
                               FormatNumber(report.mode_frequency_hz[b], 4) + " Hz), band dotted";
      std::fprintf(gnuplot, ", \\\n     $band%zu using 1:2 with lines lw 2 lc rgb '%s' title %s", b, kColours[b % 6],
                   GnuplotQuoted(name).c_str());
    }
    std::fprintf(gnuplot, "\nunset output\nquit\n");
  });
}

}  // namespace

std::vector<std::string> WriteDesignOutputs(const std::string& out_dir, const DesignReport& report) {
  StagedDirectory staged(out_dir);
  const std::filesystem::path dir(staged.path());
  std::vector<std::string> files{"design.json", "design.yaml"};
  try {
    WriteFileAtomically((dir / "design.json").string(),
                        [&](std::ostream& out) { out << DesignJson(report).dump(2) << "\n"; });
    WriteFileAtomically((dir / "design.yaml").string(),
                        [&](std::ostream& out) { out << DesignFragment(report, report.form); });
    if (report.table_too_long()) {
      WriteFileAtomically((dir / "design_impulses.yaml").string(),
                          [&](std::ostream& out) { out << DesignFragment(report, DesignForm::kImpulses); });
      files.push_back("design_impulses.yaml");
    }
    WriteDesignPlot((dir / "design.png").string(), report);
    files.push_back("design.png");
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  return files;
}

}  // namespace shapebench::bench
