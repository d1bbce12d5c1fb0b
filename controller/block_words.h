// One block's words, each checked on its own (a finite number; a letter or G code of the
// dialect) and indexed by where it sits, for ProgramBuilder and its arc and reference-return
// helpers. Internal to the controller's program reading.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "controller/gcode_dialect.h"
#include "controller/program.h"
#include "controller/program_words.h"

namespace shapebench::controller {

// Indices are into Block::words, -1 when absent: letters other than G by letter, G words
// by modal group. Throws ProgramError for a second word of a letter or G group.
class BlockWords {
 public:
  BlockWords(const Block& block, Dialect dialect);

  int at(char letter) const { return at_[static_cast<std::size_t>(letter - 'A')]; }
  double value(int i) const { return words_[static_cast<std::size_t>(i)].value; }
  int code(int i) const { return codes_[static_cast<std::size_t>(i)]; }  // G word, in tenths
  int motion_word() const { return motion_word_; }      // G0-G3
  int nonmodal_word() const { return nonmodal_word_; }  // G4, G28, G30
  int plane_word() const { return plane_word_; }        // G17-G19
  int distance_word() const { return distance_word_; }  // G90, G91
  int arc_distance_word() const { return arc_distance_word_; }  // G90.1, G91.1
  int units_word() const { return units_word_; }        // G20, G21
  int path_mode_word() const { return path_mode_word_; }  // G61, G61.1, G64
  Dialect dialect() const { return dialect_; }

  bool HasAxisWord() const;     // any of X, Y, Z
  int FirstCentreWord() const;  // the first of I/J/K in the block
  // Whether the word was written with a decimal point (P0.5, not P500).
  bool HasDecimalPoint(int i) const;

  // As written ("G01"), or letter and value when there is no text.
  std::string Shown(int i) const;
  ProgramError WordError(int i, const std::string& message) const;
  ProgramError BlockError(const std::string& message) const;

 private:
  void IndexGWord(int i);
  void IndexAddressWord(int i);
  void TakeGroup(int* slot, int i, const std::string& rule);
  ProgramError Unsupported(int i) const;

  const std::vector<Word>& words_;
  int line_;
  Dialect dialect_;
  std::array<int, 26> at_;
  int motion_word_ = -1, nonmodal_word_ = -1, plane_word_ = -1, distance_word_ = -1,
      arc_distance_word_ = -1, units_word_ = -1, path_mode_word_ = -1;
  std::vector<int> codes_;  // the G code of each G word in tenths, -1 for the others
};

constexpr char kAxisLetters[] = "XYZ";
constexpr char kCentreLetters[] = "IJK";

}  // namespace shapebench::controller
