// G-code in one of three dialects (GcodeOptions::program, controller/gcode_dialect.h) ->
// Program: ProgramExpander (controller/subprogram_expander.h) runs subprograms, O-words and
// parameters and hands over the blocks in execution order; ProgramBuilder documents the
// words and their modal behaviour. docs/gcode.md lists it all.
//
// Lexical rules:
//   - One block per line (LF or CRLF). Blank lines and lines holding only comments are
//     skipped.
//   - Comments: `( ... )` within a line (not nested; an unclosed `(` is an error) and `;`
//     to the end of the line.
//   - `%` alone on a line (comments may follow) may open the program before its first
//     block and close it after its last; after the closing `%` only blank lines and
//     comments may follow. `%` anywhere else is an error.
//   - A word is a letter (case-insensitive) and a number. Spaces between words are
//     optional (`G1X10Y-5.5F600`); spaces and tabs between the letter and its number are
//     allowed (`X 10`, `X -5`), not inside the number.
//   - Numbers: optional sign, digits with at most one decimal point (`10`, `-5.5`, `.5`,
//     `5.`); no exponent. G takes an unsigned number (`G01` is G1, `G91.1`); N an unsigned
//     integer.
//   - Part-program words outside the motion (controller/program_builder.h lists the modelled
//     ones) are read and dropped, with ONE warning per program that lists each distinct
//     word with its first line (Program::warnings): O (program number), T (tool), S
//     (spindle speed), H and D (offset numbers), M (spindle, coolant, tool change, end:
//     M3 M4 M5 M6 M8 M9 M30 and any other), G43/G44 (tool-length offset) and G54-G59
//     (work offsets). The bench has no tool or offset table, so the offsets do not move
//     the commanded path. G40, G49, G80 and G94 select the state the bench models (no
//     cutter compensation, no length offset, no canned cycle, feed per minute) and are
//     accepted without a warning. GcodeOptions::strict refuses every dropped word.
//   - Words that would change the motion the bench does not model are refused: G41/G42
//     (cutter compensation), G95/G96 (feed per revolution, constant surface speed),
//     canned cycles (G73, G74, G76, G81-G89), G53 (machine coordinates), M98/M99 outside
//     the fanuc dialect, polar coordinates (`@`, `^`), `#`/`[` and O-word control flow
//     outside the linuxcnc dialect (each message says which dialect reads it), and any
//     block after M2/M30 (the program end).
//   - Columns are 1-based characters (a tab counts as one). Every error about a word,
//     including a malformed number, points at the word's letter; an unclosed comment at
//     its `(`; a stray character at itself.
#pragma once

#include <cstddef>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "controller/gcode_dialect.h"
#include "controller/program.h"
#include "controller/program_builder.h"

namespace shapebench::controller {

// Bounds checked while parsing, so that a huge file is refused at the block that crosses
// them instead of after the whole program is built (docs/reliability.md, guard rails).
// `*_key` names the limit in the message (the caller's configuration key).
struct GcodeLimits {
  std::size_t max_blocks = std::numeric_limits<std::size_t>::max();
  std::string max_blocks_key;
  // The path's time at its programmed feeds (each block's chord over its feed, a lower
  // bound of an arc's) plus the dwells, in s.
  double max_path_s = std::numeric_limits<double>::infinity();
  std::string max_path_key;
  double default_feed_m_s = 0.0;  // blocks before the first F word
  double rapid_feed_m_s = 0.0;    // G0
};

// How strictly the part-program words outside the motion are read.
struct GcodeOptions {
  // Refuse the words that would otherwise be dropped with a warning (O, T, S, H, D, M,
  // G43, G44, G54-G59), each at its line and column.
  bool strict = false;
  std::string strict_key = "strict";  // names the setting in the message
  ProgramOptions program;              // the dialect and its settings (gcode_dialect.h)
};

// Throws ProgramError with the 1-based line and column of what is wrong.
Program ParseGcode(const std::string& text,
                   const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero(),
                   const GcodeLimits& limits = {}, const GcodeOptions& options = {});

}  // namespace shapebench::controller
