// The `pattern` command's report: the shaping pattern as the patent's para. 49
// parameters, as jerk impulses in continuous time, as the profile table on the
// interpolation-period grid that the controller actually uses, and the residual
// vibration each leaves at the design frequency.
#pragma once

#include <ostream>

#include "controller/controller.h"

namespace shapebench::bench {

void PrintPatternReport(std::ostream& out, const controller::ControllerConfig& controller);

}  // namespace shapebench::bench
