#include "bench/config/override.h"

#include "common/shown_text.h"
#include "bench/config/config_error.h"
#include "bench/config/key_path.h"

namespace shapebench::bench {

Override ParseOverride(const std::string& text, int index) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) {
    throw ConfigError(kOverrideSource, index, 1, "",
                      "expected KEY=VALUE (e.g. controller.pattern.method=3), got '" + ClippedForMessage(text) +
                          "'");
  }
  Override result{text.substr(0, eq), text.substr(eq + 1)};
  if (!ParseKeyPath(result.key_path)) {
    throw ConfigError(kOverrideSource, index, 1, result.key_path,
                      "not a key path; expected keys joined by '.' with optional [INDEX], "
                      "e.g. machine.modes[0].frequency_hz");
  }
  return result;
}

std::vector<Override> ParseOverrides(const std::vector<std::string>& texts) {
  std::vector<Override> overrides;
  overrides.reserve(texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) {
    overrides.push_back(ParseOverride(texts[i], static_cast<int>(i) + 1));
  }
  return overrides;
}

}  // namespace shapebench::bench
