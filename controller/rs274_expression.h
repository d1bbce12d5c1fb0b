// LinuxCNC's RS274NGC parameters and expressions (program_dialect: linuxcnc), as its
// manual defines them (docs/gcode.md):
//   - Numbered parameters #1-#5399 (0 until set); #1-#30 are a subroutine call's
//     arguments, local to the call. Named parameters: #<_name> global, #<name> local to
//     the subroutine (or the main program) that sets it; names are read without spaces and
//     case-insensitive; reading one that is not set is an error.
//   - A real value: a number, -value, +value, #value (indirection: #[1+2], ##1),
//     #<name>, [expression], or a function: ABS ACOS ASIN COS EXP FIX FUP ROUND LN SIN
//     SQRT TAN of [expression] (angles in degrees), ATAN[y]/[x], EXISTS[#<name>].
//   - Binary operators, loosest last, left to right within a level: ** ; * / MOD ;
//     + - ; EQ NE GT GE LT LE ; AND OR XOR. EQ/NE compare within 1e-4 (rs274ngc's
//     TOLERANCE_EQUAL); MOD's result takes the divisor's magnitude's sign (>= 0);
//     ROUND rounds half away from zero. A unary minus binds tighter than ** (-2**2 = 4).
//   - Assignments (#1 = 5, #<depth> = [#1 * 2]) take effect after their whole line is
//     read (a word on that line reads the old value).
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace shapebench::controller {

class Rs274Parameters {
 public:
  Rs274Parameters();

  // Throws ProgramError at (line, column) for a number out of 1-5399 or a name not set.
  double Numbered(double number, int line, int column) const;
  void SetNumbered(double number, double value, int line, int column);
  double Named(const std::string& name, int line, int column) const;
  bool HasNamed(const std::string& name) const;
  void SetNamed(const std::string& name, double value);

  // A subroutine call: #1-#30 are `arguments` (the rest 0) and named locals start empty.
  void PushCall(const std::vector<double>& arguments);
  void PopCall();
  std::size_t depth() const { return frames_.size() - 1; }

 private:
  struct Frame {
    std::array<double, 30> arguments{};
    std::map<std::string, double> named;
  };
  std::vector<Frame> frames_;  // frames_[0]: the main program
  std::map<int, double> numbered_;  // #31-#5399
  std::map<std::string, double> global_named_;
};

// Reads the real value that starts at text[*pos] (skipping blanks) and moves *pos past
// it. Throws ProgramError at the offending column of `line`.
double ReadRealValue(const std::string& text, std::size_t* pos, int line,
                     const Rs274Parameters& parameters);

// Whether `text` holds parameters or expressions ('#' or '[' outside comments).
bool HasRs274Syntax(const std::string& text);

// The line with every word's computed value written out as a number (X[#1*2] -> X10)
// and its assignments removed, then applied to `parameters`. Comments stay.
std::string SubstituteLine(const std::string& text, int line, Rs274Parameters* parameters);

}  // namespace shapebench::controller
