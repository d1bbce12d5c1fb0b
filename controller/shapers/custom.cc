// custom: `impulses: [{amplitude, time_s}, ...]` as given (amplitudes summing to 1, times
// >= 0 strictly ascending); frequency_hz / frequencies_hz and design_damping_ratio then
// only say which vibration the grid realization keeps.
#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {


void ValidateCustom(const PatternConfig& config) {
  if (config.impulses.empty()) {
    throw ValidationError("impulses", "method custom needs at least one impulse, e.g. impulses: "
                                      "[{amplitude: 0.5, time_s: 0}, {amplitude: 0.5, time_s: 0.02}]");
  }
  double total = 0.0;
  for (std::size_t i = 0; i < config.impulses.size(); ++i) {
    const Impulse& impulse = config.impulses[i];
    const std::string at = "impulses[" + std::to_string(i) + "]";
    if (!std::isfinite(impulse.amplitude)) {
      throw ValidationError(at + ".amplitude", "must be a finite number (got " + FormatNumber(impulse.amplitude) + ")");
    }
    if (!(std::isfinite(impulse.time_s) && impulse.time_s >= 0.0)) {
      throw ValidationError(at + ".time_s", "must be >= 0 s (got " + FormatNumber(impulse.time_s) + ")");
    }
    if (i > 0 && !(impulse.time_s > config.impulses[i - 1].time_s)) {
      throw ValidationError(at + ".time_s", "must be after the previous impulse's (" +
                                                FormatNumber(config.impulses[i - 1].time_s) +
                                                " s): times strictly ascending (got " +
                                                FormatNumber(impulse.time_s) + ")");
    }
    total += impulse.amplitude;
  }
  if (std::abs(total - 1.0) > 1e-9) {
    throw ValidationError("impulses", "the amplitudes must sum to 1 (unit DC gain; got " + FormatNumber(total) + ")");
  }
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_custom() {
  ShaperEntry custom;
  custom.key = "custom";
  custom.name = "Custom";
  custom.description = "the impulses given (amplitudes summing to 1, times strictly ascending)";
  custom.kind = ShaperKind::kCustom;
  custom.rank = 900;
  custom.design = [](const PatternConfig& config, double) { return config.impulses; };
  custom.validate = ValidateCustom;
  custom.parameters = {"impulses"};
  custom.summary = [](const PatternConfig& config) {
    return std::to_string(config.impulses.size()) + " impulses";
  };
  return {custom};
}

}  // namespace shapebench::controller
