// The `machine:` mapping: the modal form (`modes`) or the lumped
// mass-spring-damper form (`bodies`, `elements`, ...) for one axis, or the multi-axis form
// `axes: {x: FORM, y: FORM, z: FORM}`. Physical checks are left to validate().
#pragma once

#include "bench/config/node_reader.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

// Either
//   (a) a single form (`modes:` or `bodies:` ...) with an optional `axis: x|y|z` (default
//       y): that axis gets the model and is the driven axis (single_form = true), or
//   (b) `axes:` mapping any of x, y, z to a single form (without `axis`), with an optional
//       `driven_axis: x|y|z` (default y). An axis left out is rigid (`axes: {}`: a rigid
//       machine).
// Errors carry the key paths of the YAML (machine.axes.x.bodies[1].mass_kg).
model::MultiAxisMachineConfig ReadMachineAxes(const NodeReader& machine);

// The model of the driven axis of either form above (the single-axis view kept for
// callers that simulate one axis); an error when that axis has no model.
model::MachineConfig ReadMachine(const NodeReader& machine);

}  // namespace shapebench::bench
