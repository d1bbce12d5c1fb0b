#include "bench/modes_report.h"

#include <cmath>
#include <cstdio>

namespace shapebench::bench {
namespace {

// JSON has no NaN/inf: they become null, as in the metrics.
nlohmann::ordered_json Number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

void PrintModesTable(std::ostream& out, const model::ModalAnalysis& analysis) {
  char line[128];
  std::snprintf(line, sizeof line, "%-6s%-16s%-16s%s\n", "mode", "frequency_hz", "damping_ratio",
                "participation");
  out << line;
  for (std::size_t i = 0; i < analysis.modes.size(); ++i) {
    const auto& mode = analysis.modes[i];
    std::snprintf(line, sizeof line, "%-6zu%-16.6g%-16.6g%.6g\n", i + 1, mode.frequency_hz,
                  mode.damping_ratio, mode.participation);
    out << line;
  }
  std::snprintf(line, sizeof line, "static_deflection_per_accel_s2  %.6g m per m/s^2\n",
                analysis.static_deflection_per_accel_s2);
  out << line;
}

nlohmann::ordered_json ModesJson(const model::ModalAnalysis& analysis) {
  nlohmann::ordered_json modes = nlohmann::ordered_json::array();
  for (const auto& mode : analysis.modes) {
    nlohmann::ordered_json entry = nlohmann::ordered_json::object();
    entry["frequency_hz"] = Number(mode.frequency_hz);
    entry["damping_ratio"] = Number(mode.damping_ratio);
    entry["participation"] = Number(mode.participation);
    modes.push_back(entry);
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  json["modes"] = modes;
  json["static_deflection_per_accel_s2"] = Number(analysis.static_deflection_per_accel_s2);
  return json;
}

}  // namespace shapebench::bench
