#include "controller/gcode_parser.h"

#include "controller/source_line.h"
#include "controller/subprogram_expander.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <vector>

namespace shapebench::controller {
namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

bool IsNumberChar(char c) { return IsDigit(c) || c == '.' || c == '+' || c == '-'; }

// [+-]? (digits [. digits?] | . digits)
bool IsDecimal(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < text.size() && IsDigit(text[i])) ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && IsDigit(text[i])) ++i, ++digits;
  }
  return i == text.size() && digits > 0;
}

bool IsUnsignedInteger(const std::string& text) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (!IsDigit(c)) return false;
  }
  return true;
}

std::string Quoted(char c) {
  if (std::isprint(static_cast<unsigned char>(c))) return "'" + std::string(1, c) + "'";
  return "character code " + std::to_string(static_cast<unsigned char>(c));
}

// After an O number at `pos`: a LinuxCNC O-word keyword (o100 sub, o101 while [...]).
bool IsOWordControl(const std::string& line, std::size_t pos) {
  while (pos < line.size() && IsLineBlank(line[pos])) ++pos;
  if (pos < line.size() && line[pos] == '<') {  // a named O-word: o<name> sub
    const std::size_t close = line.find('>', pos);
    if (close == std::string::npos) return false;
    pos = close + 1;
    while (pos < line.size() && IsLineBlank(line[pos])) ++pos;
  }
  std::string keyword;
  while (pos < line.size() && std::isalpha(static_cast<unsigned char>(line[pos]))) {
    keyword += static_cast<char>(std::tolower(static_cast<unsigned char>(line[pos++])));
  }
  for (const char* control : {"sub", "endsub", "call", "return", "if", "elseif", "else",
                              "endif", "while", "endwhile", "do", "repeat", "endrepeat",
                              "break", "continue"}) {
    if (keyword == control) return true;
  }
  return false;
}

constexpr const char* kWordExample = "a word is a letter and a number, e.g. X-5.5";

struct ScannedLine {
  std::vector<Word> words;
  int percent_column = 0;  // 1-based column of a `%`, 0 if none
};

ProgramError ErrorAt(int line_number, std::size_t pos, const std::string& message) {
  return ProgramError(line_number, static_cast<int>(pos) + 1, -1, message);
}

// A character that starts no word: what it is, when another controller's syntax.
ProgramError ForeignCharacter(char c, std::size_t pos, int line_number, Dialect dialect) {
  if (c == '@' || c == '^') {
    return ErrorAt(line_number, pos, std::string("'") + c + "' (polar coordinates, LinuxCNC) is "
                   "not read by the bench in any dialect; program X and Y");
  }
  if (c == '#' || c == '[') {
    return ErrorAt(line_number, pos, std::string("'") + c + "' (an RS274NGC parameter or "
                   "expression) is LinuxCNC's; the " + DialectName(dialect) + " dialect does "
                   "not read it; allowed: program_dialect: linuxcnc");
  }
  return ErrorAt(line_number, pos, "unexpected character " + Quoted(c) +
                                       "; a block is words (a letter and a number, e.g. X10) "
                                       "with comments in ( ) or after ;");
}

// Checks a word's number as its letter takes it (N an integer, G unsigned).
void CheckNumber(char letter, const std::string& number, std::size_t letter_pos, int line_number) {
  const std::string text = std::string(1, letter) + number;
  if (letter == 'N' && !IsUnsignedInteger(number)) {
    throw ErrorAt(line_number, letter_pos, "malformed number '" + text + "': N takes an unsigned "
                                           "integer, e.g. N10");
  }
  if (letter == 'G' && (!IsDecimal(number) || number[0] == '-' || number[0] == '+')) {
    throw ErrorAt(line_number, letter_pos, "malformed number '" + text + "': G takes an unsigned "
                                           "number, e.g. G1, G91.1");
  }
  if (letter != 'G' && letter != 'N' && !IsDecimal(number)) {
    throw ErrorAt(line_number, letter_pos, "malformed number '" + text + "': a number is digits "
                                           "with at most one decimal point and an optional "
                                           "sign, e.g. X-5.5, X.5, X10");
  }
}

