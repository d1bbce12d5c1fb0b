// The registry against a design's specification; see the header.
#include "controller/design_comparison.h"

#include <algorithm>
#include <stdexcept>

#include "controller/shaper_registry.h"

namespace shapebench::controller {

double WorstImpulseResidualOverBand(const std::vector<Impulse>& impulses, const DesignBand& band, int frequencies) {
  std::vector<double> dampings{band.damping_lo};
  if (band.damping_hi > band.damping_lo) {
    dampings.push_back(0.5 * (band.damping_lo + band.damping_hi));
    dampings.push_back(band.damping_hi);
  }
  const int count = band.frequency_hi_hz > band.frequency_lo_hz ? std::max(frequencies, 2) : 1;
  double worst = 0.0;
  for (int i = 0; i < count; ++i) {
    const double f = count == 1 ? band.frequency_lo_hz
                                : band.frequency_lo_hz + (band.frequency_hi_hz - band.frequency_lo_hz) * i / (count - 1);
    for (double z : dampings) worst = std::max(worst, ResidualVibration(impulses, f, z));
  }
  return worst;
}

std::vector<ShaperAgainstSpec> CompareRegistryShapers(const DesignSpec& spec) {
  std::vector<ShaperAgainstSpec> all;
  for (const ShaperEntry* entry : Shapers()) {
    if (entry->kind != ShaperKind::kPatentStep && entry->kind != ShaperKind::kImpulse) continue;
    PatternConfig config;
    config.method = entry->key;
    config.vibration_tolerance = spec.tolerance > 0.0 ? spec.tolerance : PatternConfig{}.vibration_tolerance;
    for (const DesignBand& band : spec.bands) {
      config.frequencies_hz.push_back(0.5 * (band.frequency_lo_hz + band.frequency_hi_hz));
      config.damping_ratios.push_back(0.5 * (band.damping_lo + band.damping_hi));
    }
    config.frequency_hz = config.frequencies_hz.front();
    // The patent's methods are designed for an undamped mode (pattern_validation.cc);
    // they are still held to the bands' damping.
    if (entry->kind == ShaperKind::kPatentStep) config.damping_ratios.clear();
    ShaperAgainstSpec s;
    s.method = entry->key;
    try {
      config.validate();
      s.impulses = ShaperImpulses(config);
    } catch (const std::exception&) {
      continue;  // e.g. methods 1-4 take one frequency; an EI with no damped design
    }
    s.duration_s = ShaperDuration(s.impulses);
    s.meets = true;
    for (const Impulse& i : s.impulses) s.meets = s.meets && i.amplitude >= 0.0;
    for (const DesignBand& band : spec.bands) {
      s.worst_v.push_back(WorstImpulseResidualOverBand(s.impulses, band));
      s.meets = s.meets && s.worst_v.back() <= spec.tolerance + 1e-12;
    }
    all.push_back(std::move(s));
  }
  std::stable_sort(all.begin(), all.end(), [](const ShaperAgainstSpec& a, const ShaperAgainstSpec& b) {
    if (a.meets != b.meets) return a.meets;
    return a.duration_s < b.duration_s;
  });
  return all;
}

}  // namespace shapebench::controller
