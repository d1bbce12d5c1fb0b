// The metrics:, plots: and checks: of a sweep file (bench/sweep/sweep.h describes them),
// and the plots drawn when plots: is left out.
#pragma once

#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "bench/sweep/sweep_definition.h"

namespace shapebench::bench {

std::vector<std::string> ReadMetrics(const NodeReader& node);

std::vector<SweepPlot> ReadPlots(const NodeReader& node, const std::vector<std::string>& metrics,
                                 const std::vector<SweepAxis>& axes);

// Default plots: each kept ratio metric (all kept metrics when metrics: is given) against
// the first key, one line per value of the second axis' first key when it is short.
std::vector<SweepPlot> DefaultPlots(const std::vector<std::string>& metrics, bool metrics_given,
                                    const std::vector<SweepAxis>& axes);

// A sampled sweep's default plots: the empirical CDF of each metric DefaultPlots would
// draw, one curve per value of the first other axis' first key when it is short.
std::vector<SweepPlot> DefaultCdfPlots(std::vector<SweepPlot> plots, const std::vector<SweepAxis>& axes,
                                       std::size_t sample_axis);

// A sweep's checks: min/max checks of every point (ReadChecks) and, in a sampled sweep,
// quantile and yield gates (bench/sweep/sampling.h, SampleGate).
void ReadSweepChecks(const NodeReader& checks, Sweep* sweep);

// Each cdf plot's limits: the bounds of the checks and gates on its metric.
void SetCdfLimits(Sweep* sweep);

}  // namespace shapebench::bench