// The word whose letter stands at *pos; *pos moves past its number.
Word ReadWord(const std::string& line, std::size_t* pos, int line_number, Dialect dialect) {
  const std::size_t letter_pos = *pos;
  const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(line[*pos])));
  ++*pos;
  while (*pos < line.size() && IsLineBlank(line[*pos])) ++*pos;
  const std::size_t number_pos = *pos;
  while (*pos < line.size() && IsNumberChar(line[*pos])) ++*pos;
  const std::string number = line.substr(number_pos, *pos - number_pos);
  const std::string text = std::string(1, letter) + number;
  const std::string dialect_rule = std::string("LinuxCNC's; the ") + DialectName(dialect) +
                                   " dialect does not read ";
  if (letter == 'O' && IsOWordControl(line, *pos)) {
    throw ErrorAt(line_number, letter_pos, "O-word control flow ('" + line.substr(letter_pos) +
                                           "': RS274NGC sub/call/if/while/repeat) is " +
                                           dialect_rule + "it; allowed: program_dialect: linuxcnc");
  }
  const char next = number_pos < line.size() ? line[number_pos] : '\0';
  if (number.empty() && (next == '#' || next == '[')) {
    throw ErrorAt(line_number, letter_pos, "'" + std::string(1, letter) + "' is followed by " +
                                           Quoted(next) + ": RS274NGC parameters and "
                                           "expressions are " + dialect_rule + "them; allowed: "
                                           "program_dialect: linuxcnc");
  }
  if (number.empty()) {
    const bool followed = next != '\0' && next != '(' && next != ';';
    throw ErrorAt(line_number, letter_pos,
                  "malformed number: '" + std::string(1, letter) + "' " +
                      (followed ? "is followed by " + Quoted(next) + ", not a number"
                                : std::string("has no number")) + "; " + kWordExample);
  }
  CheckNumber(letter, number, letter_pos, line_number);
  errno = 0;
  const double value = std::strtod(number.c_str(), nullptr);
  if (errno == ERANGE && std::isinf(value)) {
    throw ErrorAt(line_number, letter_pos, "number out of range in '" + text + "'");
  }
  Word word;
  word.letter = letter;
  word.value = value;
  word.column = static_cast<int>(letter_pos) + 1;
  word.text = text;
  return word;
}

ScannedLine ScanLine(const std::string& line, int line_number, Dialect dialect) {
  ScannedLine scanned;
  const std::string percent_rule =
      "'%' must stand alone on its line (comments may follow), to open or close the program";
  std::size_t pos = 0;
  while (pos < line.size()) {
    const char c = line[pos];
    if (IsLineBlank(c)) {
      ++pos;
      continue;
    }
    if (c == '(') {
      const std::size_t close = line.find(')', pos + 1);
      if (close == std::string::npos) {
        throw ErrorAt(line_number, pos, "unclosed comment: '(' without ')' on its line; a "
                                        "comment is ( ... ) within one line, or ; to the end "
                                        "of the line");
      }
      pos = close + 1;
      continue;
    }
    if (c == ';') break;
    if (c == '%') {
      if (scanned.percent_column > 0 || !scanned.words.empty()) {
        throw ErrorAt(line_number, pos, percent_rule);
      }
      scanned.percent_column = static_cast<int>(pos) + 1;
      ++pos;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      throw ForeignCharacter(c, pos, line_number, dialect);
    }
    if (scanned.percent_column > 0) {
      throw ErrorAt(line_number, static_cast<std::size_t>(scanned.percent_column - 1), percent_rule);
    }
    scanned.words.push_back(ReadWord(line, &pos, line_number, dialect));
  }
  return scanned;
}

// The time `block` takes at least: its chord at its feed (a lower bound of an arc's
// length; a full circle's chord is 0), plus its dwell.
double MinimumBlockSeconds(const ProgramBlock& block, const GcodeLimits& limits) {
  const double feed = block.kind == MotionKind::kRapid ? limits.rapid_feed_m_s
                      : std::isnan(block.feed_m_s)      ? limits.default_feed_m_s
                                                        : block.feed_m_s;
  const double chord_m = (block.end_m - block.start_m).norm();
  const double move_s = feed > 0.0 && std::isfinite(chord_m) ? chord_m / feed : 0.0;
  return move_s + block.dwell_s;
}

