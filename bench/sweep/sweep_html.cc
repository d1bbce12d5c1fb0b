// ReadSweepHtmlData (bench/sweep/sweep_html.h).
#include "bench/sweep/sweep_html.h"

#include <fstream>
#include <stdexcept>

#include "common/csv.h"

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
  return data;
}

}  // namespace shapebench::bench
