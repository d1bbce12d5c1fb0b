// WriteStabilisationPlot (bench/output/identify_report.h).
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/output/gnuplot.h"
#include "bench/output/identify_report.h"

namespace shapebench::bench {
namespace {

// The poles of one stability as a datablock: frequency, order.
void WritePoles(std::FILE* gnuplot, const char* name, const model::ModalIdentification& id,
                model::PoleStability stability) {
  std::fprintf(gnuplot, "$%s << EOD\n", name);
  bool any = false;
  for (const model::DiagramPole& pole : id.diagram) {
    if (pole.stability != stability) continue;
    std::fprintf(gnuplot, "%.10g %d\n", pole.frequency_hz, pole.order);
    any = true;
  }
  if (!any) std::fprintf(gnuplot, "NaN NaN\n");  // an empty block would make gnuplot fail
  std::fprintf(gnuplot, "EOD\n");
}

// Per record: frequency, |measured|, |synthesised| over the band's lines.
void WriteMagnitudes(std::FILE* gnuplot, const IdentifiedFrfs& frfs) {
  const model::ModalIdentification& id = frfs.identification;
  for (std::size_t k = 0; k < frfs.frfs.size(); ++k) {
    std::fprintf(gnuplot, "$frf%zu << EOD\n", k);
    std::size_t line = 0;
    for (std::size_t i = 0; i < frfs.frequency_hz.size() && line < id.frequency_hz.size(); ++i) {
      if (frfs.frequency_hz[i] != id.frequency_hz[line]) continue;
      std::fprintf(gnuplot, "%.10g %.10g %.10g\n", frfs.frequency_hz[i], std::abs(frfs.frfs[k][i]),
                   std::abs(id.fits[k].synthesized[line]));
      ++line;
    }
    std::fprintf(gnuplot, "EOD\n");
  }
}

// The identified modes: a dashed line each, numbered at its top; their frequencies and
// damping ratios in one line under the title (labels at the lines would overlap for
// close modes).
void WriteModeMarks(std::FILE* gnuplot, const model::ModalIdentification& id) {
  std::string list;
  for (std::size_t r = 0; r < id.modes.size(); ++r) {
    const model::IdentifiedMode& mode = id.modes[r];
    std::fprintf(gnuplot, "set arrow from %.10g, graph 0 to %.10g, graph 1 nohead dt 2 lw 1 lc rgb '#2ca02c' back\n",
                 mode.frequency_hz, mode.frequency_hz);
    std::fprintf(gnuplot, "set label '%zu' at %.10g, graph 1.02 center font 'sans,9' tc rgb '#2ca02c'\n", r + 1,
                 mode.frequency_hz);
    char text[96];
    std::snprintf(text, sizeof text, "%s%zu: %.4g Hz %.3g %%", r == 0 ? "" : "    ", r + 1, mode.frequency_hz,
                  100.0 * mode.damping_ratio);
    list += text;
  }
  // Clusters the data did not show (identify's JSON "rejected" says why): grey, crossed.
  for (const model::RejectedMode& mode : id.rejected) {
    std::fprintf(gnuplot, "set arrow from %.10g, graph 0 to %.10g, graph 1 nohead dt 3 lw 1 lc rgb '#aaaaaa' back\n",
                 mode.frequency_hz, mode.frequency_hz);
    std::fprintf(gnuplot, "set label 'x' at %.10g, graph 1.02 center font 'sans,9' tc rgb '#aaaaaa'\n",
                 mode.frequency_hz);
  }
  if (list.empty()) list = "no mode identified (no cluster of stable physical poles)";
  if (!id.rejected.empty()) {
    list += "    (x: " + std::to_string(id.rejected.size()) + " dropped, not shown by the data)";
  }
  std::fprintf(gnuplot, "set label %s at screen 0.5, screen 0.93 center font 'sans,9' tc rgb '#2ca02c'\n",
               GnuplotQuoted(list).c_str());
}

}  // namespace

void WriteStabilisationPlot(const std::string& path_png, const IdentifiedFrfs& frfs, const std::string& title) {
  const model::ModalIdentification& id = frfs.identification;
  const std::string units = frfs.file.records[frfs.records.front()].units;
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    std::fprintf(gnuplot, "set terminal pngcairo size 1100,640 noenhanced font 'sans,10'\n");
    std::fprintf(gnuplot, "set encoding utf8\nset output %s\n", GnuplotQuoted(output_path).c_str());
    std::fprintf(gnuplot, "set label %s at screen 0.5, screen 0.975 center font 'sans,11'\n",
                 GnuplotQuoted(title).c_str());
    std::fprintf(gnuplot, "set tmargin 7\nset bmargin 6\nset rmargin 12\n");
    std::fprintf(gnuplot, "set xlabel 'frequency [Hz]'\nset ylabel 'model order [pole pairs]'\n");
    // The right axis: |H| in the file's unit, ticks as 1e-08 rather than 0.00000001 (which
    // pushed the label off the page).
    std::fprintf(gnuplot, "set y2label %s\n",
                 GnuplotQuoted("|H| [" + (units.empty() ? std::string("no unit in the file") : units) + "], log scale")
                     .c_str());
    std::fprintf(gnuplot, "set format y2 '%%g'\n");
    std::fprintf(gnuplot, "set xrange [%.10g:%.10g]\nset yrange [0:%d]\n", id.frequency_hz.front(),
                 id.frequency_hz.back(), id.max_order + 1);
    std::fprintf(gnuplot, "set logscale y2\nset y2tics\nset ytics nomirror\nset grid xtics ytics\n");
    std::fprintf(gnuplot, "set key at screen 0.5, screen 0.01 center bottom horizontal box\n");
    WritePoles(gnuplot, "stable", id, model::PoleStability::kStable);
    WritePoles(gnuplot, "frequency", id, model::PoleStability::kFrequency);
    WritePoles(gnuplot, "new", id, model::PoleStability::kNew);
    WriteMagnitudes(gnuplot, frfs);
    WriteModeMarks(gnuplot, id);
    std::fprintf(gnuplot, "plot ");
    for (std::size_t k = 0; k < frfs.frfs.size(); ++k) {
      std::fprintf(gnuplot,
                   "$frf%zu using 1:2 axes x1y2 with lines lw 1 lc rgb '#999999' title %s, \\\n"
                   "  $frf%zu using 1:3 axes x1y2 with lines lw 1 dt 2 lc rgb '#d62728' title %s, \\\n  ",
                   k, GnuplotQuoted(k == 0 ? "|H| measured" : "").c_str(), k,
                   GnuplotQuoted(k == 0 ? "|H| synthesised" : "").c_str());
    }
    std::fprintf(gnuplot,
                 "$new using 1:2 with points pt 2 ps 0.6 lc rgb '#bbbbbb' title 'new pole', \\\n"
                 "  $frequency using 1:2 with points pt 8 ps 0.8 lc rgb '#ff7f0e' title 'stable frequency', \\\n"
                 "  $stable using 1:2 with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'stable frequency and damping'\n");
    std::fprintf(gnuplot, "unset output\nquit\n");
  });
}

}  // namespace shapebench::bench
