// Numbers as people write them: decimal only, one grammar for YAML values
// (bench/config/node_reader.h's IsNumberText) and command-line options. strtod alone also
// reads hexadecimal ("0x10" is 16: a --gate of 1600%), "inf", "nan" and leading blanks.
#pragma once

#include <string_view>

namespace shapebench {

// The whole text matches [-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)? (YAML 1.2's core-schema
// decimal numbers). A hand-written matcher: std::regex made reading a scenario several
// times slower, which sweeps do per point.
bool IsDecimalText(std::string_view text);

// True, with *value (as strtod reads it), when IsDecimalText(text) and the value is finite.
bool ParseDecimal(std::string_view text, double* value);

}  // namespace shapebench
