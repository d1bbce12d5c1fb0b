#include "controller/ngc_control_flow.h"

#include <cctype>
#include <algorithm>
#include <cmath>
#include <iterator>

#include "controller/program_builder.h"
#include "controller/source_line.h"

namespace shapebench::controller {
namespace {

const std::map<std::string, int>& Keywords() {
  // The values are NgcControlFlow::Kind's, in its order (kNone is 0).
  static const std::map<std::string, int> kKeywords = {
      {"sub", 1},  {"endsub", 2},   {"call", 3},  {"return", 4},    {"if", 5},
      {"elseif", 6}, {"else", 7},   {"endif", 8}, {"while", 9},     {"endwhile", 10},
      {"do", 11},  {"repeat", 13},  {"endrepeat", 14}, {"break", 15}, {"continue", 16}};
  return kKeywords;
}

bool IsLoop(int kind) { return kind == 9 || kind == 11 || kind == 13; }

}  // namespace

NgcControlFlow::Control NgcControlFlow::ParseControl(const std::string& text) {
  Control control;
  std::size_t pos = 0;
  while (pos < text.size() && IsLineBlank(text[pos])) ++pos;
  if (pos >= text.size() || std::tolower(static_cast<unsigned char>(text[pos])) != 'o') {
    return control;
  }
  control.column = static_cast<int>(pos) + 1;
  ++pos;
  while (pos < text.size() && IsLineBlank(text[pos])) ++pos;
  if (pos < text.size() && text[pos] == '<') {
    const std::size_t close = text.find('>', pos);
    if (close == std::string::npos) return control;
    for (std::size_t k = pos; k <= close; ++k) {
      if (!IsLineBlank(text[k])) {
        control.label += static_cast<char>(std::tolower(static_cast<unsigned char>(text[k])));
      }
    }
    pos = close + 1;
  } else {
    while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos]))) {
      control.label += text[pos++];
    }
    const std::size_t nonzero = control.label.find_first_not_of('0');
    control.label = nonzero == std::string::npos ? "0" : control.label.substr(nonzero);
  }
  while (pos < text.size() && IsLineBlank(text[pos])) ++pos;
  std::string keyword;
  while (pos < text.size() && std::isalpha(static_cast<unsigned char>(text[pos]))) {
    keyword += static_cast<char>(std::tolower(static_cast<unsigned char>(text[pos++])));
  }
  const auto found = Keywords().find(keyword);
  if (found == Keywords().end()) return control;
  control.kind = static_cast<Kind>(found->second);
  control.keyword = keyword;
  control.arguments = pos;
  return control;
}

bool NgcControlFlow::Needed(const std::vector<std::string>& lines) {
  for (const std::string& line : lines) {
    if (HasRs274Syntax(line) || ParseControl(line).kind != Kind::kNone) return true;
  }
  return false;
}

NgcControlFlow::NgcControlFlow(const std::vector<std::string>& lines, const ProgramOptions& options)
    : lines_(lines), options_(options) {
  controls_.reserve(lines.size());
  for (const std::string& line : lines) controls_.push_back(ParseControl(line));
  Pair();
}

std::string NgcControlFlow::Shown(std::size_t i) const {
  return "'o" + controls_[i].label + " " + controls_[i].keyword + "' (line " +
         std::to_string(i + 1) + ")";
}

ProgramError NgcControlFlow::Error(std::size_t i, const std::string& message) const {
  return ProgramError(static_cast<int>(i) + 1, std::max(1, controls_[i].column), -1, message);
}

