// An FE modal export as a machine (`machine: {modal_file: FILE.csv}`): mass-normalised
// modes with their participation and shape along x, y, z, read as the coupled modes of
// the single `modes:` form (model/coupled_modes.h). The CSV:
//
//   mode,frequency_hz,damping_ratio,participation_x,participation_y,participation_z,shape_x,shape_y,shape_z
//   -,Hz,1,sqrt(kg),sqrt(kg),sqrt(kg),1/sqrt(kg),1/sqrt(kg),1/sqrt(kg)
//   1,25.0,0.03,0,38.5,0,0,0.0311,0
//
// The first row names the columns (each of the nine once, in any order), the second their
// units (mode: `-` or empty); then one row per mode, at least one, at most
// kMaxModelEntries. shape is phi at the tool point relative to the workpiece (1/sqrt(kg)),
// participation Gamma = phi^T M r per unit base acceleration along the axis (sqrt(kg)):
// their product is dimensionless, the `gain` of a one-axis mode. mode is a positive
// integer, each once; frequency_hz > 0; damping_ratio in [0, 1). Lines whose first
// non-blank character is `#` and blank lines are skipped; spaces around a field and CR
// line ends are ignored; numbers are plain decimals (no inf, nan, hex). Anything else is a
// ConfigError at FILE:LINE:COLUMN naming the column and what is allowed (exit 2).
#pragma once

#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "model/machine.h"

namespace shapebench::bench {

// The modes of `text`, the contents of `file` (the name errors carry).
std::vector<model::ModalMode> ParseModalFile(const std::string& text, const std::string& file);

// `modal_file:`'s value, resolved relative to the YAML file that gives it (absolute paths
// kept; a --set value relative to the file of the mapping it sets), read and parsed: the
// modal form with `modal_file` set to the resolved path. A file that cannot be read is an
// error at the key, naming the resolved path.
model::ModalMachineConfig ReadModalFile(const NodeReader& modal_file);

}  // namespace shapebench::bench
