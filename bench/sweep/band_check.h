// Band checks: a check with `band: {key: KEY, from: A, to: B}` bounds the worst value of
// its metric while KEY spans [A, B] (docs/scenario-reference.md, checks), e.g.
//   checks:
//     residual_ratio: {max: 0.05, band: {key: "machine.modes[0].frequency_hz", from: 24, to: 26}}
// The worst is the maximum for a max bound, the minimum for a min bound; with both, each
// is searched and the one further on the wrong side of its bound (Violation) is reported.
// The search (common/interval_search.h): 64 evenly spaced points, then golden-section on
// the brackets around the scan's 3 most extreme local extrema until the bracket is 1e-4 of
// B - A wide. A point whose metric is undefined (NaN) fails the check there.
// A key that is a number of the machine's structure (structure_numbers.h) is set on the
// scenario loaded once and the runs share one command (the controller does not read it):
// a point costs one run of the plant. Any other key reloads the scenario per point.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bench/config/config_error.h"
#include "bench/config/override.h"
#include "bench/scenario/checks.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario.h"
#include "common/interval_search.h"

namespace shapebench::bench {

// The metric of `scenario` (loaded from scenario.source_file with `overrides`) with the
// band's key set to x: what the band search evaluates. An error caused by the band's value
// (a key the scenario does not have, a value it refuses) is a ConfigError located at the
// band's key; other errors (SolverError) pass through. `scenario` must outlive it.
class BandPointRunner {
 public:
  BandPointRunner(const Scenario& scenario, const std::vector<Override>& overrides,
                  const Check& check);
  double operator()(double x);
  int runs() const { return runs_; }
  // Whether the run at x had a static displacement of 0 (its ratios n/a: ZeroStaticReason).
  bool ZeroStaticAt(double x) const;
  bool fast() const { return fast_; }  // the structure-number path
  // The scenario loaded from its sources with the key set to `text`.
  Scenario LoadAt(const std::string& text) const;

 private:
  ConfigError AtBandKey(const ConfigError& error, const std::string& text) const;

  const Scenario& scenario_;
  std::vector<Override> overrides_;
  Check check_;
  bool fast_ = false;
  std::shared_ptr<const controller::MultiAxisCommand> command_;
  int runs_ = 0;
  std::vector<double> zero_static_at_;
};

// The number text a band point is set with: %.17g (reads back as exactly x).
std::string BandValueText(double x);

// Loads the scenario with each band's key at `from` and at `to`: a key the scenario does not
// take, or a value it refuses, is a ConfigError at the band's key. `check` calls it
// before anything runs.
void ValidateBandChecks(const Scenario& scenario, const std::vector<Override>& overrides);

// The band check's result: its worst value over the band and where.
CheckResult EvaluateBandCheck(const Scenario& scenario, const std::vector<Override>& overrides,
                              const Check& check, const ExtremumSearch& search = {});

// EvaluateChecks, with each band check's result replaced by EvaluateBandCheck's.
std::vector<CheckResult> EvaluateScenarioChecks(const Scenario& scenario,
                                                const std::vector<Override>& overrides,
                                                const Metrics& metrics);

}  // namespace shapebench::bench
