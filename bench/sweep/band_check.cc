// Band checks (bench/sweep/band_check.h).
#include "bench/sweep/band_check.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "bench/config/config_document.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/structure_numbers.h"
#include "bench/scenario/metrics.h"
#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::bench {

std::string BandValueText(double x) { return FormatNumber(x, 17); }

BandPointRunner::BandPointRunner(const Scenario& scenario, const std::vector<Override>& overrides,
                                 const Check& check)
    : scenario_(scenario), overrides_(overrides), check_(check) {
  fast_ = IsStructureNumberKey(check.band->key);
}

ConfigError BandPointRunner::AtBandKey(const ConfigError& error, const std::string& text) const {
  // The band's value is the last override: an error there is the band's.
  const bool band_value = error.file() == kOverrideSource &&
                          error.line() == static_cast<int>(overrides_.size()) + 1;
  if (!band_value) return error;
  const CheckBand& band = *check_.band;
  return ConfigError(band.file, band.line, band.column, band.path,
                     "band point " + band.key + " = " + text + ": " +
                         (error.key_path().empty() ? "" : error.key_path() + ": ") + error.message());
}

Scenario BandPointRunner::LoadAt(const std::string& text) const {
  std::vector<Override> overrides = overrides_;
  overrides.push_back({check_.band->key, text});
  try {
    const ParseCacheScope parse_once;
    return LoadScenario(scenario_.source_file, overrides);
  } catch (const ConfigError&) {
    // Loaded again outside the cache, which locates the error.
    try {
      return LoadScenario(scenario_.source_file, overrides);
    } catch (const ConfigError& error) {
      throw AtBandKey(error, text);
    }
  }
}

double BandPointRunner::operator()(double x) {
  const std::string text = BandValueText(x);
  ++runs_;
  Scenario scenario;
  bool set = false;
  if (fast_) {
    scenario = scenario_;
    set = SetStructureNumbers(&scenario, {{check_.band->key, text}});
  }
  if (!set) scenario = LoadAt(text);
  RunResult result;
  try {
    if (set && command_) {
      result = RunScenario(scenario, RunOptions{false, command_.get()});
    } else {
      result = RunScenario(scenario, RunOptions{false});
      // A structure number is not read by the controller: every point's command is this one.
      if (set) command_ = std::make_shared<const controller::MultiAxisCommand>(std::move(result.command));
    }
  } catch (const ValidationError& error) {
    std::vector<Override> overrides = overrides_;
    overrides.push_back({check_.band->key, text});
    throw AtBandKey(LocateValidationError(scenario_.source_file, overrides, error), text);
  }
  if (result.metrics.static_displacement_m == 0.0) zero_static_at_.push_back(x);
  const MetricInfo* info = FindMetric(check_.metric);
  return info != nullptr ? result.metrics.*info->field : NAN;
}

bool BandPointRunner::ZeroStaticAt(double x) const {
  return std::find(zero_static_at_.begin(), zero_static_at_.end(), x) != zero_static_at_.end();
}

void ValidateBandChecks(const Scenario& scenario, const std::vector<Override>& overrides) {
  for (const Check& check : scenario.checks) {
    if (!check.band) continue;
    const BandPointRunner runner(scenario, overrides, check);
    runner.LoadAt(BandValueText(check.band->from));
    runner.LoadAt(BandValueText(check.band->to));
  }
}

CheckResult EvaluateBandCheck(const Scenario& scenario, const std::vector<Override>& overrides,
                              const Check& check, const ExtremumSearch& search) {
  BandPointRunner runner(scenario, overrides, check);
  const auto metric = [&](double x) { return runner(x); };
  // The worst per bound: the maximum for max, the minimum for min.
  std::optional<IntervalPoint> worst;
  for (const Extreme extreme : {Extreme::kMaximum, Extreme::kMinimum}) {
    if (!(extreme == Extreme::kMaximum ? check.max : check.min)) continue;
    const IntervalPoint found =
        FindExtremum(metric, check.band->from, check.band->to, extreme, search).worst;
    if (!worst || Violation(check, found.value) > Violation(check, worst->value)) worst = found;
    if (std::isnan(found.value)) break;
  }
  CheckResult result = EvaluateCheck(check, worst->value, worst->x, runner.runs());
  const std::string reason = runner.ZeroStaticAt(worst->x) ? ZeroStaticReason(check.metric) : "";
  if (std::isnan(worst->value) && !reason.empty()) {
    result.message = check.metric + " is n/a at " + check.band->key + " = " + FormatValue(worst->x, 7) +
                     " because " + reason;
  }
  return result;
}

std::vector<CheckResult> EvaluateScenarioChecks(const Scenario& scenario,
                                                const std::vector<Override>& overrides,
                                                const Metrics& metrics) {
  std::vector<CheckResult> results = EvaluateChecks(scenario.checks, metrics);
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (scenario.checks[i].band) results[i] = EvaluateBandCheck(scenario, overrides, scenario.checks[i]);
  }
  return results;
}

}  // namespace shapebench::bench
