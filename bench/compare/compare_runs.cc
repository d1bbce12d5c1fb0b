#include "bench/compare/compare_runs.h"

#include <stdexcept>
#include <utility>

#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench {
namespace {

// Appends the overrides of one option (ParseOverride locates a malformed one at
// "--set:N:1", N the position among all of this side's overrides; relabeled below).
void AddOverrides(CompareSide* side, const std::string& option, const std::vector<std::string>& texts) {
  for (std::size_t i = 0; i < texts.size(); ++i) {
    side->origins.emplace_back(option, static_cast<int>(i) + 1);
    try {
      side->overrides.push_back(ParseOverride(texts[i], static_cast<int>(side->overrides.size()) + 1));
    } catch (const ConfigError& error) {
      throw side->Relabeled(error);
    }
  }
}

// RunScenario's ValidationErrors are about the scenario: located in its sources.
RunResult RunSide(const CompareSide& side, const Scenario& scenario) {
  try {
    return RunScenario(scenario);
  } catch (const ValidationError& error) {
    throw side.Relabeled(LocateValidationError(scenario.source_file, side.overrides, error));
  }
}

Scenario LoadScenarioSide(CompareSide* side) {
  try {
    Scenario scenario = LoadScenario(side->file, side->overrides);
    side->name = scenario.name;
    return scenario;
  } catch (const ConfigError& error) {
    throw side->Relabeled(error);
  }
}

}  // namespace

std::string CompareSide::Label() const {
  std::string label = file;
  for (const Override& override : overrides)
    label += " --set " + override.key_path + "=" + override.value_yaml;
  return label;
}

ConfigError CompareSide::Relabeled(const ConfigError& error) const {
  if (error.file() != kOverrideSource || error.line() < 1 ||
      error.line() > static_cast<int>(origins.size())) {
    return error;
  }
  const auto& [option, position] = origins[static_cast<std::size_t>(error.line() - 1)];
  return ConfigError(option, position, error.column(), error.key_path(), error.message());
}

std::string CompareSide::Relabeled(const std::string& message) const {
  const std::string prefix = std::string(kOverrideSource) + ":";
  if (message.rfind(prefix, 0) != 0) return message;
  const std::size_t colon = message.find(':', prefix.size());
  if (colon == std::string::npos || colon == prefix.size()) return message;
  const std::string digits = message.substr(prefix.size(), colon - prefix.size());
  if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return message;
  const int line = std::stoi(digits);
  if (line < 1 || line > static_cast<int>(origins.size())) return message;
  const auto& [option, position] = origins[static_cast<std::size_t>(line - 1)];
  return option + ":" + std::to_string(position) + message.substr(colon);
}

CompareSide BaselineSide(const CompareRequest& request) {
  CompareSide side;
  side.file = request.baseline_file;
  AddOverrides(&side, "--set", request.sets);
  AddOverrides(&side, "--baseline-set", request.baseline_sets);
  return side;
}

CompareSide CandidateSide(const CompareRequest& request) {
  if (request.candidate_file.empty() && request.baseline_sets.empty() && request.candidate_sets.empty()) {
    throw std::runtime_error(
        "compare: nothing to compare: give a CANDIDATE file or --candidate-set KEY=VALUE "
        "(e.g. compare configs/demo.yaml --candidate-set controller.pattern.method=zvd)");
  }
  CompareSide side;
  side.file = request.candidate_file.empty() ? request.baseline_file : request.candidate_file;
  AddOverrides(&side, "--set", request.sets);
  AddOverrides(&side, "--candidate-set", request.candidate_sets);
  return side;
}

bool ScenarioComparison::passed() const {
  for (const Gate& gate : gates) {
    if (!GatePasses(gate, changes[static_cast<std::size_t>(gate.info - MetricTable().data())])) {
      return false;
    }
  }
  return true;
}

ScenarioComparison CompareScenarios(const CompareRequest& request, const std::vector<Gate>& gates) {
  CompareSide baseline = BaselineSide(request);
  CompareSide candidate = CandidateSide(request);
  Scenario baseline_scenario = LoadScenarioSide(&baseline);
  Scenario candidate_scenario = LoadScenarioSide(&candidate);
  RunResult baseline_run = RunSide(baseline, baseline_scenario);
  RunResult candidate_run = RunSide(candidate, candidate_scenario);
  std::vector<MetricChange> changes = CompareMetrics(baseline_run.metrics, candidate_run.metrics);
  return ScenarioComparison{std::move(baseline),          std::move(candidate),
                            std::move(baseline_scenario), std::move(candidate_scenario),
                            std::move(baseline_run),      std::move(candidate_run),
                            std::move(changes),           gates};
}

}  // namespace shapebench::bench
