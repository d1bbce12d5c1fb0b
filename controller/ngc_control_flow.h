// LinuxCNC's O-word control flow and parameters for ProgramExpander
// (controller/subprogram_expander.h describes what runs). Internal to the program reading.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "controller/gcode_dialect.h"
#include "controller/program_words.h"
#include "controller/rs274_expression.h"
#include "controller/source_line.h"

namespace shapebench::controller {

class NgcControlFlow {
 public:
  // Whether `lines` use O-word control flow or parameters.
  static bool Needed(const std::vector<std::string>& lines);

  // Pairs every O-word with its partner (sub/endsub, if/.../endif, while/endwhile,
  // do/while, repeat/endrepeat); throws ProgramError for an unmatched one.
  NgcControlFlow(const std::vector<std::string>& lines, const ProgramOptions& options);

  bool Next(SourceLine* line);

 private:
  enum class Kind {
    kNone, kSub, kEndsub, kCall, kReturn, kIf, kElseif, kElse, kEndif, kWhile, kEndwhile,
    kDo, kDoWhile, kRepeat, kEndrepeat, kBreak, kContinue
  };
  struct Control {
    Kind kind = Kind::kNone;
    std::string label;     // "100" or "<name>"
    std::string keyword;   // as read, lower case
    std::size_t arguments = 0;  // where the text after the keyword starts
    int column = 0;        // of the 'o'
  };
  static Control ParseControl(const std::string& text);
  void Pair();
  void PairEnd(std::size_t i, std::vector<std::size_t>* open);
  void Execute(std::size_t i);
  void Branch(std::size_t i);
  void Call(std::size_t i);
  void Return(std::size_t i);
  void Repeat(std::size_t i);
  void EndRepeat(std::size_t i);
  bool Condition(std::size_t i);
  void Count(std::size_t i);
  ProgramError Error(std::size_t i, const std::string& message) const;
  std::string Shown(std::size_t i) const;

  const std::vector<std::string>& lines_;
  ProgramOptions options_;
  std::vector<Control> controls_;
  std::map<std::size_t, std::size_t> match_;      // the partner of each paired O-word
  std::map<std::size_t, std::size_t> next_branch_;  // if/elseif -> the next branch or endif
  std::map<std::size_t, std::size_t> endif_of_;   // if/elseif/else -> endif
  std::map<std::size_t, std::size_t> loop_of_;    // break/continue -> the loop's first line
  std::map<std::string, std::size_t> subs_;       // label -> its sub line
  Rs274Parameters parameters_;
  struct Frame {
    std::size_t return_pc;
    int line;
  };
  std::vector<Frame> calls_;
  std::map<std::pair<std::size_t, std::size_t>, long> repeats_;  // (depth, line) -> left
  std::size_t pc_ = 0;
  long iterations_ = 0;
};

}  // namespace shapebench::controller
