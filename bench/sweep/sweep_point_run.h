// Running one point of a sweep: its scenario (loaded, or the last one's with the point's
// structure numbers set), a command shared with the points that differ only in the plant,
// and the outcome, a failure located at the value that caused it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/config/override.h"
#include "bench/scenario/metrics.h"
#include "bench/sweep/sweep_definition.h"

namespace shapebench::bench {

// What running one point gave.
struct PointOutcome {
  enum class Status { kOk, kBadInput, kSolverFailed, kFailed };
  std::uint64_t index = 0;
  Status status = Status::kOk;
  Metrics metrics;
  std::string error;  // "FILE:LINE:COL: key: message", "solver failed: FLAG: ..."
  bool ok() const { return status == Status::kOk; }
};

// Loads and runs one point; throws only std::bad_alloc (out of memory says nothing of the
// point: a row "error" would be kept by a resumed sweep, so the sweep stops instead). An error caused by one of the point's values
// is located at that value in the sweep file; one caused by a --set reads --set:N:1.
PointOutcome RunPoint(const Sweep& sweep, const std::vector<Override>& sets, std::uint64_t index);
// The same for the point MakePoint(sweep, point.index, sets) made.
PointOutcome RunPoint(const Sweep& sweep, const SweepPoint& point);

}  // namespace shapebench::bench
