// A number in the JSON outputs: JSON has no NaN or infinity, so they are null (as in the
// metrics; docs/output-formats.md).
#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace shapebench::bench {

inline nlohmann::ordered_json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace shapebench::bench
