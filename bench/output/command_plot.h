// command.png of `run --out`: the commanded acceleration and jerk over time, the scenario's
// shaped command against the same program unshaped (pattern method none), so the shaper's
// effect on the command is seen beside its effect on the deflection (docs/views.md).
#pragma once

#include <string>

#include "bench/run/run_result.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

// Acceleration (m/s^2, top) and jerk (m/s^3, bottom) per interpolation period: along the
// only axis that moves, else the magnitude of the vector. The unshaped command is left out
// (with a note in the title) when it cannot be planned, and when the pattern is none.
// Throws std::runtime_error when gnuplot fails.
void WriteCommandPlot(const std::string& path_png, const RunResult& result, const Scenario& scenario,
                      const std::string& title);

}  // namespace shapebench::bench
