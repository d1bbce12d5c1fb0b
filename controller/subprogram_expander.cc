#include "controller/subprogram_expander.h"

#include <cctype>
#include <cmath>
#include <utility>

#include "controller/ngc_control_flow.h"
#include "controller/program_words.h"
#include "controller/rs274_expression.h"

namespace shapebench::controller {
namespace {

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    if (end == text.size() && begin == text.size()) break;  // after the final newline
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

// A Fanuc address word's letter, number as written and place in its line.
struct Token {
  char letter;
  std::string number;
  std::size_t begin, end;
};

std::vector<Token> FanucTokens(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == ';') break;
    if (c == '(') {
      const std::size_t close = text.find(')', pos);
      if (close == std::string::npos) break;
      pos = close + 1;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c))) {
      ++pos;
      continue;
    }
    Token token{static_cast<char>(std::toupper(static_cast<unsigned char>(c))), "", pos, 0};
    ++pos;
    while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
    while (pos < text.size() && (std::isdigit(static_cast<unsigned char>(text[pos])) ||
                                 text[pos] == '.' || text[pos] == '-' || text[pos] == '+')) {
      token.number += text[pos++];
    }
    token.end = pos;
    tokens.push_back(token);
  }
  return tokens;
}

bool IsCode(const Token& token, char letter, int code) {
  if (token.letter != letter || token.number.empty()) return false;
  for (const char c : token.number) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return std::stol(token.number) == code;
}

// Whether a Fanuc program may call subprograms: an M98 or M99 anywhere (M 098 too).
bool MayCallSubprograms(const std::string& text) {
  for (std::size_t pos = 0; pos < text.size(); ++pos) {
    if (text[pos] != 'M' && text[pos] != 'm') continue;
    std::size_t k = pos + 1;
    while (k < text.size() && (text[k] == ' ' || text[k] == '\t' || text[k] == '0')) ++k;
    if (k + 1 < text.size() && text[k] == '9' && (text[k + 1] == '8' || text[k + 1] == '9')) {
      return true;
    }
  }
  return false;
}

// Whether a LinuxCNC program holds parameters, expressions or O-words: '#', '[', or a line
// that starts with an O.
bool MayHoldRs274(const std::string& text) {
  if (text.find_first_of("#[") != std::string::npos) return true;
  bool line_start = true;
  for (const char c : text) {
    if (line_start && (c == 'o' || c == 'O')) return true;
    if (c == '\n') {
      line_start = true;
    } else if (c != ' ' && c != '\t') {
      line_start = false;
    }
  }
  return false;
}

}  // namespace

struct ProgramExpander::State {
  ProgramOptions options;
  const std::string* text = nullptr;
  std::size_t begin = 0;  // streaming: where the next line starts
  int streamed = 0;       // streaming: the lines handed out
  bool split = false;     // the text is held as lines (it needs expansion)
  std::vector<std::string> lines;
  std::size_t pc = 0;
  long iterations = 0;
  std::unique_ptr<NgcControlFlow> ngc;  // linuxcnc with O-words or parameters
  // Fanuc subprograms.
  bool fanuc_calls = false;
  std::size_t first_block = 0;               // where M99 in the main program jumps
  std::map<long, std::size_t> subprograms;   // O number -> its line index
  std::map<std::size_t, std::size_t> sub_end;  // O line index -> its M99 line index
  struct Call {
    std::size_t return_pc, start;
    long remaining;
  };
  std::vector<Call> calls;
  bool main_ended = false;

  void Count(std::size_t i) {
    if (++iterations <= options.max_iterations) return;
    throw ProgramError(static_cast<int>(i) + 1, 1, -1,
                       "the program has made more than " + std::to_string(options.max_iterations) +
                           " loop passes, subprogram calls and M99 jumps by this line, more "
                           "than " + options.max_iterations_key + " allows (a program that "
                           "never ends?); reading stopped here");
  }
  void IndexFanuc();
  bool FanucLine(std::size_t i, std::string* text);
  void FanucCall(std::size_t i, const std::vector<Token>& tokens, std::size_t m98);
  void FanucReturn(std::size_t i, const std::vector<Token>& tokens, std::size_t m99);
};

