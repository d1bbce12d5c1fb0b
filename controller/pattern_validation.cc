// PatternConfig::validate: the keys every shaper shares are checked here, the rest by the
// shaper's registry entry (controller/shaper_registry.h). Apart from pattern_config.cc:
// the registry's entries are built on PatternConfig.
#include "controller/pattern_config.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {


// The keys of the registry's entries of `kind` (or of `other`), in registry order.
std::string KeysOfKind(ShaperKind kind, ShaperKind other) {
  std::string keys;
  for (const ShaperEntry* entry : Shapers()) {
    if (entry->kind == kind || entry->kind == other) keys += (keys.empty() ? "" : ", ") + entry->key;
  }
  return keys;
}

// `damping_ratios`: one per design frequency, each like design_damping_ratio.
void ValidateDampingRatios(const PatternConfig& config, const ShaperEntry& entry) {
  if (config.damping_ratios.empty()) return;
  if (config.damping_ratios.size() != config.frequencies_hz.size()) {
    throw ValidationError("damping_ratios",
                          "needs one ratio per design frequency: " +
                              std::to_string(config.damping_ratios.size()) + " given, " +
                              std::to_string(config.frequencies_hz.size()) + " in frequencies_hz" +
                              (config.frequencies_hz.empty() ? " (give frequencies_hz, or "
                                                               "design_damping_ratio for one mode)"
                                                             : ""));
  }
  if (config.design_damping_ratio != 0.0) {
    throw ValidationError("damping_ratios", "replaces design_damping_ratio; give one of them");
  }
  for (std::size_t i = 0; i < config.damping_ratios.size(); ++i) {
    const double z = config.damping_ratios[i];
    const std::string field = "damping_ratios[" + std::to_string(i) + "]";
    if (!(std::isfinite(z) && z >= 0.0 && z < 1.0)) {
      throw ValidationError(field, "must be in [0, 1) (got " + FormatNumber(z) + ")");
    }
    if (z > 0.0 && entry.kind == ShaperKind::kPatentStep) {
      throw ValidationError(field, "the patent's methods (" +
                                       KeysOfKind(ShaperKind::kPatentStep, ShaperKind::kPatentStep) +
                                       ") are designed for an undamped mode (got " + FormatNumber(z) + ")");
    }
  }
}

// The entry's own checks; with a damping ratio per mode, mode by mode (the design of
// each reads its own ratio), a complaint about the ratio naming that mode's.
void ValidateEntry(const PatternConfig& config, const ShaperEntry& entry) {
  if (!entry.validate) return;
  if (config.damping_ratios.empty()) {
    entry.validate(config);
    return;
  }
  for (std::size_t i = 0; i < config.damping_ratios.size(); ++i) {
    try {
      entry.validate(config.ForMode(i));
    } catch (const ValidationError& error) {
      if (error.field() != "design_damping_ratio") throw;
      throw ValidationError("damping_ratios[" + std::to_string(i) + "]", error.message());
    }
  }
}

}  // namespace

void PatternConfig::validate() const {
  const ShaperEntry& entry = FindShaper(method);
  if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
    throw ValidationError("frequency_hz", "must be a finite number > 0 (got " + FormatNumber(frequency_hz) + ")");
  }
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    const double f = frequencies_hz[i];
    if (!(std::isfinite(f) && f > 0.0)) {
      throw ValidationError("frequencies_hz[" + std::to_string(i) + "]",
                            "must be a finite number > 0 (got " + FormatNumber(f) + ")");
    }
  }
  const double z = design_damping_ratio;
  if (!(std::isfinite(z) && z >= 0.0 && z < 1.0)) {
    throw ValidationError("design_damping_ratio", "must be in [0, 1) (got " + FormatNumber(z) + ")");
  }
  if (z > 0.0 && entry.kind == ShaperKind::kPatentStep) {
    throw ValidationError("design_damping_ratio",
                          "applies to the library shapers (" +
                              KeysOfKind(ShaperKind::kImpulse, ShaperKind::kCustom) +
                              "); the patent's methods (" +
                              KeysOfKind(ShaperKind::kPatentStep, ShaperKind::kPatentStep) +
                              ") are designed for an undamped mode (got " + FormatNumber(z) + ")");
  }
  ValidateDampingRatios(*this, entry);
  const double v = vibration_tolerance;
  if (!(std::isfinite(v) && v > 0.0 && v < 1.0)) {
    throw ValidationError("vibration_tolerance", "must be in (0, 1) (a fraction of the unshaped "
                                                 "vibration; got " + FormatNumber(v) + ")");
  }
  if (entry.kind != ShaperKind::kCustom && !impulses.empty()) {
    throw ValidationError("impulses", "is for method " + KeysOfKind(ShaperKind::kCustom, ShaperKind::kCustom) +
                                          " only (method is " + method + ")");
  }
  ValidateEntry(*this, entry);
  if (entry.kind == ShaperKind::kImpulse || entry.kind == ShaperKind::kPatentStep) {
    // Guard rail (docs/reliability.md): the convolved shaper has the product of the
    // designs' impulse counts; at most ZVDD's at 8 frequencies, 4^8.
    constexpr double kMaxConvolvedImpulses = 65536.0;
    const std::vector<double> frequencies = DesignFrequencies();
    const double per_mode = static_cast<double>(entry.design(*this, frequencies.front()).size());
    const double count = std::pow(per_mode, static_cast<double>(frequencies.size()));
    if (count > kMaxConvolvedImpulses) {
      throw ValidationError(frequencies_hz.empty() ? "frequency_hz" : "frequencies_hz",
                            "the shaper convolved for " + std::to_string(frequencies.size()) +
                                " frequencies would have " + FormatNumber(per_mode) + "^" +
                                std::to_string(frequencies.size()) + " = " + FormatNumber(count) +
                                " impulses; allowed: at most 65536 (fewer frequencies or impulses)");
    }
  }
  if (!(std::isfinite(step_resolution_s) && step_resolution_s >= 0.0)) {
    throw ValidationError("step_resolution_s", "must be >= 0 (0 keeps exact step times; got " +
                                                   FormatNumber(step_resolution_s) + ")");
  }
}

}  // namespace shapebench::controller
