#include "controller/gcode_parser.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace shapebench::controller {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

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

constexpr const char* kWordExample = "a word is a letter and a number, e.g. X-5.5";

struct ScannedLine {
  std::vector<Word> words;
  int percent_column = 0;  // 1-based column of a `%`, 0 if none
};

ScannedLine ScanLine(const std::string& line, int line_number) {
  ScannedLine scanned;
  auto error = [&](std::size_t pos, const std::string& message) {
    return ProgramError(line_number, static_cast<int>(pos) + 1, -1, message);
  };
  const std::string percent_rule =
      "'%' must stand alone on its line (comments may follow), to open or close the program";
  std::size_t pos = 0;
  while (pos < line.size()) {
    const char c = line[pos];
    if (IsBlank(c)) {
      ++pos;
      continue;
    }
    if (c == '(') {
      const std::size_t close = line.find(')', pos + 1);
      if (close == std::string::npos) {
        throw error(pos, "unclosed comment: '(' without ')' on its line; a comment is "
                         "( ... ) within one line, or ; to the end of the line");
      }
      pos = close + 1;
      continue;
    }
    if (c == ';') break;
    if (c == '%') {
      if (scanned.percent_column > 0 || !scanned.words.empty()) throw error(pos, percent_rule);
      scanned.percent_column = static_cast<int>(pos) + 1;
      ++pos;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      throw error(pos, "unexpected character " + Quoted(c) +
                           "; a block is words (a letter and a number, e.g. X10) with "
                           "comments in ( ) or after ;");
    }
    if (scanned.percent_column > 0) {
      throw error(static_cast<std::size_t>(scanned.percent_column - 1), percent_rule);
    }
    const std::size_t letter_pos = pos;
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    ++pos;
    while (pos < line.size() && IsBlank(line[pos])) ++pos;
    const std::size_t number_pos = pos;
    while (pos < line.size() && IsNumberChar(line[pos])) ++pos;
    const std::string number = line.substr(number_pos, pos - number_pos);
    const std::string text = std::string(1, letter) + number;
    if (number.empty()) {
      const bool followed = number_pos < line.size() && line[number_pos] != '(' &&
                            line[number_pos] != ';';
      throw error(letter_pos, "malformed number: '" + std::string(1, letter) + "' " +
                                  (followed ? "is followed by " + Quoted(line[number_pos]) +
                                                  ", not a number"
                                            : std::string("has no number")) +
                                  "; " + kWordExample);
    }
    if (letter == 'G' || letter == 'N') {
      if (!IsUnsignedInteger(number)) {
        throw error(letter_pos, "malformed number '" + text + "': " + std::string(1, letter) +
                                    " takes an unsigned integer, e.g. " +
                                    (letter == 'G' ? "G1" : "N10"));
      }
    } else if (!IsDecimal(number)) {
      throw error(letter_pos, "malformed number '" + text +
                                  "': a number is digits with at most one decimal point and "
                                  "an optional sign, e.g. X-5.5, X.5, X10");
    }
    errno = 0;
    const double value = std::strtod(number.c_str(), nullptr);
    if (errno == ERANGE && std::isinf(value)) {
      throw error(letter_pos, "number out of range in '" + text + "'");
    }
    Word word;
    word.letter = letter;
    word.value = value;
    word.column = static_cast<int>(letter_pos) + 1;
    word.text = text;
    scanned.words.push_back(word);
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

}  // namespace

Program ParseGcode(const std::string& text, const Eigen::Vector3d& start_m, const GcodeLimits& limits) {
  ProgramBuilder builder(start_m);
  double path_s = 0.0;  // the path's time so far, at least
  bool opened = false;     // an opening `%` was read
  int closing_line = 0;    // the line of the closing `%`, 0 while open
  bool any_block = false;  // a line with words was read
  int line_number = 0;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ++line_number;
    if (end == text.size() && line.empty()) break;  // after the final newline

    const ScannedLine scanned = ScanLine(line, line_number);
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
    Block block;
    block.words = scanned.words;
    block.source_line = line_number;
    const std::size_t counted = builder.program().blocks.size();
    builder.Apply(block);
    CheckParsedSoFar(builder.program(), counted, &path_s, limits, line_number);
    any_block = true;
  }
  Program program = builder.TakeProgram();
  program.gcode_lines = true;
  return program;
}

}  // namespace shapebench::controller