// The closing O-words: each pairs with the innermost open one of the same label.
void NgcControlFlow::PairEnd(std::size_t i, std::vector<std::size_t>* open) {
  const Control& c = controls_[i];
  const std::map<Kind, std::vector<Kind>> opens = {
      {Kind::kEndsub, {Kind::kSub}},   {Kind::kElseif, {Kind::kIf}},
      {Kind::kElse, {Kind::kIf}},      {Kind::kEndif, {Kind::kIf}},
      {Kind::kEndwhile, {Kind::kWhile}}, {Kind::kEndrepeat, {Kind::kRepeat}}};
  const std::vector<Kind>& wanted = opens.at(c.kind);
  if (open->empty() || controls_[open->back()].label != c.label ||
      controls_[open->back()].kind != wanted[0]) {
    throw Error(i, Shown(i) + " has no open 'o" + c.label + " " +
                       (wanted[0] == Kind::kSub ? "sub" : wanted[0] == Kind::kIf ? "if"
                        : wanted[0] == Kind::kWhile ? "while" : "repeat") +
                       "' before it (O-words nest, each closed by its own label)");
  }
  const std::size_t start = open->back();
  if (c.kind == Kind::kElseif || c.kind == Kind::kElse) {
    std::size_t last = start;  // the chain so far: if -> elseif -> ...
    while (next_branch_.count(last) > 0) last = next_branch_[last];
    next_branch_[last] = i;
    return;
  }
  open->pop_back();
  match_[start] = i;
  match_[i] = start;
  if (c.kind == Kind::kEndsub) subs_[c.label] = start;
  if (c.kind != Kind::kEndif) return;
  std::size_t branch = start;
  for (;;) {
    endif_of_[branch] = i;
    if (next_branch_.count(branch) == 0) break;
    branch = next_branch_[branch];
  }
  std::size_t last = start;
  while (next_branch_.count(last) > 0) last = next_branch_[last];
  next_branch_[last] = i;
}

void NgcControlFlow::Pair() {
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < controls_.size(); ++i) {
    Control& c = controls_[i];
    switch (c.kind) {
      case Kind::kNone: case Kind::kCall: break;
      case Kind::kSub: case Kind::kIf: case Kind::kDo: case Kind::kRepeat:
        open.push_back(i);
        break;
      case Kind::kWhile:
        if (!open.empty() && controls_[open.back()].kind == Kind::kDo &&
            controls_[open.back()].label == c.label) {
          c.kind = Kind::kDoWhile;  // closes o<label> do
          match_[open.back()] = i;
          match_[i] = open.back();
          open.pop_back();
        } else {
          open.push_back(i);
        }
        break;
      case Kind::kBreak: case Kind::kContinue: case Kind::kReturn: {
        std::size_t k = open.size();
        const bool loop = c.kind != Kind::kReturn;
        while (k > 0 && !(controls_[open[k - 1]].label == c.label &&
                          (loop ? IsLoop(static_cast<int>(controls_[open[k - 1]].kind))
                                : controls_[open[k - 1]].kind == Kind::kSub))) {
          --k;
        }
        if (k == 0) {
          throw Error(i, Shown(i) + " is not inside an 'o" + c.label + "' " +
                             (loop ? "loop (while, do, repeat)" : "sub"));
        }
        loop_of_[i] = open[k - 1];
        break;
      }
      default:
        PairEnd(i, &open);
    }
  }
  if (!open.empty()) {
    throw Error(open.back(), Shown(open.back()) + " is never closed (the file ends first)");
  }
}

void NgcControlFlow::Count(std::size_t i) {
  if (++iterations_ <= options_.max_iterations) return;
  throw Error(i, "the program has made more than " + std::to_string(options_.max_iterations) +
                     " loop passes and subroutine calls by " + Shown(i) + ", more than " +
                     options_.max_iterations_key + " allows (a loop that never ends?); "
                     "reading stopped here");
}

bool NgcControlFlow::Condition(std::size_t i) {
  std::size_t pos = controls_[i].arguments;
  return ReadRealValue(lines_[i], &pos, static_cast<int>(i) + 1, parameters_) != 0;
}

// if/elseif: the first branch whose condition holds (or else) runs.
void NgcControlFlow::Branch(std::size_t i) {
  std::size_t j = i;
  for (;;) {
    const Kind kind = controls_[j].kind;
    if (kind == Kind::kEndif || kind == Kind::kElse || Condition(j)) {
      pc_ = j + 1;
      return;
    }
    j = next_branch_.at(j);
  }
}

void NgcControlFlow::Call(std::size_t i) {
  const Control& c = controls_[i];
  const auto sub = subs_.find(c.label);
  if (sub == subs_.end()) {
    throw Error(i, Shown(i) + " calls a subroutine that is not in this file (the bench reads "
                              "one file; define 'o" + c.label + " sub' ... 'o" + c.label +
                              " endsub' in it)");
  }
  std::vector<double> arguments;
  std::size_t pos = c.arguments;
  const std::string& text = lines_[i];
  for (;;) {
    while (pos < text.size() && IsLineBlank(text[pos])) ++pos;
    if (pos >= text.size() || text[pos] == '(' || text[pos] == ';') break;
    arguments.push_back(ReadRealValue(text, &pos, static_cast<int>(i) + 1, parameters_));
  }
  if (calls_.size() >= static_cast<std::size_t>(kMaxCallDepth)) {
    throw Error(i, Shown(i) + ": subroutine calls nest more than " +
                       std::to_string(kMaxCallDepth) + " deep");
  }
  Count(i);
  calls_.push_back({pc_, static_cast<int>(i) + 1});
  parameters_.PushCall(arguments);
  pc_ = sub->second + 1;
}

