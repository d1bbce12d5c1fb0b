// The two sides of `shapebench compare` (docs/compare.md): which files with which --set
// options, loaded and run; two scenarios compared metric by metric.
//
//   compare BASELINE [CANDIDATE] [--set K=V]... [--baseline-set K=V]... [--candidate-set K=V]...
//
// The candidate's file is CANDIDATE, or BASELINE when it is left out. --set applies to both
// sides (first), --baseline-set to the baseline only, --candidate-set to the candidate only
// (after --set: a later option wins on the same key). Both files are scenarios or both are
// sweeps (IsSweepFile).
#pragma once

#include <string>
#include <vector>

#include "bench/compare/compare.h"
#include "bench/config/config_error.h"
#include "bench/config/override.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

struct CompareRequest {
  std::string baseline_file;
  std::string candidate_file;               // empty: baseline_file
  std::vector<std::string> sets;            // --set: both sides
  std::vector<std::string> baseline_sets;   // --baseline-set
  std::vector<std::string> candidate_sets;  // --candidate-set
};

// One side: its file and the overrides applied to it, in order, each with the option that
// gave it ("--set", "--candidate-set", ...) and its 1-based position among that option's.
struct CompareSide {
  std::string file;
  std::string name;  // the scenario's or the sweep's name, once loaded
  std::vector<Override> overrides;
  std::vector<std::pair<std::string, int>> origins;  // per override: (option, position)

  // The arguments of `run` (or `sweep`) that give this side: "demo.yaml --set k=v ...".
  std::string Label() const;
  // A ConfigError located at "--set:N:1" (N counting this side's overrides) located at the
  // option that gave the override instead: "--candidate-set:1:1". Others unchanged.
  ConfigError Relabeled(const ConfigError& error) const;
  // The same for a message that starts with "--set:N:1: " (a sweep point's error).
  std::string Relabeled(const std::string& message) const;
};

// The baseline's and the candidate's sides of a request. Throws ConfigError for a
// malformed --set option (located at its option) and std::runtime_error (exit 2) when
// nothing differs (no CANDIDATE, no --baseline-set, no --candidate-set).
CompareSide BaselineSide(const CompareRequest& request);
CompareSide CandidateSide(const CompareRequest& request);

// Two scenarios, loaded (both before either runs: bad input fails fast) and run with
// their traces.
struct ScenarioComparison {
  CompareSide baseline;
  CompareSide candidate;
  Scenario baseline_scenario;
  Scenario candidate_scenario;
  RunResult baseline_run;
  RunResult candidate_run;
  std::vector<MetricChange> changes;  // MetricTable() order
  std::vector<Gate> gates;
  // Whether every gate passes (GatePasses); true without gates.
  bool passed() const;
};

// Loads and runs both sides. Errors: ConfigError (located, exit 2), model::SolverError
// (exit 3).
ScenarioComparison CompareScenarios(const CompareRequest& request, const std::vector<Gate>& gates);

}  // namespace shapebench::bench
