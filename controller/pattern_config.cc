// PatternConfig's design frequencies and damping ratios (its validate(): pattern_validation.cc).
#include "controller/pattern_config.h"

#include <vector>

namespace shapebench::controller {

std::vector<double> PatternConfig::DesignFrequencies() const {
  return frequencies_hz.empty() ? std::vector<double>{frequency_hz} : frequencies_hz;
}

std::vector<double> PatternConfig::DesignDampingRatios() const {
  if (!damping_ratios.empty()) return damping_ratios;
  return std::vector<double>(DesignFrequencies().size(), design_damping_ratio);
}

PatternConfig PatternConfig::ForMode(std::size_t i) const {
  PatternConfig mode = *this;
  mode.frequency_hz = DesignFrequencies().at(i);
  mode.design_damping_ratio = DesignDampingRatios().at(i);
  mode.frequencies_hz.clear();
  mode.damping_ratios.clear();
  return mode;
}

}  // namespace shapebench::controller
