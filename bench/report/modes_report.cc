#include "bench/report/modes_report.h"

#include <cmath>
#include <cstdio>

namespace shapebench::bench {
namespace {

// JSON has no NaN/inf: they become null, as in the metrics.
nlohmann::ordered_json Number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json ModeJson(const model::ModeInfo& mode, const char* axis) {
  nlohmann::ordered_json entry = nlohmann::ordered_json::object();
  if (axis != nullptr) entry["axis"] = axis;
  entry["frequency_hz"] = Number(mode.frequency_hz);
  entry["damping_ratio"] = Number(mode.damping_ratio);
  entry["participation"] = Number(mode.participation);
  return entry;
}

}  // namespace

void PrintModesTable(std::ostream& out, const std::vector<model::AxisModes>& axes,
                     int driven_axis) {
  char line[160];
  std::snprintf(line, sizeof line, "%-6s%-6s%-16s%-16s%s\n", "axis", "mode", "frequency_hz",
                "damping_ratio", "participation");
  out << line;
  for (const model::AxisModes& axis : axes) {
    for (std::size_t i = 0; i < axis.analysis.modes.size(); ++i) {
      const auto& mode = axis.analysis.modes[i];
      std::snprintf(line, sizeof line, "%-6s%-6zu%-16.6g%-16.6g%.6g\n",
                    model::AxisName(axis.axis), i + 1, mode.frequency_hz, mode.damping_ratio,
                    mode.participation);
      out << line;
    }
  }
  for (const model::AxisModes& axis : axes) {
    std::snprintf(line, sizeof line, "static_deflection_per_accel_s2  %s  %.6g m per m/s^2%s\n",
                  model::AxisName(axis.axis), axis.analysis.static_deflection_per_accel_s2,
                  axis.axis == driven_axis ? "  (driven axis)" : "");
    out << line;
  }
}

nlohmann::ordered_json ModesJson(const std::vector<model::AxisModes>& axes, int driven_axis) {
  nlohmann::ordered_json modes = nlohmann::ordered_json::array();
  nlohmann::ordered_json by_axis = nlohmann::ordered_json::object();
  double driven_static = 0.0;
  for (const model::AxisModes& axis : axes) {
    const char* name = model::AxisName(axis.axis);
    for (const auto& mode : axis.analysis.modes) modes.push_back(ModeJson(mode, name));
    by_axis[name] = Number(axis.analysis.static_deflection_per_accel_s2);
    if (axis.axis == driven_axis) driven_static = axis.analysis.static_deflection_per_accel_s2;
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  json["modes"] = modes;
  json["static_deflection_per_accel_s2"] = Number(driven_static);
  json["static_deflection_per_accel_s2_by_axis"] = by_axis;
  return json;
}

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
  for (const auto& mode : analysis.modes) modes.push_back(ModeJson(mode, nullptr));
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  json["modes"] = modes;
  json["static_deflection_per_accel_s2"] = Number(analysis.static_deflection_per_accel_s2);
  return json;
}

}  // namespace shapebench::bench
