// The `machine:` mapping (SPEC section 3): the modal form (`modes`) or the lumped
// mass-spring-damper form (`bodies`, `elements`, ...). Physical checks are left to
// MachineConfig::validate().
#pragma once

#include "bench/node_reader.h"
#include "model/machine.h"

namespace shapebench::bench {

model::MachineConfig ReadMachine(const NodeReader& machine);

}  // namespace shapebench::bench
