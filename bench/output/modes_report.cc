#include "bench/output/modes_report.h"

#include <cmath>
#include <cstdio>

#include "bench/output/json_number.h"
#include "model/coupled_modes.h"

namespace shapebench::bench {
namespace {

nlohmann::ordered_json ModeJson(const model::ModeInfo& mode, const char* axis) {
  nlohmann::ordered_json entry = nlohmann::ordered_json::object();
  if (axis != nullptr) entry["axis"] = axis;
  entry["frequency_hz"] = JsonNumber(mode.frequency_hz);
  entry["damping_ratio"] = JsonNumber(mode.damping_ratio);
  entry["participation"] = JsonNumber(mode.participation);
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
    by_axis[name] = JsonNumber(axis.analysis.static_deflection_per_accel_s2);
    if (axis.axis == driven_axis) driven_static = axis.analysis.static_deflection_per_accel_s2;
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  json["modes"] = modes;
  json["static_deflection_per_accel_s2"] = JsonNumber(driven_static);
  json["static_deflection_per_accel_s2_by_axis"] = by_axis;
  return json;
}

void PrintModesCoupling(std::ostream& out, const model::MultiAxisMachineConfig& machine) {
  const model::ModalMachineConfig* coupled = machine.CoupledModes();
  if (coupled == nullptr) return;
  char line[256];
  const Eigen::Matrix3d compliance = model::ModalCompliance(*coupled, machine.driven_axis);
  out << "\nstatic compliance, m per m/s^2 (row: deflection along; column: acceleration along)\n";
  std::snprintf(line, sizeof line, "%-6s%-16s%-16s%s\n", "", "x", "y", "z");
  out << line;
  for (int b = 0; b < model::kNumAxes; ++b) {
    std::snprintf(line, sizeof line, "%-6s%-16.6g%-16.6g%.6g\n", model::AxisName(b), compliance(b, 0),
                  compliance(b, 1), compliance(b, 2));
    out << line;
  }
  out << "\ncoupling (participation: how each axis' acceleration excites the mode; shape: tool "
         "deflection per unit modal coordinate)\n";
  std::snprintf(line, sizeof line, "%-6s%-14s%-15s%-17s%-17s%-17s%-14s%-14s%s\n", "mode", "frequency_hz",
                "damping_ratio", "participation_x", "participation_y", "participation_z", "shape_x", "shape_y",
                "shape_z");
  out << line;
  for (std::size_t i = 0; i < coupled->modes.size(); ++i) {
    const model::ModalMode& mode = coupled->modes[i];
    const Eigen::Vector3d p = model::ModeParticipation(mode, machine.driven_axis);
    const Eigen::Vector3d s = model::ModeShape(mode, machine.driven_axis);
    std::snprintf(line, sizeof line, "%-6zu%-14.6g%-15.6g%-17.6g%-17.6g%-17.6g%-14.6g%-14.6g%.6g\n", i + 1,
                  mode.frequency_hz, mode.damping_ratio, p(0), p(1), p(2), s(0), s(1), s(2));
    out << line;
  }
  if (!coupled->modal_file.empty()) out << "modes from " << coupled->modal_file << "\n";
}

void AddModesCouplingJson(const model::MultiAxisMachineConfig& machine, nlohmann::ordered_json* json) {
  const model::ModalMachineConfig* coupled = machine.CoupledModes();
  if (coupled == nullptr) return;
  const Eigen::Matrix3d compliance = model::ModalCompliance(*coupled, machine.driven_axis);
  nlohmann::ordered_json matrix = nlohmann::ordered_json::array();
  for (int b = 0; b < model::kNumAxes; ++b) {
    matrix.push_back({JsonNumber(compliance(b, 0)), JsonNumber(compliance(b, 1)), JsonNumber(compliance(b, 2))});
  }
  auto vector = [](const Eigen::Vector3d& v) {
    nlohmann::ordered_json entry = nlohmann::ordered_json::object();
    for (int a = 0; a < model::kNumAxes; ++a) entry[model::AxisName(a)] = JsonNumber(v(a));
    return entry;
  };
  nlohmann::ordered_json coupling = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < coupled->modes.size(); ++i) {
    const model::ModalMode& mode = coupled->modes[i];
    nlohmann::ordered_json entry = nlohmann::ordered_json::object();
    entry["mode"] = i + 1;
    entry["frequency_hz"] = JsonNumber(mode.frequency_hz);
    entry["damping_ratio"] = JsonNumber(mode.damping_ratio);
    entry["participation"] = vector(model::ModeParticipation(mode, machine.driven_axis));
    entry["shape"] = vector(model::ModeShape(mode, machine.driven_axis));
    coupling.push_back(entry);
  }
  (*json)["static_compliance_m_per_m_s2"] = matrix;
  (*json)["coupling"] = coupling;
  if (!coupled->modal_file.empty()) (*json)["modal_file"] = coupled->modal_file;
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
  json["static_deflection_per_accel_s2"] = JsonNumber(analysis.static_deflection_per_accel_s2);
  return json;
}

}  // namespace shapebench::bench
