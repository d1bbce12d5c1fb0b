// Runs a part program's control flow and hands the parser its blocks in execution order,
// one source line at a time (ParseGcode pulls them, so its limits stop a long expansion
// early):
//   fanuc     M98 P<n> [L<count>] calls the subprogram O<n> of the same file (P with more
//             than four digits packs the count: P30010 is O0010 three times; L0 skips the
//             call); M99 returns from it, or in the main program jumps back to its start.
//             An O number at the top of the file names the main program; an O block that
//             M98 calls and that ends with M99 is a subprogram, skipped after M2/M30.
//   linuxcnc  RS274NGC parameters and expressions (controller/rs274_expression.h) and the
//             O-words sub/endsub/call/return, if/elseif/else/endif, while/endwhile,
//             do/while, repeat/endrepeat, break, continue (numbered o100 or named o<name>).
//   grbl      plain blocks; M98/M99, '#' and O-words are refused by the parser.
// Loops, calls and M99 jumps together are bounded by ProgramOptions::max_iterations (a
// program that never ends is refused at the line that crosses it); calls nest at most
// kMaxCallDepth deep.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controller/gcode_dialect.h"
#include "controller/source_line.h"

namespace shapebench::controller {

class ProgramExpander {
 public:
  // `text` must outlive the expander.
  ProgramExpander(const std::string& text, const ProgramOptions& options);
  ~ProgramExpander();

  // The next line to parse; false after the last. Throws ProgramError.
  bool Next(SourceLine* line);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace shapebench::controller
