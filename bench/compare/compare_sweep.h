// `compare` on two sweeps (docs/compare.md): the same grid run twice, the baseline's point
// p against the candidate's point p, every metric; per metric the point where the
// candidate fares worst; a gate fails when any point fails it.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "bench/compare/compare.h"
#include "bench/compare/compare_runs.h"
#include "bench/sweep/sweep.h"

namespace shapebench::bench {

// Throws std::runtime_error (exit 2) naming the first difference unless both sweeps have
// the same axes in the same order, the same keys on each and the same values (as
// results.csv shows them): then point p is the same point in both.
void CheckSameGrid(const Sweep& baseline, const Sweep& candidate);

// A point and one metric's change there.
struct PointChange {
  std::uint64_t point = 0;
  std::string label;  // SweepPoint::Label()
  MetricChange change;
};

// One metric over every point that ran on both sides.
struct SweepMetricSummary {
  const MetricInfo* info = nullptr;
  std::uint64_t candidate_better = 0;
  std::uint64_t baseline_better = 0;
  std::uint64_t same = 0;
  std::uint64_t not_comparable = 0;  // n/a on either side
  bool has_worst = false;
  PointChange worst;  // the largest worsening (the least improvement when all improve)
};

// One gate over every point that ran on both sides: the points where it fails (those
// where the metric is n/a on a side included) and the worst.
struct SweepGateSummary {
  Gate gate;
  std::uint64_t failed = 0;
  std::uint64_t not_comparable = 0;  // of `failed`: n/a on a side
  bool has_worst = false;
  PointChange worst;  // the largest worsening among the comparable points
  bool passed() const { return failed == 0; }
};

struct SweepComparison {
  CompareSide baseline;
  CompareSide candidate;
  std::uint64_t points = 0;
  std::uint64_t failed_points = 0;  // did not run on a side (reported on `err`)
  // 0, or the most severe of the failed points: 2 bad input, 3 solver failure (then 2 wins).
  int point_exit_code = 0;
  std::vector<SweepMetricSummary> metrics;  // MetricTable() order
  std::vector<SweepGateSummary> gates;
  bool passed() const;  // every gate
};

// Both sweeps of a request, loaded (each side's --set options apply to its every point) and
// their grids checked (CheckSameGrid): bad input fails before anything runs. Throws
// ConfigError (located at the sweep file or the option) or std::runtime_error (exit 2).
struct ComparedSweeps {
  CompareSide baseline;
  CompareSide candidate;
  Sweep baseline_sweep;
  Sweep candidate_sweep;
};
ComparedSweeps LoadComparedSweeps(const CompareRequest& request);

// Runs both sweeps point by point on `jobs` threads. `points_csv`, when not null, receives
// a row per point and metric (docs/compare.md), in point order. A point that fails on
// either side is a line on `err` and counts in failed_points. Throws InterruptedError when
// a signal stops it (the points in progress finish first).
SweepComparison CompareSweeps(const ComparedSweeps& sweeps, const std::vector<Gate>& gates, int jobs,
                              std::ostream* points_csv, std::ostream& err);

}  // namespace shapebench::bench