void ProgramExpander::State::IndexFanuc() {
  bool first = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::vector<Token> tokens = FanucTokens(lines[i]);
    for (const Token& t : tokens) fanuc_calls = fanuc_calls || IsCode(t, 'M', 98) || IsCode(t, 'M', 99);
    if (tokens.empty()) continue;
    if (first) {
      first = false;
      first_block = i;
      continue;  // an O number here names the main program
    }
    if (tokens[0].letter != 'O' || tokens[0].number.empty()) continue;
    const long number = std::strtol(tokens[0].number.c_str(), nullptr, 10);
    subprograms[number] = i;
    std::size_t end = i + 1;
    while (end < lines.size()) {
      bool m99 = false;
      for (const Token& t : FanucTokens(lines[end])) m99 = m99 || IsCode(t, 'M', 99);
      if (m99) break;
      ++end;
    }
    sub_end[i] = end;
  }
}

// M98 P<n> [L<count>] (or P<count><nnnn>): the call after the rest of the block.
void ProgramExpander::State::FanucCall(std::size_t i, const std::vector<Token>& tokens,
                                       std::size_t m98) {
  const int line = static_cast<int>(i) + 1;
  const Token* p = nullptr;
  const Token* l = nullptr;
  for (const Token& t : tokens) {
    if (t.letter == 'P') p = &t;
    if (t.letter == 'L') l = &t;
  }
  auto integer = [&](const Token* t) {
    for (const char c : t->number) {
      if (!std::isdigit(static_cast<unsigned char>(c))) {
        throw ProgramError(line, static_cast<int>(t->begin) + 1, -1,
                           "'" + std::string(1, t->letter) + t->number + "' with M98 takes an "
                           "unsigned integer (e.g. M98 P1000 L2)");
      }
    }
    if (t->number.empty()) {
      throw ProgramError(line, static_cast<int>(t->begin) + 1, -1, "M98's " +
                         std::string(1, t->letter) + " needs its number (e.g. M98 P1000 L2)");
    }
    return std::stol(t->number.substr(0, 9));
  };
  if (p == nullptr) {
    throw ProgramError(line, static_cast<int>(tokens[m98].begin) + 1, -1,
                       "M98 needs the subprogram number: P (e.g. M98 P1000)");
  }
  long number = integer(p);
  long count = l != nullptr ? integer(l) : 1;
  if (p->number.size() > 4) {  // P30010: three times O0010
    if (l != nullptr) {
      throw ProgramError(line, static_cast<int>(l->begin) + 1, -1,
                         "M98 takes its repeat count as L or packed in P (P30010), not both");
    }
    count = std::stol(p->number.substr(0, p->number.size() - 4));
    number = std::stol(p->number.substr(p->number.size() - 4));
  }
  const auto found = subprograms.find(number);
  if (found == subprograms.end()) {
    throw ProgramError(line, static_cast<int>(p->begin) + 1, -1,
                       "M98 calls O" + std::to_string(number) + ", which is not in this file "
                       "(the bench reads one file; put the subprogram after M30, ending with M99)");
  }
  if (count <= 0) return;  // L0: no call
  if (calls.size() >= static_cast<std::size_t>(kMaxCallDepth)) {
    throw ProgramError(line, static_cast<int>(tokens[m98].begin) + 1, -1,
                       "subprograms nest more than " + std::to_string(kMaxCallDepth) + " deep");
  }
  Count(i);
  calls.push_back({pc, found->second, count - 1});
  pc = found->second + 1;
}

