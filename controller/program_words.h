// The part program's address words and blocks, and the error that locates what is wrong
// in them: shared by the readers (controller/gcode_parser.h, the YAML `program:` list),
// ProgramBuilder and the subprogram expander.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace shapebench::controller {

// One address word: is {'X', -5.5}.
struct Word {
  char letter = 0;     // upper case
  double value = 0.0;  // as written: mm, mm/min, ms or s
  int column = 0;      // 1-based column of the letter in its G-code line; 0 if not from text
  std::string text;    // as written ("G01", "X-5.5") for messages; empty: letter + value
};

struct Block {
  std::vector<Word> words;
  int source_line = 0;  // copied to ProgramBlock::source_line and ProgramError::line
};

// The highest feed a program or a controller setting may ask for, mm/min (1 km/min,
// several times the fastest machine tools): the planner's arithmetic (the cruise as the
// distance less v^2/a) loses the move's length to rounding far above it (F1e20 ran a 10 mm
// move 264 mm off its path, F1e30 asked for terabytes:
// fuzz/regressions/gcode/feed_1e30_planner_allocates_terabytes.nc).
inline constexpr double kMaxFeedMmMin = 1.0e6;

// A part-program error: what is wrong and what is allowed, at a line and column.
class ProgramError : public std::runtime_error {
 public:
  // word_index: the offending word's index in Block::words, -1 when the error concerns
  // the block (or a line) as a whole. column: 1-based; 0 when there is none.
  ProgramError(int line, int column, int word_index, std::string message);

  int line() const { return line_; }
  int column() const { return column_; }
  int word_index() const { return word_index_; }
  const std::string& message() const { return message_; }  // without the position

 private:
  int line_;
  int column_;
  int word_index_;
  std::string message_;
};

}  // namespace shapebench::controller
