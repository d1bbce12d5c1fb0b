// What `shapebench design SCENARIO.yaml` writes (bench/cli/design_command.cc,
// docs/design.md): the synthesised pattern (controller/pattern_design.h), its bands and the
// worst V over each, the registry's shapers and the patent's methods held to the same
// specification, the table or JSON, the scenario fragment any command takes, and with --out
// design.json, design.yaml (design_impulses.yaml for a table longer than max_table_length)
// and design.png (V over each band).
#pragma once

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/run/design_validation.h"
#include "controller/design_comparison.h"
#include "controller/impulse.h"
#include "controller/pattern_design.h"

namespace shapebench::bench {

enum class DesignForm { kProfileTable, kImpulses };

struct DesignReport {
  std::string file;
  DesignForm form = DesignForm::kProfileTable;
  controller::DesignSpec spec;
  std::vector<int> modes;                  // the participating mode of each band
  std::vector<double> mode_frequency_hz;   // that mode's frequency and damping
  std::vector<double> mode_damping_ratio;
  std::string axes;                        // the moved axes, "y"
  int max_table_length = 64;               // the scenario's controller.post_interp's
  controller::DesignResult result;
  std::vector<controller::ShaperAgainstSpec> registry;
  std::vector<BandValidation> validation;  // --validate: one per band
  // The motion time added to the scenario's move or program over no shaping (NaN when it
  // cannot be planned): the design's, each registry entry's.
  double added_motion_time_s = NAN;
  std::vector<double> registry_added_time_s;
  bool table_too_long() const {
    return form == DesignForm::kProfileTable &&
           static_cast<int>(result.coefficients.size()) > max_table_length;
  }
};

// The pattern as impulses: the non-zero coefficients, and the last grid point (its time
// is the reference of V) even when zero.
std::vector<controller::Impulse> DesignImpulses(const controller::DesignResult& result);

void PrintDesignReport(std::ostream& out, const DesignReport& report);

// {"file", "form", "grid_s", "duration_s", "mean_time_s", "coefficients" (profile_table) or
// "impulses": [{time_s, amplitude}], "tolerance", "margin", "polygon_sides",
// "guaranteed_v", "derivatives", "bands": [{mode, frequency_lo_hz, frequency_hi_hz,
// damping_lo, damping_hi, worst_v}], "lp_solves", "secondary_objective", "table_too_long",
// "added_motion_time_s", "registry": [{method, duration_s, added_motion_time_s, meets,
// worst_v}], with --validate "validation": [{mode, worst_residual_ratio, at_hz, at_damping,
// worst_peak_ratio, runs}]}
nlohmann::ordered_json DesignJson(const DesignReport& report);

// The scenario fragment: a `custom` pattern's impulses, or `post_interp: {type:
// profile_table, table}` with the pattern off.
std::string DesignFragment(const DesignReport& report, DesignForm form);

// --out DIR: the files written, in order.
std::vector<std::string> WriteDesignOutputs(const std::string& out_dir, const DesignReport& report);

}  // namespace shapebench::bench
