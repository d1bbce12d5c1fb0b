// Searches of a scalar function of one number over an interval, shared by the band checks
// of `check` (bench/sweep/band_check.h: the worst value of a metric over a range of one
// key) and `sensitivity` (bench/sensitivity/sensitivity.h: the edges of the band where a
// shaper's residual stays below a level). The function is costly (a whole run) and may be
// neither smooth nor unimodal: a dense scan finds where to look, a local refinement
// (golden-section on the bracket around a scan point, bisection for a crossing) then
// narrows that place down.
#pragma once

#include <functional>

namespace shapebench {

enum class Extreme { kMaximum, kMinimum };

struct IntervalPoint {
  double x = 0.0;
  double value = 0.0;  // NaN: f was not defined at x
};

struct ExtremumSearch {
  // Evenly spaced scan points, both ends included (>= 3). 64 resolves a feature a
  // sixty-third of the interval wide; narrower ones may be missed.
  int scan_points = 64;
  // The best local extrema of the scan refined (near ties between two humps are each
  // refined, so the scan's spacing does not pick the wrong one).
  int candidates = 3;
  // Golden-section stops when its bracket is this fraction of (to - from) wide.
  double tolerance = 1e-4;
};

struct ExtremumResult {
  IntervalPoint worst;   // the most extreme value found, or the first x where f is NaN
  int evaluations = 0;
};

// The maximum (or minimum) of f on [from, to] (from < to): the scan, then golden-section
// on [x[k-1], x[k+1]] around each candidate scan point k. The result is the best point
// evaluated, so it is never worse than the scan. A NaN value ends the search: `worst` is
// then that point.
ExtremumResult FindExtremum(const std::function<double(double)>& f, double from, double to,
                            Extreme extreme, const ExtremumSearch& search = {});

// Golden-section search for an extremum of f on [low, high] until the bracket is at most
// `width` wide; the best point evaluated (the ends are not evaluated).
IntervalPoint GoldenSection(const std::function<double(double)>& f, double low, double high,
                            Extreme extreme, double width, int* evaluations = nullptr);

// The crossing of a predicate between `inside` (where it holds) and `outside` (where it
// does not), bisected until the two are `width` apart (at most 200 halvings); the
// midpoint of the last pair.
double BisectEdge(const std::function<bool(double)>& holds, double inside, double outside,
                  double width);

}  // namespace shapebench
