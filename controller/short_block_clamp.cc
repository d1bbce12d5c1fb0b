#include "controller/short_block_clamp.h"

#include <algorithm>
#include <cmath>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::controller {
namespace {

void CheckRatio(const char* field, double value, bool zero_allowed) {
  if (!(std::isfinite(value) && (value > 0.0 || (zero_allowed && value == 0.0)) && value <= 1.0)) {
    throw ValidationError(field, std::string("must be in ") + (zero_allowed ? "[0, 1] (0 = none)" : "(0, 1]") +
                                     " (got " + FormatNumber(value) + ")");
  }
}

}  // namespace

void ShortBlockConfig::validate() const {
  CheckRatio("ratio_line", ratio_line, false);
  CheckRatio("ratio_arc", ratio_arc, false);
  CheckRatio("min_ratio_line", min_ratio_line, true);
  CheckRatio("min_ratio_arc", min_ratio_arc, true);
  CheckRatio("scale", scale, false);
  if (!(std::isfinite(preset_feed_mm_min) && preset_feed_mm_min > 0.0)) {
    throw ValidationError("preset_feed_mm_min", "must be > 0 (got " + FormatNumber(preset_feed_mm_min) + ")");
  }
}

double ShortBlockRatio(const ShortBlockConfig& config, bool is_arc) {
  const double input = is_arc ? config.ratio_arc : config.ratio_line;
  const double minimum = is_arc ? config.min_ratio_arc : config.min_ratio_line;
  return minimum > 0.0 ? std::min(input, minimum) : input;
}

ShortBlockFeed ClampShortBlock(const ShortBlockConfig& config, bool is_arc, double length_m,
                               double feed_m_s, double period_s) {
  const double travel = feed_m_s * period_s;  // one period's travel at the feed
  switch (config.mode) {
    case ShortBlockMode::kOff:
      break;
    case ShortBlockMode::kRatio: {
      const double allowed = ShortBlockRatio(config, is_arc) * length_m;
      if (allowed < travel) return {allowed / period_s, true};
      break;
    }
    case ShortBlockMode::kLength:
      if (length_m < travel) return {length_m / period_s, true};
      break;
    case ShortBlockMode::kScale:
      if (length_m < travel) return {feed_m_s * config.scale, true};
      break;
    case ShortBlockMode::kPreset:
      if (length_m < travel) return {std::min(feed_m_s, config.preset_feed_mm_min / 60000.0), true};
      break;
  }
  return {feed_m_s, false};
}

std::vector<std::string> ShortBlockWarnings(const ShortBlockConfig& config) {
  std::vector<std::string> warnings;
  if (config.mode != ShortBlockMode::kRatio) return warnings;
  auto check = [&](const char* key, double input, const char* min_key, double minimum, const char* shape) {
    if (minimum > 0.0 && input > minimum) {
      warnings.push_back("controller.short_block." + std::string(key) + ": " + FormatNumber(input) +
                         " is above the minimum " + FormatNumber(minimum) + " set for " + shape +
                         " (" + min_key + "); the minimum is used");
    }
  };
  check("ratio_line", config.ratio_line, "min_ratio_line", config.min_ratio_line, "lines");
  check("ratio_arc", config.ratio_arc, "min_ratio_arc", config.min_ratio_arc, "arcs");
  return warnings;
}

}  // namespace shapebench::controller
