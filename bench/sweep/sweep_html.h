// `sweep --report FILE.html`: a finished sweep's results.csv as the report's plain data.
#pragma once

#include <string>
#include <vector>

#include "bench/output/html_report.h"
#include "bench/sweep/sweep.h"

namespace shapebench::bench {

// The sweep's name, keys and results.csv (at `results_csv`), and its base scenario with
// the --set overrides applied. Throws std::runtime_error when results.csv cannot be read.
SweepHtmlData ReadSweepHtmlData(const Sweep& sweep, const std::vector<Override>& sets,
                                const std::string& results_csv);

}  // namespace shapebench::bench
