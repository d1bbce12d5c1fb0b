// ReadSweepHtmlData (bench/sweep/sweep_html.h).
#include "bench/sweep/sweep_html.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/csv.h"
#include "bench/sweep/robust_band.h"
#include "bench/sweep/sweep_plot.h"

namespace shapebench::bench {

SweepHtmlData ReadSweepHtmlData(const Sweep& sweep, const std::vector<Override>& sets,
                                const std::string& results_csv) {
  SweepHtmlData data;
  data.name = sweep.name;
  data.file = sweep.file;
  data.keys = sweep.Keys();
  std::ifstream in(results_csv, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + results_csv + " for the report");
  CsvReader reader(in);
  std::vector<std::string> fields;
  if (reader.Next(&fields)) data.columns = fields;
  while (reader.Next(&fields)) data.rows.push_back(fields);
  data.base_yaml = EffectiveScenarioYaml(sweep.base, sets);
  // The sweep's own plots and robust bands, drawn as its PNGs are.
  const SweepLayout layout = SweepLayout::Of(sweep);
  for (const SweepPlot& plot : layout.plots) {
    data.plots.emplace_back(SweepPlotFileName(plot, layout.keys), SweepPlotSvg(layout, plot, results_csv));
  }
  if (!layout.bands.empty()) {
    std::istringstream bands(BandsCsv(SweepBands(layout, results_csv)));
    CsvReader bands_reader(bands);
    if (bands_reader.Next(&fields)) data.bands.header = fields;
    while (bands_reader.Next(&fields)) data.bands.rows.push_back(fields);
  }
  return data;
}

}  // namespace shapebench::bench
