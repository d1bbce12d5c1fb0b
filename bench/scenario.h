// A scenario: everything one run needs (SPEC section 3), already validated.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "controller/controller.h"
#include "model/drive.h"
#include "model/integrator.h"
#include "model/machine.h"

namespace shapebench::bench {

// A bound on one metric (SPEC section 4 names), e.g. peak_ratio: {max: 1.01}.
struct Check {
  std::string metric;
  std::optional<double> min;
  std::optional<double> max;
};

struct Scenario {
  model::MachineConfig machine;
  model::DriveConfig drive;
  controller::ControllerConfig controller;
  controller::MoveConfig move;
  model::IntegratorConfig integrator;
  std::vector<Check> checks;
  std::string name;         // the file's stem, for reports
  std::string source_file;  // as given on the command line
};

}  // namespace shapebench::bench
