// The `controller:` and `move:` mappings. Physical checks are left to
// ControllerConfig::validate() and MoveConfig::validate().
#pragma once

#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "controller/controller.h"

namespace shapebench::bench {

controller::ControllerConfig ReadController(const NodeReader& controller);
// One `pattern:` mapping (controller.pattern, or a shaper of a sensitivity file, which
// allows `extra_keys` beside the pattern's, read by the caller).
controller::PatternConfig ReadPattern(const NodeReader& pattern,
                                      const std::vector<std::string>& extra_keys = {});
controller::MoveConfig ReadMove(const NodeReader& move);

}  // namespace shapebench::bench
