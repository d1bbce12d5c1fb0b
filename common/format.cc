#include "common/format.h"

#include <cmath>

namespace shapebench {

std::pair<std::string, std::string> EngineeringValue(double value, std::string_view unit, int digits) {
  if (std::isnan(value)) return {"n/a", ""};
  if (unit == "bool") return {value != 0.0 ? "yes" : "no", ""};
  if (unit == "count") return {FormatNumber(value, 12), ""};
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
  return {FormatNumber(value * scale, digits), shown};
}

std::string EngineeringText(double value, std::string_view unit, int digits) {
  const auto [number, shown] = EngineeringValue(value, unit, digits);
  return shown.empty() ? number : number + " " + shown;
}

}  // namespace shapebench
