// What `shapebench design` (bench/cli/design_command.cc) and Python's shapebench.design ask
// for, turned into its report (bench/output/design_report.h): the scenario loaded, a band per
// participating mode of its moved axes (or per mode named), the spec validated, the pattern
// designed, the registry compared, --validate's runs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bench/output/design_report.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

struct DesignRequest {
  std::string file;
  std::vector<std::string> sets;      // --set KEY=VALUE
  std::vector<std::string> bands;     // --band MODE=LO:HI (Hz)
  std::vector<std::string> dampings;  // --damping MODE=LO:HI
  double tolerance = 0.05;
  int derivatives = 0;
  std::string form = "profile_table";  // or "impulses"
  std::optional<double> grid_s;        // impulses only; default 0.1 ms
  std::optional<double> margin;        // default tolerance / 5, at least 0.001
  bool registry = true;
  bool validate = false;
};

// The report before the design: the scenario (into `loaded`), the bands and the spec,
// validated. Throws ValidationError naming the option (--band, --tolerance, ...), or the
// scenario's errors (ConfigError).
DesignReport PrepareDesign(const DesignRequest& request, Scenario* loaded);

// PrepareDesign, then the design (controller::DesignError propagates: exit 3), the registry,
// the motion time each adds (FinishDesign) and --validate's runs as asked.
DesignReport ComputeDesign(const DesignRequest& request);

// After the design: the registry (when asked) and the motion time the design and each
// registry entry add to the scenario's move or program.
void FinishDesign(const DesignRequest& request, const Scenario& scenario, DesignReport* report);

}  // namespace shapebench::bench
