#include "common/engineering_units.h"

#include <cmath>
#include <cstdio>

namespace shapebench::bench {

std::string EngineeringText(double value, std::string_view unit, int digits) {
  if (std::isnan(value)) return "n/a";
  double scale = 1.0;
  std::string shown(unit == "m" || unit == "s" || unit == "Hz" ? unit : "");
  const double magnitude = std::abs(value);
  if (magnitude > 0.0 && std::isfinite(value)) {
    if (unit == "m" && magnitude < 1e-3) {
      scale = 1e6, shown = "um";
    } else if (unit == "m" && magnitude < 1.0) {
      scale = 1e3, shown = "mm";
    } else if (unit == "s" && magnitude < 1.0) {
      scale = 1e3, shown = "ms";
    }
  }
  char number[48];
  std::snprintf(number, sizeof number, "%.*g", digits, value * scale);
  return shown.empty() ? std::string(number) : std::string(number) + " " + shown;
}

}  // namespace shapebench::bench