// Refuses the program as soon as its blocks or its path's time cross `limits`.
void CheckParsedSoFar(const Program& program, std::size_t counted, double* path_s,
                      const GcodeLimits& limits, int line_number) {
  for (std::size_t i = counted; i < program.blocks.size(); ++i) {
    *path_s += MinimumBlockSeconds(program.blocks[i], limits);
  }
  if (program.blocks.size() > limits.max_blocks) {
    throw ProgramError(line_number, 1, -1,
                       "the program has more than " + std::to_string(limits.max_blocks) +
                           " blocks by this line, more than " + limits.max_blocks_key +
                           " allows; reading stopped here");
  }
  if (*path_s > limits.max_path_s) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4g s at its feeds by this line (limit %.4g s)", *path_s,
                  limits.max_path_s);
    throw ProgramError(line_number, 1, -1,
                       std::string("the program's path already takes ") + text + ", more than " +
                           limits.max_path_key + " allows; reading stopped here");
  }
}

// What the parser does with a word before ProgramBuilder sees the block.
enum class WordUse { kModelled, kNoEffect, kIgnored };

// The G or M code of `word` (-1 when it is none or beyond any code's range).
int CodeOf(const Word& word) {
  if (!(word.value >= 0 && word.value <= 1000) || word.value != std::floor(word.value)) return -1;
  return static_cast<int>(word.value);
}

// Why `word` is refused: it would change the motion and the bench does not model it; ""
// for the others.
std::string RefusalReason(const Word& word) {
  const int code = CodeOf(word);
  const std::string shown = "'" + word.text + "'";
  if (word.letter == 'M' && (code == 98 || code == 99)) {
    return shown + " (subprogram call or return) is fanuc's; allowed: program_dialect: fanuc "
           "(LinuxCNC calls with O-word sub/call, grbl has no subprograms)";
  }
  if (word.letter != 'G') return "";
  if (code == 41 || code == 42) {
    return shown + " (cutter radius compensation) offsets the path by the tool radius, and the "
           "bench has no tool table; program the tool-centre path (G40)";
  }
  if (code == 95 || code == 96) {
    return shown + " (feed per revolution, constant surface speed) ties the feed to the "
           "spindle, which the bench does not model; program F in mm/min (G94)";
  }
  if (code == 73 || code == 74 || code == 76 || (code >= 81 && code <= 89)) {
    return shown + " is a canned cycle, which expands into moves the bench does not generate; "
           "program the moves with G0/G1 (G80 cancels a cycle)";
  }
  if (code == 53) {
    return shown + " (machine coordinates) needs the work offsets, which the bench does not "
           "model; program the moves in the part's coordinates";
  }
  return "";
}

WordUse UseOf(const Word& word) {
  if (std::strchr("OTSHDM", word.letter) != nullptr) return WordUse::kIgnored;
  if (word.letter != 'G') return WordUse::kModelled;
  const int code = CodeOf(word);
  if (code == 43 || code == 44 || (code >= 54 && code <= 59)) return WordUse::kIgnored;
  if (code == 40 || code == 49 || code == 80 || code == 94) return WordUse::kNoEffect;
  return WordUse::kModelled;
}

bool IsOffsetWord(const Word& word) {
  const int code = word.letter == 'G' ? CodeOf(word) : -1;
  return code == 43 || code == 44 || (code >= 54 && code <= 59);
}

// The words a program drops, each distinct one (as written) once, with its first line.
class IgnoredWords {
 public:
  void Add(const std::string& shown, int line) {
    if (!seen_.insert(shown).second) return;
    if (entries_.size() < kMaxListed) {
      entries_.push_back(shown + " (line " + std::to_string(line) + ")");
    } else {
      ++unlisted_;
    }
  }
  void NoteOffset() { offsets_ = true; }

  // The one warning of the program, "" when nothing was dropped.
  std::string Warning() const {
    if (seen_.empty()) return "";
    std::string text = "ignored words not modelled by the bench: ";
    for (std::size_t i = 0; i < entries_.size(); ++i) text += (i > 0 ? ", " : "") + entries_[i];
    if (unlisted_ > 0) text += " and " + std::to_string(unlisted_) + " more";
    if (offsets_) {
      text += "; tool-length and work offsets do not move the commanded path (the bench has "
              "no tool or offset table)";
    }
    return text;
  }

