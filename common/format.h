// Numbers in error messages: six significant digits, the way a user typed them.
#pragma once

#include <cstdio>
#include <string>

namespace shapebench {

inline std::string FormatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace shapebench
