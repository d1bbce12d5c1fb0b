// Numbers as text, the one place for them: in messages (six significant digits, the way a
// user typed them), in reports (a fixed count of digits), and in engineering units (the
// `run` table, check lines, the HTML report).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <utility>

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
// not that of the double. "%.*g".
inline std::string FormatNumber(double value, int digits) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

// " (got VALUE)", VALUE as FormatNumber(value): the tail of a validation message.
inline std::string FormatGot(double value) { return " (got " + FormatNumber(value) + ")"; }

// `decimals` digits after the point ("%.*f"): seconds in JUnit, percentages.
inline std::string FormatFixed(double value, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

// Mantissa with `decimals` digits and an exponent ("%.*e"): a residual near zero.
inline std::string FormatScientific(double value, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*e", decimals, value);
  return buffer;
}

// A value (SI, in `unit` as in the metric table: "m", "s", "Hz", "1", "count", ...) in
// engineering units, as (number, unit): lengths in um below 1 mm and in mm below 1 m,
// times in ms below 1 s, to `digits` significant digits (counts to 12). The prefix is
// chosen per value by its magnitude; zero and infinities keep the SI unit ("0 m"); units
// "1" and "count" show none; NaN is ("n/a", ""). JSON and CSV keep SI: this is for display.
std::pair<std::string, std::string> EngineeringValue(double value, std::string_view unit, int digits = 6);

// EngineeringValue as one text: "7.99855 um", "12.5 ms", "25 Hz", "0.726", "n/a".
std::string EngineeringText(double value, std::string_view unit, int digits = 6);

}  // namespace shapebench