// endsub/return [value]: back after the call; the value goes to #<_value>.
void NgcControlFlow::Return(std::size_t i) {
  if (calls_.empty()) throw Error(i, Shown(i) + " is reached outside a call");
  std::size_t pos = controls_[i].arguments;
  const std::string& text = lines_[i];
  while (pos < text.size() && IsLineBlank(text[pos])) ++pos;
  const bool value = pos < text.size() && text[pos] == '[';
  const double result = value ? ReadRealValue(text, &pos, static_cast<int>(i) + 1, parameters_) : 0;
  const std::size_t depth = parameters_.depth();
  for (auto it = repeats_.begin(); it != repeats_.end();) {
    it = it->first.first >= depth ? repeats_.erase(it) : std::next(it);
  }
  parameters_.PopCall();
  if (value) parameters_.SetNamed("_value", result);
  pc_ = calls_.back().return_pc;
  calls_.pop_back();
}

void NgcControlFlow::Repeat(std::size_t i) {
  std::size_t pos = controls_[i].arguments;
  const double count = ReadRealValue(lines_[i], &pos, static_cast<int>(i) + 1, parameters_);
  const long n = static_cast<long>(std::floor(count + 0.5));
  if (n <= 0) {
    pc_ = match_.at(i) + 1;
    return;
  }
  repeats_[{parameters_.depth(), i}] = n - 1;
  Count(i);
  pc_ = i + 1;
}

void NgcControlFlow::EndRepeat(std::size_t i) {
  const std::size_t start = match_.at(i);
  const auto key = std::make_pair(parameters_.depth(), start);
  const auto left = repeats_.find(key);
  if (left != repeats_.end() && left->second > 0) {
    --left->second;
    Count(start);
    pc_ = start + 1;
    return;
  }
  repeats_.erase(key);
  pc_ = i + 1;
}

void NgcControlFlow::Execute(std::size_t i) {
  switch (controls_[i].kind) {
    case Kind::kSub: pc_ = match_.at(i) + 1; break;  // defined here, runs when called
    case Kind::kEndsub: case Kind::kReturn: Return(i); break;
    case Kind::kCall: Call(i); break;
    case Kind::kIf: Branch(i); break;
    case Kind::kElseif: case Kind::kElse: pc_ = endif_of_.at(i) + 1; break;  // a branch ran
    case Kind::kWhile:
      if (Condition(i)) {
        Count(i);
      } else {
        pc_ = match_.at(i) + 1;
      }
      break;
    case Kind::kEndwhile: pc_ = match_.at(i); break;
    case Kind::kDo: Count(i); break;
    case Kind::kDoWhile:
      if (Condition(i)) {
        Count(i);
        pc_ = match_.at(i) + 1;
      }
      break;
    case Kind::kRepeat: Repeat(i); break;
    case Kind::kEndrepeat: EndRepeat(i); break;
    case Kind::kBreak: {
      const std::size_t loop = loop_of_.at(i);
      repeats_.erase({parameters_.depth(), loop});
      pc_ = match_.at(loop) + 1;
      break;
    }
    case Kind::kContinue: {
      const std::size_t loop = loop_of_.at(i);
      pc_ = controls_[loop].kind == Kind::kWhile ? loop : match_.at(loop);
      break;
    }
    case Kind::kEndif: case Kind::kNone: break;
  }
}

bool NgcControlFlow::Next(SourceLine* line) {
  while (pc_ < lines_.size()) {
    const std::size_t i = pc_++;
    if (controls_[i].kind != Kind::kNone) {
      Execute(i);
      continue;
    }
    line->line = static_cast<int>(i) + 1;
    line->text = HasRs274Syntax(lines_[i])
                     ? SubstituteLine(lines_[i], line->line, &parameters_)
                     : lines_[i];
    return true;
  }
  return false;
}

}  // namespace shapebench::controller
