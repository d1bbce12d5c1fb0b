// The one rule for relative paths in the input (machine:, program_file:, modal_file:,
// frf_file:, machine.fmu:, a sweep's path values): a path written in a file is relative to that file's
// folder; a path given on the command line (a --set value) to the current directory.
#pragma once

#include <string>

#include "bench/config/node_reader.h"

namespace shapebench::bench {

// The file `node` names, resolved by the rule above (lexically normal; absolute paths as
// given).
std::string ResolvedInputPath(const NodeReader& node);

// `reference` resolved against the folder of `file` ("" for the current directory).
std::string ResolvedFrom(const std::string& file, const std::string& reference);

// Whether the key path names a file (its last key is one of the keys above; `machine`
// at the top level only).
bool IsPathKey(const std::string& key_path);

}  // namespace shapebench::bench
