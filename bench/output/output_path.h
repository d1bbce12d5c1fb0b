// Output paths checked before anything is loaded or run: a bad --out, --junit or --report
// would otherwise be found only after the simulation (or after every point of a sweep).
#pragma once

#include <string>

namespace shapebench::bench {

// Throws std::runtime_error "OPTION PATH: cannot write there: CAUSE" unless `path` is an
// existing writable directory or can be created (its nearest existing ancestor is a
// writable directory). Writability is probed by creating and removing a temporary
// directory, so the check leaves nothing behind and sees what the OS would do.
void RequireWritableOutputDir(const std::string& option, const std::string& path);

// The same for an output file (--junit, --report): not an existing directory, and its
// parent directory exists and is writable (probed the same way); or an existing device
// or FIFO (/dev/stdout) this process may write to.
void RequireWritableOutputFile(const std::string& option, const std::string& path);

}  // namespace shapebench::bench