void ProgramExpander::State::FanucReturn(std::size_t i, const std::vector<Token>& tokens,
                                         std::size_t m99) {
  for (const Token& t : tokens) {
    if (t.letter == 'P') {
      throw ProgramError(static_cast<int>(i) + 1, static_cast<int>(t.begin) + 1, -1,
                         "M99 P (return to a sequence number) is not read by the bench; "
                         "allowed: M99 alone");
    }
  }
  (void)m99;
  Count(i);
  if (calls.empty()) {  // M99 in the main program: from its start again, endlessly
    pc = first_block;
    return;
  }
  Call& call = calls.back();
  if (call.remaining > 0) {
    --call.remaining;
    pc = call.start + 1;
    return;
  }
  pc = call.return_pc;
  calls.pop_back();
}

// A Fanuc line: M98/M99 (and their P, L) taken out of it and run; false to skip it.
bool ProgramExpander::State::FanucLine(std::size_t i, std::string* text) {
  const std::vector<Token> tokens = FanucTokens(*text);
  if (!tokens.empty() && sub_end.count(i) > 0) {
    if (main_ended && calls.empty()) {
      pc = sub_end[i] + 1;  // a subprogram's definition after M2/M30
      return false;
    }
    throw ProgramError(static_cast<int>(i) + 1, static_cast<int>(tokens[0].begin) + 1, -1,
                       "the program runs into subprogram O" + tokens[0].number + " without "
                       "M2/M30 or M99 before it; end the main program (M30) before its "
                       "subprograms");
  }
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    const bool call = IsCode(tokens[k], 'M', 98), back = IsCode(tokens[k], 'M', 99);
    if (!call && !back) continue;
    for (const Token& t : tokens) {
      if (&t == &tokens[k] || t.letter == 'P' || (call && t.letter == 'L')) {
        text->replace(t.begin, t.end - t.begin, std::string(t.end - t.begin, ' '));
      }
    }
    if (call) FanucCall(i, tokens, k);
    if (back) FanucReturn(i, tokens, k);
    return true;
  }
  for (const Token& t : tokens) {
    if (calls.empty() && (IsCode(t, 'M', 2) || IsCode(t, 'M', 30))) main_ended = true;
  }
  return true;
}

ProgramExpander::ProgramExpander(const std::string& text, const ProgramOptions& options)
    : state_(std::make_unique<State>()) {
  state_->options = options;
  state_->text = &text;
  // Most programs need no expansion: they stream line by line, never held as lines.
  const bool fanuc = options.dialect == Dialect::kFanuc && MayCallSubprograms(text);
  const bool ngc = options.dialect == Dialect::kLinuxcnc && MayHoldRs274(text);
  if (!fanuc && !ngc) return;
  state_->lines = SplitLines(text);
  state_->split = true;
  if (fanuc) state_->IndexFanuc();
  if (ngc && NgcControlFlow::Needed(state_->lines)) {
    state_->ngc = std::make_unique<NgcControlFlow>(state_->lines, options);
  }
}

ProgramExpander::~ProgramExpander() = default;

bool ProgramExpander::Next(SourceLine* line) {
  State& s = *state_;
  if (s.ngc) return s.ngc->Next(line);
  if (!s.split) {  // streaming: the next line of the text as it stands
    const std::string& text = *s.text;
    if (s.begin >= text.size()) return false;
    std::size_t end = text.find('\n', s.begin);
    if (end == std::string::npos) end = text.size();
    line->line = ++s.streamed;
    line->text = text.substr(s.begin, end - s.begin);
    s.begin = end + 1;
    return true;
  }
  while (s.pc < s.lines.size()) {
    const std::size_t i = s.pc++;
    std::string text = s.lines[i];
    if (s.fanuc_calls && !s.FanucLine(i, &text)) continue;
    line->line = static_cast<int>(i) + 1;
    line->text = std::move(text);
    return true;
  }
  return false;
}

}  // namespace shapebench::controller
