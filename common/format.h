// Numbers in error messages: six significant digits, the way a user typed them, and more
// when six would not tell the value from a bound (a damping of 1.000001 is not "1").
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace shapebench {

// The shortest "%.Ng" text (6 <= N <= 15) that reads back as exactly `value`: a number as
// typed (15 digits survive a round trip through a double). A computed one, which needs 16
// or 17 digits (10.001100000000001), keeps six (10.0011).
inline std::string FormatNumber(double value) {
  char buffer[32];
  for (int digits = 6; digits <= 15; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (value != value || std::strtod(buffer, nullptr) == value) return buffer;
  }
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// A measured quantity to `digits` significant digits (a deviation, a time): its precision is
// not that of the double.
inline std::string FormatNumber(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace shapebench
