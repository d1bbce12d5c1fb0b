// One line of a part program as the parser reads it, after the subprogram expander
// (controller/subprogram_expander.h) ran its control flow and parameters.
#pragma once

#include <string>

namespace shapebench::controller {

inline constexpr int kMaxCallDepth = 10;  // LinuxCNC's and Fanuc's nesting limits

// The blanks between words of a program line (spaces, tabs, a DOS line end's '\r').
inline bool IsLineBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

struct SourceLine {
  int line = 0;  // 1-based, in the file
  std::string text;
};

}  // namespace shapebench::controller
