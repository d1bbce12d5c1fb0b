// The exit codes every command shares (docs/reliability.md): 0 ok, 1 a check failed, 2 bad
// input (file, line, key, what is allowed), 3 the solver failed (the CVODE flag in words).
#pragma once

namespace shapebench {

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

}  // namespace shapebench
