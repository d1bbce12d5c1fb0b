// Two runs side by side, metric by metric (`shapebench compare`, docs/compare.md): the
// change of every metric of MetricTable() (bench/scenario/metrics.h), which run is better by
// the table's better-direction, and gates that fail when the candidate is worse than the
// baseline by more than a relative amount.
//
// Relative amounts are taken against max(|baseline|, floor), the floor one per metric
// unit (RelativeFloor): a baseline of 0 (no overshoot, no Z deflection) or of numerical
// noise (a perfect shaper's residual_ratio of 1e-14) would otherwise turn any candidate
// into an infinite or meaningless percentage.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bench/scenario/metrics.h"

namespace shapebench::bench {

// Which run a metric favours.
enum class Verdict { kSame, kBaseline, kCandidate, kNotComparable };

// "same", "baseline", "candidate", "n/a".
std::string_view VerdictName(Verdict verdict);

// The smallest denominator of a relative change, by MetricInfo::unit:
//   "m"     1e-9 (1 nm: about three orders below the um deflections of the shipped
//            machines, four above the solver's noise on them at rtol 1e-8)
//   "s"     1e-6 (1 us: a thousandth of the 1 ms controller period)
//   "1"     1e-6 (ratios are of order 1; a perfect shaper leaves ~1e-14 of noise)
//   "count" 1    (one block)
//   "bool"  1    (false -> true is a change of 100%)
double RelativeFloor(std::string_view unit);

// One metric of the two runs.
struct MetricChange {
  const MetricInfo* info = nullptr;
  double baseline = NAN;
  double candidate = NAN;
  double change = NAN;           // candidate - baseline
  double relative_change = NAN;  // change / max(|baseline|, RelativeFloor(unit)), signed
  // How much worse the candidate is, relative as above; negative when it is better.
  // Lower-is-better compares magnitudes (|candidate| - |baseline|: radial_error_m is signed,
  // its magnitude is what counts; every other such metric is >= 0), higher-is-better
  // baseline - candidate. NaN when either run leaves the metric undefined.
  double worsening = NAN;
  Verdict better = Verdict::kNotComparable;
};

// The change of one metric between two values (NaN: not defined for that run).
MetricChange CompareMetric(const MetricInfo& info, double baseline, double candidate);

// Every metric, in MetricTable() order.
std::vector<MetricChange> CompareMetrics(const Metrics& baseline, const Metrics& candidate);

// --gate METRIC=REL: fails when the candidate's worsening exceeds max_worsening (a
// fraction: 0.05 is 5%; 0 fails on any worsening).
struct Gate {
  const MetricInfo* info = nullptr;
  double max_worsening = 0.0;
  std::string text;  // as given
};

// Parses "METRIC=REL" (REL a finite number >= 0). An unknown metric name throws
// std::runtime_error (exit 2) naming the closest names and listing the allowed ones.
Gate ParseGate(const std::string& text);
std::vector<Gate> ParseGates(const std::vector<std::string>& texts);

// The names of `names` closest to `name` by edit distance (at most a third of its length
// away, and always one within two edits), best first; empty when none is close.
std::vector<std::string> ClosestNames(const std::string& name, const std::vector<std::string>& names);

// A gate passes when both runs define the metric and worsening <= max_worsening. A metric
// undefined (n/a) on either side fails it, as a check fails on n/a (bench/scenario/checks.h):
// a gate that cannot be evaluated does not pass.
bool GatePasses(const Gate& gate, const MetricChange& change);

// "worse by 12.3% (gate 5%)", "better by 99.6% (gate 0%)", "candidate n/a (gate 5%)".
std::string GateDetail(const Gate& gate, const MetricChange& change);

// A relative amount as a signed percentage with four significant digits: "+12.35%",
// "-99.56%", "0%"; "n/a" for NaN.
std::string FormatPercent(double fraction);

// The change a table shows: "same" when |change| is within the metric's noise floor
// (NoiseFloor: rounding, not a change), else the signed change in engineering units
// ("+87.0475 um"); n/a when undefined.
std::string ChangeText(const MetricChange& change);
// The relative change a table shows: "same" within the noise floor, else FormatPercent.
std::string RelativeText(const MetricChange& change);
// The favours column of a table: "same" within the noise floor (the JSON keeps the exact
// verdict), else VerdictName.
std::string FavoursText(const MetricChange& change);
// The largest |candidate - baseline| of `info` that is numerical noise, for these
// values: the unit's absolute floor (1 pm, 1 ns, 1e-9 Hz or of a ratio, 1e-12 m/s^2; a
// count or bool none) or 1e-9 of the larger magnitude, whichever is larger.
double NoiseFloor(const MetricInfo& info, double baseline, double candidate);

}  // namespace shapebench::bench
