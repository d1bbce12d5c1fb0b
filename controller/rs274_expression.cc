#include "controller/rs274_expression.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "controller/program_words.h"
#include "controller/source_line.h"

namespace shapebench::controller {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
constexpr double kEqualTolerance = 1e-4;  // rs274ngc's TOLERANCE_EQUAL
constexpr int kMaxNumbered = 5399;


std::string Lower(const std::string& text) {
  std::string lower;
  for (const char c : text) {
    if (!IsLineBlank(c)) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return lower;
}

// The binary operators and their levels (1 binds tightest).
struct Operator {
  const char* name;
  int level;
};
constexpr Operator kOperators[] = {{"**", 1}, {"*", 2},  {"/", 2},  {"MOD", 2}, {"+", 3},
                                   {"-", 3},  {"EQ", 4}, {"NE", 4}, {"GT", 4},  {"GE", 4},
                                   {"LT", 4}, {"LE", 4}, {"AND", 5}, {"OR", 5}, {"XOR", 5}};
constexpr int kLoosest = 5;

// A value as a G-code number: fixed point, no exponent, trailing zeros dropped.
std::string Formatted(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, std::abs(value) < 1e15 ? "%.10f" : "%.0f", value);
  std::string text = buffer;
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  return text == "-0" ? "0" : text;
}

class ValueReader {
 public:
  ValueReader(const std::string& text, std::size_t pos, int line, const Rs274Parameters& parameters)
      : text_(text), pos_(pos), line_(line), parameters_(parameters) {}

  double RealValue();
  std::size_t pos() const { return pos_; }

 private:
  double Bracketed();
  double Binary(int level);
  double Parameter();
  double Function();
  double Number();
  const Operator* PeekOperator();
  double Apply(const std::string& op, double a, double b, std::size_t op_at) const;
  void SkipBlanks() {
    while (pos_ < text_.size() && IsLineBlank(text_[pos_])) ++pos_;
  }
  char Peek() {
    SkipBlanks();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  void Expect(char c, const std::string& what) {
    if (Peek() != c) throw Error("expected '" + std::string(1, c) + "' " + what);
    ++pos_;
  }
  ProgramError Error(const std::string& message) const {
    return ProgramError(line_, static_cast<int>(pos_) + 1, -1, message);
  }

  const std::string& text_;
  std::size_t pos_;
  int line_;
  const Rs274Parameters& parameters_;
};

double ValueReader::RealValue() {
  const char c = Peek();
  if (c == '[') return Bracketed();
  if (c == '#') return Parameter();
  if (c == '-') return ++pos_, -RealValue();
  if (c == '+') return ++pos_, RealValue();
  if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return Number();
  if (std::isalpha(static_cast<unsigned char>(c))) return Function();
  throw Error(c == '\0' ? "a value is missing at the end of the line"
                        : "expected a value (a number, #parameter, [expression] or function), "
                          "found '" + std::string(1, c) + "'");
}

double ValueReader::Bracketed() {
  Expect('[', "to open an expression");
  const double value = Binary(kLoosest);
  Expect(']', "to close the expression");
  return value;
}

double ValueReader::Binary(int level) {
  if (level == 0) return RealValue();
  double left = Binary(level - 1);
  for (;;) {
    const std::size_t at = pos_;
    const Operator* op = PeekOperator();
    if (op == nullptr || op->level != level) {
      pos_ = at;
      return left;
    }
    const std::size_t op_at = pos_;
    pos_ += std::string(op->name).size();
    const double right = Binary(level - 1);
    left = Apply(op->name, left, right, op_at);
  }
}

const Operator* ValueReader::PeekOperator() {
  SkipBlanks();
  for (const Operator& op : kOperators) {
    const std::size_t n = std::string(op.name).size();
    if (pos_ + n > text_.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < n; ++k) {
      same = same && std::toupper(static_cast<unsigned char>(text_[pos_ + k])) == op.name[k];
    }
    if (same) return &op;
  }
  return nullptr;
}

double ValueReader::Apply(const std::string& op, double a, double b, std::size_t op_at) const {
  if (op == "**") return std::pow(a, b);
  if (op == "*") return a * b;
  if (op == "/" || op == "MOD") {
    if (b == 0) {
      throw ProgramError(line_, static_cast<int>(op_at) + 1, -1, "division by zero ('" + op + "')");
    }
    if (op == "/") return a / b;
    const double r = std::fmod(a, b);
    return r < 0 ? r + std::abs(b) : r;
  }
  if (op == "+") return a + b;
  if (op == "-") return a - b;
  if (op == "EQ") return std::abs(a - b) < kEqualTolerance ? 1 : 0;
  if (op == "NE") return std::abs(a - b) >= kEqualTolerance ? 1 : 0;
  if (op == "GT") return a > b ? 1 : 0;
  if (op == "GE") return a >= b ? 1 : 0;
  if (op == "LT") return a < b ? 1 : 0;
  if (op == "LE") return a <= b ? 1 : 0;
  if (op == "AND") return a != 0 && b != 0 ? 1 : 0;
  if (op == "OR") return a != 0 || b != 0 ? 1 : 0;
  return (a != 0) != (b != 0) ? 1 : 0;  // XOR
}

double ValueReader::Parameter() {
  const int column = static_cast<int>(pos_) + 1;
  ++pos_;  // '#'
  if (Peek() == '<') {
    const std::size_t close = text_.find('>', pos_);
    if (close == std::string::npos) throw Error("'#<' without its '>'");
    const std::string name = Lower(text_.substr(pos_ + 1, close - pos_ - 1));
    pos_ = close + 1;
    return parameters_.Named(name, line_, column);
  }
  return parameters_.Numbered(RealValue(), line_, column);
}

double ValueReader::Number() {
  const std::size_t start = pos_;
  while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) ||
                                 text_[pos_] == '.')) {
    ++pos_;
  }
  const std::string digits = text_.substr(start, pos_ - start);
  char* end = nullptr;
  const double value = std::strtod(digits.c_str(), &end);
  if (digits == "." || end != digits.c_str() + digits.size()) {
    pos_ = start;
    throw Error("malformed number '" + digits + "'");
  }
  return value;
}

