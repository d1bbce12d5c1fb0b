// G2/G3 blocks for ProgramBuilder: the centre from I/J/K (incremental, or absolute under
// G90.1) or R, and the check that the end lies on the circle (the dialect's rule,
// gcode_dialect.h). Internal to the controller's program reading.
#pragma once

#include <string>

#include "controller/block_words.h"
#include "controller/gcode_dialect.h"
#include "controller/program.h"

namespace shapebench::controller {

struct ArcContext {
  double unit_m = 1e-3;          // one input unit (mm, or inch under G20), m
  bool absolute_centre = false;  // G90.1
  ArcTolerance tolerance;
  std::string tolerance_key;     // names the setting in messages
};

// A G2/G3 block: its centre (and, for a full circle, its end set to the start exactly).
// False for a block that only makes G2/G3 modal.
bool CompleteArc(const BlockWords& words, const ArcContext& context, ProgramBlock* arc);

std::string MotionName(MotionKind motion);  // "G0" ... "G3"

}  // namespace shapebench::controller
