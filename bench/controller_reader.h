// The `controller:` and `move:` mappings (SPEC section 3). Physical checks are left to
// ControllerConfig::validate() and MoveConfig::validate().
#pragma once

#include "bench/node_reader.h"
#include "controller/controller.h"

namespace shapebench::bench {

controller::ControllerConfig ReadController(const NodeReader& controller);
controller::MoveConfig ReadMove(const NodeReader& move);

}  // namespace shapebench::bench
