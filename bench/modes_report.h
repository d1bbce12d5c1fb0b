// The `modes` command's report: natural frequencies, damping ratios and static
// participation of the machine model (SPEC section 2).
#pragma once

#include <ostream>

#include <nlohmann/json.hpp>

#include "model/machine.h"

namespace shapebench::bench {

void PrintModesTable(std::ostream& out, const model::ModalAnalysis& analysis);

// Exactly {"modes": [{"frequency_hz", "damping_ratio", "participation"}, ...],
//          "static_deflection_per_accel_s2": ...}.
nlohmann::ordered_json ModesJson(const model::ModalAnalysis& analysis);

}  // namespace shapebench::bench