 private:
  static constexpr std::size_t kMaxListed = 40;  // a long program repeats a few words
  std::set<std::string> seen_;
  std::vector<std::string> entries_;
  std::size_t unlisted_ = 0;
  bool offsets_ = false;
};

// `words` without the words the bench drops; refuses those that would change the motion
// (and, strict, the dropped ones). Sets *ends for M2/M30.
std::vector<Word> ModelledWords(const std::vector<Word>& words, int line, const GcodeOptions& options,
                                IgnoredWords* ignored, bool* ends) {
  std::vector<Word> kept;
  auto is_length_offset = [](const Word& w) {
    return w.letter == 'G' && (CodeOf(w) == 43 || CodeOf(w) == 44);
  };
  // An H word shown with its G43/G44 ("G43 H1").
  const bool length_offset = std::any_of(words.begin(), words.end(), is_length_offset);
  std::string h_word;
  for (const Word& word : words) {
    if (word.letter == 'H') h_word = word.text;
  }
  for (const Word& word : words) {
    const std::string reason = RefusalReason(word);
    if (!reason.empty()) throw ProgramError(line, word.column, -1, reason);
    const WordUse use = UseOf(word);
    if (use == WordUse::kModelled) kept.push_back(word);
    if (use != WordUse::kIgnored) continue;
    if (options.strict) {
      throw ProgramError(line, word.column, -1,
                         "'" + word.text + "' is not modelled by the bench, and " +
                             options.strict_key + " refuses the words it would otherwise "
                             "ignore (O, T, S, H, D, M, G43, G44, G54-G59)");
    }
    const int code = CodeOf(word);
    if (word.letter == 'M' && (code == 2 || code == 30)) *ends = true;
    if (IsOffsetWord(word)) ignored->NoteOffset();
    if (word.letter == 'H' && length_offset) continue;  // listed with its G43/G44
    ignored->Add(is_length_offset(word) && !h_word.empty() ? word.text + " " + h_word : word.text,
                 line);
  }
  return kept;
}

}  // namespace

Program ParseGcode(const std::string& text, const Eigen::Vector3d& start_m, const GcodeLimits& limits,
                   const GcodeOptions& options) {
  ProgramBuilder builder(start_m, options.program);
  IgnoredWords ignored;
  int end_line = 0;  // the line of M2/M30, 0 before it
  double path_s = 0.0;  // the path's time so far, at least
  bool opened = false;     // an opening `%` was read
  int closing_line = 0;    // the line of the closing `%`, 0 while open
  bool any_block = false;  // a line with words was read
  ProgramExpander expander(text, options.program);
  SourceLine source;
  while (expander.Next(&source)) {
    const std::string& line = source.text;
    const int line_number = source.line;
    const ScannedLine scanned = ScanLine(line, line_number, options.program.dialect);
    if (scanned.percent_column > 0) {
      if (closing_line > 0) {
        throw ProgramError(line_number, scanned.percent_column, -1,
                           "'%' after the closing '%' of line " +
                               std::to_string(closing_line) +
                               "; '%' may only open and close the program");
      }
      if (!opened && !any_block) {
        opened = true;
      } else {
        closing_line = line_number;
      }
      continue;
    }
    if (scanned.words.empty()) continue;
    if (closing_line > 0) {
      throw ProgramError(line_number, scanned.words.front().column, -1,
                         "a block after the closing '%' of line " +
                             std::to_string(closing_line) +
                             "; '%' may only open and close the program");
    }
    if (end_line > 0) {
      throw ProgramError(line_number, scanned.words.front().column, -1,
                         "a block after the program end (M2/M30) of line " +
                             std::to_string(end_line) + "; a control stops there");
    }
    bool ends = false;
    Block block;
    block.words = ModelledWords(scanned.words, line_number, options, &ignored, &ends);
    block.source_line = line_number;
    if (ends) end_line = line_number;
    const std::size_t counted = builder.program().blocks.size();
    builder.Apply(block);
    CheckParsedSoFar(builder.program(), counted, &path_s, limits, line_number);
    any_block = true;
  }
  Program program = builder.TakeProgram();
  const std::string warning = ignored.Warning();
  if (!warning.empty()) program.warnings.push_back(warning);
  program.gcode_lines = true;
  return program;
}

}  // namespace shapebench::controller
