// What `compare` prints and writes (docs/compare.md): the side-by-side table, the same as
// JSON, and with --out DIR the files compare.txt, compare.json and deflection.png (two
// scenarios) or points.csv (two sweeps), in a directory that appears complete or not at all.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "bench/compare/compare_runs.h"
#include "bench/compare/compare_sweep.h"

namespace shapebench::bench {

// The sides, then one line per metric: metric, unit, better (lower|higher), baseline,
// candidate, change, relative (a signed %), favours (candidate|baseline|same|n/a); then a
// PASS or FAIL line per gate.
void PrintComparison(std::ostream& out, const ScenarioComparison& comparison);

// {"kind": "scenarios", "baseline": {file, name, overrides}, "candidate": {...},
//  "metrics": [{name, unit, better, baseline, candidate, change, relative_change, favours}],
//  "gates": [{gate, metric, max_worsening, worsening, passed, detail}], "passed": bool}
// Numbers as numbers (relative ones as fractions), n/a as null, bool metrics as bools.
nlohmann::ordered_json ComparisonJson(const ScenarioComparison& comparison);

// Per metric: how many points favour the candidate, the baseline, neither, or are n/a,
// and the worst point (baseline, candidate, change, relative, its point); then a PASS or
// FAIL line per gate with its failing points and worst.
void PrintComparison(std::ostream& out, const SweepComparison& comparison);

// {"kind": "sweeps", "baseline", "candidate", "points", "failed_points",
//  "metrics": [{name, unit, better, candidate_better, baseline_better, same, not_comparable,
//               worst: {point, label, baseline, candidate, change, relative_change, favours}}],
//  "gates": [{gate, metric, max_worsening, failed_points, not_comparable, passed, worst}],
//  "passed": bool}
nlohmann::ordered_json ComparisonJson(const SweepComparison& comparison);

// compare --out DIR for two scenarios: compare.txt, compare.json and deflection.png (the
// two deflection traces overlaid).
void WriteComparisonOutputs(const std::string& out_dir, const ScenarioComparison& comparison);

// CompareSweeps with --out DIR: points.csv (a row per point and metric: point, the swept
// keys, metric, baseline, candidate, change, relative_change, favours, error) written as
// the points are compared, then compare.txt and compare.json.
SweepComparison CompareSweepsWritingTo(const std::string& out_dir, const ComparedSweeps& sweeps,
                                       const std::vector<Gate>& gates, int jobs, std::ostream& err);

}  // namespace shapebench::bench
