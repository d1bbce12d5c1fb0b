// Method none: no shaping; the acceleration steps straight to the steady a.
#include "controller/shaper_registry.h"

namespace shapebench::controller {

std::vector<ShaperEntry> BuiltInShapers_none() {
  ShaperEntry none;
  none.key = kNoShaping;
  none.name = "No shaping";
  none.description = "the acceleration steps straight to a (plain linear acc/dec)";
  none.kind = ShaperKind::kNone;
  none.rank = 0;
  none.design = [](const PatternConfig&, double) { return std::vector<Impulse>{{0.0, 1.0}}; };
  none.summary = [](const PatternConfig&) { return std::string(); };  // "method none"
  return {none};
}

}  // namespace shapebench::controller
