// Sweep points that change only numbers of the machine's structure (the natural-period
// sweep, robustness grids over damping, gain, mass, stiffness): set on a scenario loaded
// once, instead of reading the YAML again for every point (reading it was half of
// a point's time). The result is the scenario LoadScenario reads for the point, field for
// field: the same number text read by the same rule (IsNumberText, then strtod), and the
// same checks of the machine (MachineChecksPass). tests/bench/structure_numbers_test.cc
// compares the two.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bench/config/override.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

// True when `key_path` names one of these numbers (AXIS one of x, y, z, i an index):
//   machine[.axes.AXIS].modes[i].frequency_hz | damping_ratio | gain
//   machine.modes[i].participation.x | y | z, machine.modes[i].shape.x | y | z (coupled)
//   machine[.axes.AXIS].bodies[i].mass_kg
//   machine[.axes.AXIS].elements[i].stiffness_n_m | damping_n_s_m
//   machine[.axes.AXIS].damping.modal[i]
//   machine[.axes.AXIS].damping.rayleigh.alpha | beta
// A `damping:` number is set only where the axis already has that block (modal, rayleigh)
// and, for modal, the entry; a participation or shape component only where the mode has
// it, a gain only where it has neither, and no number of modes read from a modal_file;
// otherwise the point is loaded from its sources.
bool IsStructureNumberKey(const std::string& key_path);

// Sets each of `values` (IsStructureNumberKey keys) on `scenario`. False, with `scenario`
// in an unspecified state, when a key does not fit its machine (the other form, an index
// out of range, an axis without a model), a value is not a plain decimal number or is out
// of range, or the changed machine fails MachineChecksPass: the caller then loads the
// point from its sources, which gives the located error.
// `motion_s`: MinimumMotionSeconds of the scenario, when the caller knows it (the numbers
// of the structure do not change it).
bool SetStructureNumbers(Scenario* scenario, const std::vector<Override>& values,
                         std::optional<double> motion_s = std::nullopt);

}  // namespace shapebench::bench
