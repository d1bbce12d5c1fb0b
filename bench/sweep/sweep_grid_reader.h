// The grid: of a sweep file (bench/sweep/sweep.h describes it): its keys' values (lists,
// ranges, distributions), zip groups, and the samples of a sampled sweep.
#pragma once

#include <cstdint>
#include <vector>

#include "bench/config/config_document.h"
#include "bench/config/node_reader.h"
#include "bench/sweep/sweep_definition.h"

namespace shapebench::bench {

// The axes of `grid:` in file order, the distribution keys merged into one axis of samples.
std::vector<SweepAxis> ReadGrid(const ConfigDocument& document, const NodeReader& grid);

// samples:, seed:, design: and the samples of every distribution key (bench/sweep/sampling.h).
void DrawSamples(Sweep* sweep, const NodeReader& top, const SweepLoadOptions& options);

// The grid's points (the product of the axes' sizes); more than 2^64 is an error at `grid`.
std::uint64_t CountPoints(const std::vector<SweepAxis>& axes, const NodeReader& grid);

}  // namespace shapebench::bench
