// The `modes` command's report: natural frequencies, damping ratios and static
// participation of the machine model, for every modelled axis.
#pragma once

#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

// One row per mode (axis, mode number within the axis, frequency, damping, participation
// in that axis' static deflection), then each axis' static deflection per m/s^2, the
// driven axis marked.
void PrintModesTable(std::ostream& out, const std::vector<model::AxisModes>& axes,
                     int driven_axis);

// {"modes": [{"axis": "y", "frequency_hz", "damping_ratio", "participation"}, ...],
//  "static_deflection_per_accel_s2": <the driven axis'>,
//  "static_deflection_per_accel_s2_by_axis": {"x": ..., "y": ..., "z": ...}}
// (modes by axis, then ascending frequency; only modelled axes; 0 for an unmodelled
// driven axis). A coupled machine lists all three axes, each mode's share of the static
// deflection vector under that axis' acceleration, and |C e_a| as the axis' static
// deflection (model/coupled_modes.h, AnalyzeCoupledAxis).
nlohmann::ordered_json ModesJson(const std::vector<model::AxisModes>& axes, int driven_axis);

// A coupled machine's cross terms (model/coupled_modes.h), after the table above: the
// static compliance matrix C (m per m/s^2; row b the deflection along b, column a the
// acceleration along a) and each mode's participation and shape, in the machine's order.
// Nothing for an uncoupled machine.
void PrintModesCoupling(std::ostream& out, const model::MultiAxisMachineConfig& machine);
// Adds to ModesJson's object, for a coupled machine only:
//   "static_compliance_m_per_m_s2": [[C_xx, C_xy, C_xz], [C_yx, ...], [C_zx, ...]],
//   "coupling": [{"mode": 1, "frequency_hz", "damping_ratio",
//                 "participation": {"x", "y", "z"}, "shape": {"x", "y", "z"}}, ...],
//   "modal_file": the FE export's path, when the modes came from one.
void AddModesCouplingJson(const model::MultiAxisMachineConfig& machine, nlohmann::ordered_json* json);

// One axis without axis names (the original single-axis shape).
void PrintModesTable(std::ostream& out, const model::ModalAnalysis& analysis);
nlohmann::ordered_json ModesJson(const model::ModalAnalysis& analysis);

}  // namespace shapebench::bench
