// The part program of a scenario: `program:` (a YAML list of blocks) or `program_file:`
// (a G-code file). Both go through controller::ProgramBuilder, whose header documents the
// words and the modal state; every error becomes a ConfigError.
//
// `program:` entries are mappings with the keys g x y z i j k r f p q n, one per word:
//   program:
//     - {g: [90, 1], x: 100, y: 0, f: 6000}   # g: one integer or a list of integers
//     - {g: 2, x: 150, y: 50, r: 50}
//     - {g: 4, p: 500}
// Values are plain numbers in the G-code units (mm, mm/min, P per program_dialect); g is
// a number (91.1), n an integer. An empty entry `{}` does nothing. Errors: "FILE:LINE:COL: program[3].r: ..."
// at the offending value (a g list element: program[3].g[1]), or at the entry
// (program[3]) when the block as a whole is wrong. ProgramBlock::source_line is the
// entry's 0-based index.
//
// `program_file:` is resolved relative to the scenario file's directory (absolute paths
// are kept). Errors inside the file: "GCODE_FILE:LINE:COL: program_file: ...", located
// in the G-code file; a missing or unreadable file is reported at the `program_file:`
// value, naming the resolved path. The words the bench does not model (O, T, S, M, G43 H,
// G54...) are dropped with one warning per program, or refused under the scenario's
// `program_strict: true` (controller/gcode_parser.h).
#pragma once

#include <string>

#include <Eigen/Dense>

#include "bench/config/node_reader.h"
#include "controller/gcode_parser.h"
#include "controller/program.h"

namespace shapebench::bench {

controller::Program ReadProgramList(const NodeReader& program,
                                    const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero(),
                                    const controller::ProgramOptions& options = {});

// The scenario's program settings (the keys beside `program`/`program_file`):
//   program_strict: true|false         refuse the words otherwise dropped (files only)
//   program_dialect: fanuc|linuxcnc|grbl   how the words read (docs/gcode.md), default fanuc
//   program_arc_tolerance: {absolute_mm, relative, max_mm}   when an arc's end is on its
//                                      circle (controller/gcode_dialect.h); default: the
//                                      dialect's
//   program_max_iterations: N         loop passes, calls and M99 jumps (default 1000000)
//   machine.reference_mm: {g28: {x, y, z}, g30: {x, y, z}}   G28/G30's positions, mm
controller::GcodeOptions ReadProgramOptions(const NodeReader& top);

// The G-code file `program_file` names (bench/config/input_path.h: from the scenario's
// folder, or from the current directory when a --set gives it). `limits` stops the parse
// at the block that crosses them; `options.strict` refuses the
// words the parser would drop with a warning (ParseGcode).
controller::Program ReadProgramFile(const NodeReader& program_file,
                                    const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero(),
                                    const controller::GcodeLimits& limits = {},
                                    const controller::GcodeOptions& options = {});

}  // namespace shapebench::bench
