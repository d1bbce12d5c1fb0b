// PatternConfig: the keys every shaper shares are checked here, the rest by the
// shaper's registry entry (controller/shaper_registry.h).
#include "controller/pattern_config.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

std::string Num(double v) { return FormatNumber(v); }

bool Finite(double v) { return std::isfinite(v); }

// The keys of the registry's entries of `kind` (or of `other`), in registry order.
std::string KeysOfKind(ShaperKind kind, ShaperKind other) {
  std::string keys;
  for (const ShaperEntry* entry : Shapers()) {
    if (entry->kind == kind || entry->kind == other) keys += (keys.empty() ? "" : ", ") + entry->key;
  }
  return keys;
}

}  // namespace

std::vector<double> PatternConfig::DesignFrequencies() const {
  return frequencies_hz.empty() ? std::vector<double>{frequency_hz} : frequencies_hz;
}

void PatternConfig::validate() const {
  const ShaperEntry& entry = FindShaper(method);
  if (!(Finite(frequency_hz) && frequency_hz > 0.0)) {
    throw ValidationError("frequency_hz", "must be a finite number > 0 (got " + Num(frequency_hz) + ")");
  }
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    const double f = frequencies_hz[i];
    if (!(Finite(f) && f > 0.0)) {
      throw ValidationError("frequencies_hz[" + std::to_string(i) + "]",
                            "must be a finite number > 0 (got " + Num(f) + ")");
    }
  }
  const double z = design_damping_ratio;
  if (!(Finite(z) && z >= 0.0 && z < 1.0)) {
    throw ValidationError("design_damping_ratio", "must be in [0, 1) (got " + Num(z) + ")");
  }
  if (z > 0.0 && entry.kind == ShaperKind::kPatentStep) {
    throw ValidationError("design_damping_ratio",
                          "applies to the library shapers (" +
                              KeysOfKind(ShaperKind::kImpulse, ShaperKind::kCustom) +
                              "); the patent's methods (" +
                              KeysOfKind(ShaperKind::kPatentStep, ShaperKind::kPatentStep) +
                              ") are designed for an undamped mode (got " + Num(z) + ")");
  }
  const double v = vibration_tolerance;
  if (!(Finite(v) && v > 0.0 && v < 1.0)) {
    throw ValidationError("vibration_tolerance", "must be in (0, 1) (a fraction of the unshaped "
                                                 "vibration; got " + Num(v) + ")");
  }
  if (entry.kind != ShaperKind::kCustom && !impulses.empty()) {
    throw ValidationError("impulses", "is for method " + KeysOfKind(ShaperKind::kCustom, ShaperKind::kCustom) +
                                          " only (method is " + method + ")");
  }
  if (entry.validate) entry.validate(*this);
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
                                " frequencies would have " + Num(per_mode) + "^" +
                                std::to_string(frequencies.size()) + " = " + Num(count) +
                                " impulses; allowed: at most 65536 (fewer frequencies or impulses)");
    }
  }
  if (!(Finite(step_resolution_s) && step_resolution_s >= 0.0)) {
    throw ValidationError("step_resolution_s", "must be >= 0 (0 keeps exact step times; got " +
                                                   Num(step_resolution_s) + ")");
  }
}

}  // namespace shapebench::controller
