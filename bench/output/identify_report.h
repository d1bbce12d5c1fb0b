// What `shapebench identify FILE.uff` writes (bench/cli/identify_command.cc): modes from
// measured FRFs (bench/measured/frf_identification.h) as a table or JSON, and the
// stabilisation diagram as a PNG (docs/measured-data.md).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/measured/frf_identification.h"

namespace shapebench::bench {

// The header (file, records, band, orders), one row per mode and record (frequency,
// damping, stable orders, modal constant), the fit error.
void PrintIdentifyTable(std::ostream& out, const IdentifiedFrfs& frfs);

nlohmann::ordered_json IdentifyJson(const IdentifiedFrfs& frfs);

// Model order against frequency, each physical pole marked stable / stable in frequency /
// new, over the measured FRFs' magnitude and their synthesis (log scale, right axis), the
// identified modes as vertical lines. Throws std::runtime_error when gnuplot fails.
void WriteStabilisationPlot(const std::string& path_png, const IdentifiedFrfs& frfs, const std::string& title);

// The files `identify --out DIR` writes, in order: modes.json, stabilisation.png (its
// title names `file`). A new directory is filled under a temporary name and renamed when
// complete. Throws std::runtime_error naming DIR/FILE when gnuplot or the disk fails.
std::vector<std::string> WriteIdentifyOutputs(const std::string& out_dir, const IdentifiedFrfs& frfs,
                                              const std::string& file);

}  // namespace shapebench::bench
