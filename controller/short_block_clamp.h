// CN104175175 (seed 002): the short-block feed clamp. When several blocks overlap in one
// interpolation period, the interpolation points (joined by straight lines) skip the
// blocks in between and the programmed shape is lost. The clamp lowers a short block's
// feed so that one period covers no more than the distance the embodiment allows:
//   ratio  (embodiments 1-2): distance per period = ratio x block length (ratio_line for
//          lines, ratio_arc for arcs); with per-shape minimums set, an input ratio above
//          the minimum for the block's shape is a warning and the minimum is used;
//          clamps when that distance is shorter than one period's travel at the feed, to
//          feed = that distance / period;
//   length (embodiment 3): a block shorter than one period's travel gets feed = length /
//          period;
//   scale  (embodiment 4): such a block gets feed x scale;
//   preset (embodiment 5): such a block gets the preset feed.
#pragma once

#include <string>
#include <vector>
#include "common/field_list.h"

namespace shapebench::controller {

enum class ShortBlockMode { kOff, kRatio, kLength, kScale, kPreset };

struct ShortBlockConfig {
  ShortBlockMode mode = ShortBlockMode::kOff;
  double ratio_line = 0.5;
  double ratio_arc = 0.2;
  // Embodiment 2: the smallest ratio allowed per shape; 0 = none set.
  double min_ratio_line = 0.0;
  double min_ratio_arc = 0.0;
  double scale = 0.5;                // mode scale
  double preset_feed_mm_min = 600.0; // mode preset
  void validate() const;             // throws ValidationError naming the field

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("mode", &mode, Choices<ShortBlockMode>{{"off", ShortBlockMode::kOff},
                                                    {"ratio", ShortBlockMode::kRatio},
                                                    {"length", ShortBlockMode::kLength},
                                                    {"scale", ShortBlockMode::kScale},
                                                    {"preset", ShortBlockMode::kPreset}});
    a->Visit("ratio_line", &ratio_line);
    a->Visit("ratio_arc", &ratio_arc);
    a->Visit("min_ratio_line", &min_ratio_line);
    a->Visit("min_ratio_arc", &min_ratio_arc);
    a->Visit("scale", &scale);
    a->Visit("preset_feed_mm_min", &preset_feed_mm_min);
  }
};

struct ShortBlockFeed {
  double feed_m_s = 0.0;
  bool clamped = false;
};

// The ratio the clamp uses for a block of this shape (the minimum when the input is
// above it).
double ShortBlockRatio(const ShortBlockConfig& config, bool is_arc);

// The planned feed of one block of `length_m` commanded at `feed_m_s`.
ShortBlockFeed ClampShortBlock(const ShortBlockConfig& config, bool is_arc, double length_m,
                               double feed_m_s, double period_s);

// The warnings of embodiment 2: an input ratio above the minimum for its shape.
std::vector<std::string> ShortBlockWarnings(const ShortBlockConfig& config);

}  // namespace shapebench::controller
