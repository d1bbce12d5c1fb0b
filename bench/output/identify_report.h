// `shapebench identify FILE.uff`: modes from measured FRFs (bench/measured/frf_identification.h)
// as a table or JSON, and the stabilisation diagram as a PNG (docs/measured-data.md).
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/measured/frf_identification.h"

namespace shapebench::bench {

struct IdentifyArgs {
  std::string file;
  std::string axis;   // "", "x", "y", "z"
  std::string band;   // "", "MIN:MAX" in Hz
  int max_order = 30;
  bool json = false;
  std::string out_dir;  // "": identify_out/STEM
};

// The header (file, records, band, orders), one row per mode and record (frequency,
// damping, stable orders, modal constant), the fit error.
void PrintIdentifyTable(std::ostream& out, const IdentifiedFrfs& frfs);

nlohmann::ordered_json IdentifyJson(const IdentifiedFrfs& frfs);

// Model order against frequency, each physical pole marked stable / stable in frequency /
// new, over the measured FRFs' magnitude and their synthesis (log scale, right axis), the
// identified modes as vertical lines. Throws std::runtime_error when gnuplot fails.
void WriteStabilisationPlot(const std::string& path_png, const IdentifiedFrfs& frfs, const std::string& title);

// The command: the table (or JSON) on `out`, then stabilisation.png and modes.json in the
// output directory and a "wrote" line each (on `wrote`). Throws ConfigError (exit 2) for
// bad input.
int RunIdentify(const IdentifyArgs& args, std::ostream& out, std::ostream& wrote);

}  // namespace shapebench::bench
