// Applies blocks of address words (letter + number) with the modal state of a Fanuc-style
// control and collects the resulting ProgramBlocks. Both part-program readers use it: the
// G-code parser (controller/gcode_parser.h) and the YAML `program:` list
// (bench/scenario/program_reader.h). Units at this boundary are the programmer's: coordinates,
// I/J/K and R in mm, F in mm/min, P in ms, G4's X in s; the Program is SI.
//
// Words and modal groups:
//   G0 G1 G2 G3   motion (modal). Power-up state: G1, so a block with coordinates only and
//                 no motion G ever programmed is a linear move (Fanuc parameter G01 = 1).
//   G4            dwell, one shot: P in milliseconds, or X in seconds; >= 0; exactly one of
//                 them. A G4 block takes no other motion word (no G0-G3, Y, Z, I, J, K, R);
//                 the modal words (F, G17-G19, G21, G90, G91, N) may share it.
//   G17 G18 G19   plane XY (power-up), ZX, YZ (modal).
//   G90 G91       absolute (power-up) / incremental X Y Z (modal).
//   G21           mm input, accepted and without effect; G20 (inch) is an error.
//   F             feed, mm/min, > 0 (modal; NaN in the blocks until the first F).
//   X Y Z         end point, absolute or incremental per G90/G91.
//   I J K         arc centre offsets from the start point, always incremental; only the two
//                 of the active plane (G17: I J, G18: K I, G19: J K).
//   R             arc radius: R > 0 the arc of at most 180 degrees, R < 0 the longer one.
//   N             sequence number, ignored (accepted anywhere in the block).
// Every word at most once per block; at most one word of each G group.
//
// Decisions:
//   - A block without motion (only N, F or modal G words; G2/G3 without end point or
//     centre) produces no ProgramBlock; neither does a G0/G1 block whose end equals its
//     start.
//   - An arc needs I/J/K or R (not both). Its end and start coincide (within 1e-6 mm in the
//     plane; the end is then set to the start exactly) for a full circle, which only
//     I/J/K can describe. The start and end radii must agree within 1e-3 mm (1 um, the
//     least input increment) or 1e-6 of the radius, whichever is larger (i.e. radii above
//     1 m get the relative bound); the programmed end point is kept as written.
//   - R shorter than half the chord by more than that tolerance is an error; within it, the
//     centre is the chord's midpoint.
//   - Numbers are taken as written in mm (Fanuc decimal-point input with "calculator-type"
//     input: X10 is 10 mm).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "controller/program.h"

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

class ProgramBuilder {
 public:
  explicit ProgramBuilder(const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero());

  // Applies one block; throws ProgramError (the builder's state is then unspecified).
  void Apply(const Block& block);

  const Program& program() const { return program_; }
  Program TakeProgram() { return std::move(program_); }

  // The modal state after the blocks applied so far.
  const Eigen::Vector3d& position_m() const { return position_m_; }
  MotionKind motion() const { return motion_; }
  Plane plane() const { return plane_; }
  bool incremental() const { return incremental_; }
  double feed_m_s() const { return feed_m_s_; }

 private:
  Program program_;
  Eigen::Vector3d position_m_;
  MotionKind motion_ = MotionKind::kLinear;
  Plane plane_ = Plane::kXY;
  bool incremental_ = false;
  double feed_m_s_ = NAN;
};

// The words the builder accepts, for "allowed: ..." in messages.
extern const char* const kSupportedWords;

}  // namespace shapebench::controller