double ValueReader::Function() {
  const std::size_t start = pos_;
  while (pos_ < text_.size() && std::isalpha(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  std::string name = text_.substr(start, pos_ - start);
  for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (name == "EXISTS") {
    Expect('[', "after EXISTS");
    if (Peek() != '#' || pos_ + 1 >= text_.size() || text_[pos_ + 1] != '<') {
      throw Error("EXISTS takes a named parameter, e.g. EXISTS[#<depth>]");
    }
    const std::size_t close = text_.find('>', pos_);
    if (close == std::string::npos) throw Error("'#<' without its '>'");
    const bool exists = parameters_.HasNamed(Lower(text_.substr(pos_ + 2, close - pos_ - 2)));
    pos_ = close + 1;
    Expect(']', "to close EXISTS[...]");
    return exists ? 1 : 0;
  }
  if (name == "ATAN") {
    const double y = Bracketed();
    Expect('/', "in ATAN[y]/[x]");
    return std::atan2(y, Bracketed()) / kDegree;
  }
  const std::size_t at = start;
  const double x = Bracketed();
  const bool defined = (name != "ACOS" && name != "ASIN") || (x >= -1 && x <= 1);
  if (!defined || (name == "LN" && !(x > 0)) || (name == "SQRT" && !(x >= 0))) {
    throw ProgramError(line_, static_cast<int>(at) + 1, -1,
                       name + " of " + Formatted(x) + " is undefined");
  }
  if (name == "ABS") return std::abs(x);
  if (name == "ACOS") return std::acos(x) / kDegree;
  if (name == "ASIN") return std::asin(x) / kDegree;
  if (name == "COS") return std::cos(x * kDegree);
  if (name == "SIN") return std::sin(x * kDegree);
  if (name == "TAN") return std::tan(x * kDegree);
  if (name == "EXP") return std::exp(x);
  if (name == "LN") return std::log(x);
  if (name == "SQRT") return std::sqrt(x);
  if (name == "FIX") return std::floor(x);
  if (name == "FUP") return std::ceil(x);
  if (name == "ROUND") return x < 0 ? -std::floor(-x + 0.5) : std::floor(x + 0.5);
  throw ProgramError(line_, static_cast<int>(at) + 1, -1,
                     "unknown function '" + name + "'; allowed: ABS, ACOS, ASIN, ATAN[y]/[x], "
                     "COS, EXISTS, EXP, FIX, FUP, LN, ROUND, SIN, SQRT, TAN");
}

bool StartsFunction(const std::string& text, std::size_t pos) {
  std::size_t end = pos;
  while (end < text.size() && std::isalpha(static_cast<unsigned char>(text[end]))) ++end;
  while (end < text.size() && IsLineBlank(text[end])) ++end;
  return end > pos + 1 && end < text.size() && text[end] == '[';
}

}  // namespace

Rs274Parameters::Rs274Parameters() : frames_(1) {}

namespace {

// The integer a parameter number's value rounds to (rs274ngc accepts 1e-4 off).
int ParameterNumber(double number, int line, int column) {
  const double rounded = std::round(number);
  if (!(std::abs(number - rounded) < kEqualTolerance && rounded >= 1 && rounded <= kMaxNumbered)) {
    throw ProgramError(line, column, -1, "parameter number " + Formatted(number) +
                                             " is not an integer in 1-5399");
  }
  return static_cast<int>(rounded);
}

}  // namespace

double Rs274Parameters::Numbered(double number, int line, int column) const {
  const int n = ParameterNumber(number, line, column);
  if (n <= 30) return frames_.back().arguments[static_cast<std::size_t>(n - 1)];
  const auto found = numbered_.find(n);
  return found == numbered_.end() ? 0.0 : found->second;
}

void Rs274Parameters::SetNumbered(double number, double value, int line, int column) {
  const int n = ParameterNumber(number, line, column);
  if (n <= 30) {
    frames_.back().arguments[static_cast<std::size_t>(n - 1)] = value;
  } else {
    numbered_[n] = value;
  }
}

double Rs274Parameters::Named(const std::string& name, int line, int column) const {
  const auto& scope = !name.empty() && name[0] == '_' ? global_named_ : frames_.back().named;
  const auto found = scope.find(name);
  if (found == scope.end()) {
    throw ProgramError(line, column, -1, "named parameter #<" + name + "> is read before it is "
                                         "set (" + (name[0] == '_' ? "global" : "local to its "
                                         "subroutine or the main program") + ")");
  }
  return found->second;
}

bool Rs274Parameters::HasNamed(const std::string& name) const {
  const auto& scope = !name.empty() && name[0] == '_' ? global_named_ : frames_.back().named;
  return scope.count(name) > 0;
}

void Rs274Parameters::SetNamed(const std::string& name, double value) {
  auto& scope = !name.empty() && name[0] == '_' ? global_named_ : frames_.back().named;
  scope[name] = value;
}

void Rs274Parameters::PushCall(const std::vector<double>& arguments) {
  Frame frame;
  for (std::size_t k = 0; k < arguments.size() && k < frame.arguments.size(); ++k) {
    frame.arguments[k] = arguments[k];
  }
  frames_.push_back(frame);
}

void Rs274Parameters::PopCall() {
  if (frames_.size() > 1) frames_.pop_back();
}

double ReadRealValue(const std::string& text, std::size_t* pos, int line,
                     const Rs274Parameters& parameters) {
  ValueReader reader(text, *pos, line, parameters);
  const double value = reader.RealValue();
  *pos = reader.pos();
  return value;
}

bool HasRs274Syntax(const std::string& text) {
  for (std::size_t pos = 0; pos < text.size(); ++pos) {
    const char c = text[pos];
    if (c == ';') return false;
    if (c == '(') {
      pos = text.find(')', pos);
      if (pos == std::string::npos) return false;
    } else if (c == '#' || c == '[') {
      return true;
    }
  }
  return false;
}

namespace {

// `#target = value` at text[*pos] ('#'): read, to be applied after the line.
struct Assignment {
  std::string name;  // a named parameter, or
  double number = 0;  // a numbered one
  double value = 0;
  int column = 0;
};

Assignment ReadAssignment(const std::string& text, std::size_t* pos, int line,
                          const Rs274Parameters& parameters) {
  Assignment assignment;
  assignment.column = static_cast<int>(*pos) + 1;
  ++*pos;  // '#'
  while (*pos < text.size() && IsLineBlank(text[*pos])) ++*pos;
  if (*pos < text.size() && text[*pos] == '<') {
    const std::size_t close = text.find('>', *pos);
    if (close == std::string::npos) {
      throw ProgramError(line, assignment.column, -1, "'#<' without its '>'");
    }
    assignment.name = Lower(text.substr(*pos + 1, close - *pos - 1));
    *pos = close + 1;
  } else {
    assignment.number = ReadRealValue(text, pos, line, parameters);
  }
  while (*pos < text.size() && IsLineBlank(text[*pos])) ++*pos;
  if (*pos >= text.size() || text[*pos] != '=') {
    throw ProgramError(line, assignment.column, -1,
                       "a parameter outside a word must be set: #1 = 5 or #<name> = [expression]");
  }
  ++*pos;
  assignment.value = ReadRealValue(text, pos, line, parameters);
  return assignment;
}

}  // namespace

std::string SubstituteLine(const std::string& text, int line, Rs274Parameters* parameters) {
  std::string out;
  std::vector<Assignment> assignments;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == ';') {
      out += text.substr(pos);
      break;
    }
    if (c == '(') {
      const std::size_t close = text.find(')', pos);
      const std::size_t end = close == std::string::npos ? text.size() : close + 1;
      out += text.substr(pos, end - pos);
      pos = end;
      continue;
    }
    if (c == '#') {
      assignments.push_back(ReadAssignment(text, &pos, line, *parameters));
      out += ' ';
      continue;
    }
    out += c;
    ++pos;
    if (!std::isalpha(static_cast<unsigned char>(c))) continue;
    std::size_t next = pos;
    while (next < text.size() && IsLineBlank(text[next])) ++next;
    std::size_t sign = next;
    if (sign < text.size() && (text[sign] == '-' || text[sign] == '+')) ++sign;
    while (sign < text.size() && IsLineBlank(text[sign])) ++sign;
    const bool computed = sign < text.size() &&
                          (text[sign] == '[' || text[sign] == '#' || StartsFunction(text, sign));
    if (!computed) continue;
    out += Formatted(ReadRealValue(text, &pos, line, *parameters));
  }
  for (const Assignment& a : assignments) {
    if (a.name.empty()) {
      parameters->SetNumbered(a.number, a.value, line, a.column);
    } else {
      parameters->SetNamed(a.name, a.value);
    }
  }
  return out;
}

}  // namespace shapebench::controller
