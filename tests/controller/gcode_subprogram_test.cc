// Subprograms and control flow (controller/subprogram_expander.h): Fanuc M98/M99 and
// LinuxCNC's RS274NGC parameters, expressions and O-words, checked against values worked
// out by hand (comments show them); the iteration limit that stops a program that never
// ends.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller/gcode_parser.h"
#include "tests/support/gcode_test_support.h"

namespace shapebench::controller {
namespace gcode_subprogram_test {
namespace {

constexpr double kTolMm = 1e-9;  // the expander writes values with 10 decimals

// The end points of the program's blocks in mm, one coordinate (0 x, 1 y, 2 z).
std::vector<double> Ends(const Program& program, int axis) {
  std::vector<double> ends;
  for (const ProgramBlock& block : program.blocks) ends.push_back(block.end_m[axis] * 1e3);
  return ends;
}

void ExpectEnds(const Program& program, int axis, const std::vector<double>& mm) {
  const std::vector<double> ends = Ends(program, axis);
  ASSERT_EQ(ends.size(), mm.size());
  for (std::size_t k = 0; k < mm.size(); ++k) EXPECT_NEAR(ends[k], mm[k], kTolMm) << "block " << k;
}

// Tests operator precedence and order: ** before * / MOD before + - before comparisons
// before AND OR XOR, each level left to right, a unary minus tighter than **.
TEST(GcodeSubprogramTest, ExpressionPrecedence) {
  const Program program = Parse(
      "G1 X[1 + 2 * 3 ** 2] F100\n"  // 1 + 2 * 9 = 19
      "X[-2 ** 2]\n"                 // (-2) ** 2 = 4
      "X[10 - 4 - 3]\n"              // (10 - 4) - 3 = 3
      "X[2 ** 3 ** 2]\n"             // (2 ** 3) ** 2 = 64
      "X[7 MOD 3]\n"                 // 1
      "X[-7 MOD 3]\n"                // -1 + 3 = 2
      "X[1 + 2 GT 2 AND 0 OR 1 + 4]\n"  // ((3 GT 2) AND 0) OR 5 = 1
      "X[12 / 4 / 3]\n"              // (12 / 4) / 3 = 1, where the tool is: no block
      "X[1 EQ 1.00005]\n"            // equal within 1e-4: 1, no block
      "X[[2 + 3] * 4]\n",            // 20
      In(Dialect::kLinuxcnc));
  ExpectEnds(program, 0, {19, 4, 3, 64, 1, 2, 1, 20});
}

// Tests the functions: trigonometry in degrees, ATAN[y]/[x], rounding, EXISTS.
TEST(GcodeSubprogramTest, Functions) {
  const Program program = Parse(
      "G1 X[SIN[30]] Y[COS[60] * 2] Z[ATAN[1]/[1]] F100\n"  // 0.5, 1, 45
      "X[SQRT[16]] Y[ABS[-3]] Z[TAN[45]]\n"                   // 4, 3, 1
      "X[FIX[-2.5]] Y[FUP[2.1]] Z[ROUND[2.5]]\n"              // -3, 3, 3
      "X[ROUND[-2.5]] Y[EXP[0]] Z[LN[1]]\n"                   // -3, 1, 0
      "X[ACOS[0]] Y[ASIN[1]] Z[EXISTS[#<nothing>]]\n"         // 90, 90, 0
      "#<a> = 1\n"
      "X[EXISTS[#<a>]]\n",                                    // 1
      In(Dialect::kLinuxcnc));
  ExpectEnds(program, 0, {0.5, 4, -3, -3, 90, 1});
  ExpectEnds(program, 1, {1, 3, 3, 1, 90, 90});
  ExpectEnds(program, 2, {45, 1, 3, 0, 0, 0});
  ExpectError("G1 X[SQRT[-1]] F100\n", In(Dialect::kLinuxcnc), 1, 6, "SQRT of -1");
  ExpectError("G1 X[1 / 0] F100\n", In(Dialect::kLinuxcnc), 1, 8, "division by zero");
}

// Tests numbered and named parameters: an assignment takes effect after its line; #1-#30
// and #<name> are local to a call, #<_name> global; a name read before it is set is
// refused.
TEST(GcodeSubprogramTest, ParameterScopes) {
  const Program program = Parse(
      "#1 = 5\n"
      "#1 = 7 G1 X#1 F100\n"          // X5: the old value
      "G1 X#1\n"                      // X7
      "#<depth> = -2\n"
      "G1 Z#<DEPTH>\n"                // names are case-insensitive: Z-2
      "o100 sub\n"
      "  #<_out> = [#1 * 2]\n"
      "  #<depth> = 99\n"             // local to the call
      "  #1 = 1000\n"
      "o100 endsub\n"
      "o100 call [4]\n"
      "G1 X#<_out> Z#<depth> Y#1\n",  // X8, Z-2, Y7 (#1 back to the main program's)
      In(Dialect::kLinuxcnc));
  ExpectEnds(program, 0, {5, 7, 7, 8});
  ExpectEnds(program, 2, {0, 0, -2, -2});
  ExpectEnds(program, 1, {0, 0, 0, 7});
  ExpectError("o1 sub\n#<x> = 1\no1 endsub\no1 call\nG1 X#<x> F100\n", In(Dialect::kLinuxcnc), 5,
              5, "named parameter #<x> is read before it is set");
}

// Tests nested subroutine calls with arguments and a return value (#<_value>).
TEST(GcodeSubprogramTest, NestedSubroutines) {
  const Program program = Parse(
      "o<square> sub\n"
      "  o<square> return [#1 * #1]\n"
      "o<square> endsub\n"
      "o200 sub\n"                          // #1 + square(#2)
      "  o<square> call [#2]\n"
      "  G1 X[#1 + #<_value>] F100\n"
      "o200 endsub\n"
      "o200 call [1] [3]\n"                 // X[1 + 9] = 10
      "o200 call [2] [4]\n",                // X[2 + 16] = 18
      In(Dialect::kLinuxcnc));
  ExpectEnds(program, 0, {10, 18});
}

// Tests if/elseif/else, while, do/while with break, and repeat with continue.
TEST(GcodeSubprogramTest, ControlFlow) {
  const Program program = Parse(
      "#1 = 0\n"
      "o10 while [#1 LT 3]\n"
      "  #1 = [#1 + 1]\n"
      "  G1 X[#1 * 10] F100\n"              // X10, X20, X30
      "o10 endwhile\n"
      "#2 = 0\n"
      "o30 do\n"
      "  #2 = [#2 + 1]\n"
      "  o31 if [#2 EQ 3]\n"
      "    o30 break\n"
      "  o31 elseif [#2 EQ 2]\n"
      "    G1 Y20\n"                        // the second pass
      "  o31 else\n"
      "    G1 Y10\n"                        // the first pass
      "  o31 endif\n"
      "o30 while [1]\n"
      "#3 = 0\n"
      "o40 repeat [4]\n"
      "  #3 = [#3 + 1]\n"
      "  o41 if [#3 EQ 2]\n"
      "    o40 continue\n"
      "  o41 endif\n"
      "  G1 Z#3\n"                          // Z1, Z3, Z4 (2 is skipped)
      "o40 endrepeat\n",
      In(Dialect::kLinuxcnc));
  ExpectEnds(program, 0, {10, 20, 30, 30, 30, 30, 30, 30});
  ExpectEnds(program, 1, {0, 0, 0, 10, 20, 20, 20, 20});
  ExpectEnds(program, 2, {0, 0, 0, 0, 0, 1, 3, 4});
}

// Tests that a loop that never ends is refused at its line once the iteration limit is
// crossed, and that an unmatched O-word is refused where it stands.
TEST(GcodeSubprogramTest, EndlessLoopAndUnmatchedOWords) {
  ExpectError("o1 do\no1 while [1]\n", In(Dialect::kLinuxcnc, 1000), 2, 1,
              "more than 1000 loop passes and subroutine calls by 'o1 while' (line 2), more "
              "than program_max_iterations allows");
  ExpectError("o7 while [1]\nG91 G1 X1 F100\no7 endwhile\n", In(Dialect::kLinuxcnc, 50), 1, 1,
              "more than 50 loop passes");
  ExpectError("G1 X1 F100\no2 endwhile\n", In(Dialect::kLinuxcnc), 2, 1,
              "'o2 endwhile' (line 2) has no open 'o2 while' before it");
  ExpectError("o3 if [1]\nG1 X1 F100\n", In(Dialect::kLinuxcnc), 1, 1, "is never closed");
  ExpectError("o4 call\n", In(Dialect::kLinuxcnc), 1, 1, "calls a subroutine that is not in "
              "this file");
}

// Tests Fanuc M98 with L and with a packed repeat count, nested subprograms after M30,
// and L0.
TEST(GcodeSubprogramTest, FanucSubprograms) {
  const Program program = Parse(
      "O0001 (MAIN)\n"
      "G90 G0 X0 Y0\n"
      "M98 P1000 L2\n"       // X10, X20
      "M98 P21000\n"         // packed: twice O1000: X30, X40
      "M98 P2000 L0\n"       // L0: no call
      "M98 P2000\n"          // Y5 then O1000 once: X50
      "M30\n"
      "O1000 (SUB)\n"
      "G91 G1 X10 F100\n"
      "G90\n"
      "M99\n"
      "O2000\n"
      "G1 Y5 F100\n"
      "M98 P1000\n"
      "M99\n",
      In(Dialect::kFanuc));
  ExpectEnds(program, 0, {10, 20, 30, 40, 40, 50});
  ExpectEnds(program, 1, {0, 0, 0, 0, 5, 5});
  EXPECT_EQ(program.blocks[0].source_line, 9);
}

// Tests the Fanuc refusals: M99 in the main program loops until the limit, a missing
// subprogram, a block after M30 that is no subprogram, and M98 outside fanuc.
TEST(GcodeSubprogramTest, FanucRefusals) {
  ExpectError("G91 G1 X1 F100\nM99\n", In(Dialect::kFanuc, 100), 2, 1,
              "more than 100 loop passes, subprogram calls and M99 jumps");
  ExpectError("M98 P1234\nM30\n", In(Dialect::kFanuc), 1, 5, "M98 calls O1234, which is not in "
              "this file");
  ExpectError("M98 P1\nM30\nG1 X5\nO1\nG1 X1 F100\nM99\n", In(Dialect::kFanuc), 3, 1,
              "a block after the program end (M2/M30) of line 2");
  ExpectError("M98 P1\nM30\n", In(Dialect::kLinuxcnc), 1, 1, "'M98' (subprogram call or "
              "return) is fanuc's");
  ExpectError("G1 X1 F100\nO1\nG1 X2\nM99\nM98 P1\n", In(Dialect::kFanuc), 2, 1,
              "the program runs into subprogram O1 without M2/M30");
}

}  // namespace
}  // namespace gcode_subprogram_test
}  // namespace shapebench::controller
