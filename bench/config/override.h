// --set KEY=VALUE: one key of the input replaced from the command line.
#pragma once

#include <string>
#include <vector>

namespace shapebench::bench {

struct Override {
  std::string key_path;    // "controller.pattern.method", "machine.modes[0].gain"
  std::string value_yaml;  // parsed as YAML when applied: "3", "[1, 2]", "{gain: 2}"
};

// Splits "a.b[0].c=VALUE" at the first '='. `index` is the option's 1-based position
// among the --set options; a malformed option throws ConfigError at "--set:INDEX:1".
Override ParseOverride(const std::string& text, int index);
std::vector<Override> ParseOverrides(const std::vector<std::string>& texts);

// The location prefix of errors caused by the index-th --set: "--set" with line = index.
inline constexpr const char* kOverrideSource = "--set";

}  // namespace shapebench::bench
