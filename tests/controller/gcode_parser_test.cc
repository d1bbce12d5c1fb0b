// ParseGcode: every supported word, the lexical rules, and errors at their exact line and
// column. Expected positions are worked by hand in mm and compared within 1e-12 m (the
// mm -> m conversion rounds at 1e-16 m; the R centre's square root at about 1e-18 m).
#include "controller/gcode_parser.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace shapebench::controller {
namespace {

constexpr double kTolM = 1e-12;

void ExpectMm(const Eigen::Vector3d& actual_m, double x_mm, double y_mm, double z_mm) {
  EXPECT_NEAR(actual_m.x(), x_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.y(), y_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.z(), z_mm * 1e-3, kTolM);
}

ProgramError ParseError(const std::string& text) {
  try {
    ParseGcode(text);
  } catch (const ProgramError& error) {
    return error;
  }
  ADD_FAILURE() << "no ProgramError for:\n" << text;
  return ProgramError(0, 0, -1, "");
}

void ExpectError(const std::string& text, int line, int column,
                 const std::string& message_part) {
  const ProgramError error = ParseError(text);
  EXPECT_EQ(error.line(), line) << error.what();
  EXPECT_EQ(error.column(), column) << error.what();
  EXPECT_NE(error.message().find(message_part), std::string::npos) << error.what();
}

// Tests G0 and G1 with X, Y, Z and F, and that N is ignored.
TEST(GcodeParserTest, RapidLinearAxesFeedAndN) {
  const Program program = ParseGcode(
      "N10 G0 X10 Y20 Z30\n"
      "N20 G1 X0 F600\n");
  ASSERT_EQ(program.blocks.size(), 2u);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kRapid);
  ExpectMm(program.blocks[0].end_m, 10, 20, 30);
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kLinear);
  ExpectMm(program.blocks[1].end_m, 0, 20, 30);
  EXPECT_DOUBLE_EQ(program.blocks[1].feed_m_s, 0.01);  // 600 mm/min
  EXPECT_EQ(program.blocks[0].source_line, 1);
  EXPECT_EQ(program.blocks[1].source_line, 2);
}

// Tests that the program starts at start_m and G91 moves from there.
TEST(GcodeParserTest, StartPosition) {
  const Program program = ParseGcode("G91 X5\n", Eigen::Vector3d(0.001, 0.002, 0.003));
  ASSERT_EQ(program.blocks.size(), 1u);
  ExpectMm(program.blocks[0].end_m, 6, 2, 3);
}

// Tests G90/G91, F and the motion G carried over to later blocks.
TEST(GcodeParserTest, ModalCarryOver) {
  const Program program = ParseGcode(
      "G91 G0 X10 F1200\n"  // rapid, incremental: (10, 0)
      "Y5\n"                // still rapid, incremental: (10, 5)
      "G1 X-2\n"            // linear: (8, 5), F 1200
      "G90 Y0\n"            // absolute: (8, 0)
      "X1\n");              // (1, 0)
  ASSERT_EQ(program.blocks.size(), 5u);
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kRapid);
  ExpectMm(program.blocks[1].end_m, 10, 5, 0);
  EXPECT_EQ(program.blocks[2].kind, MotionKind::kLinear);
  ExpectMm(program.blocks[2].end_m, 8, 5, 0);
  ExpectMm(program.blocks[3].end_m, 8, 0, 0);
  ExpectMm(program.blocks[4].end_m, 1, 0, 0);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(program.blocks[i].feed_m_s, 0.02);
  EXPECT_EQ(program.blocks[4].kind, MotionKind::kLinear);
}

// Tests arcs by I/J in G17, K/I in G18 and J/K in G19, G2 and G3.
TEST(GcodeParserTest, ArcsByIJKInEachPlane) {
  const Program program = ParseGcode(
      "G17 G3 X0 Y10 I-10 J0\n"
      "G18 G2 X10 Z10 I10 K0\n"
      "G19 G3 Y10 Z10 J0 K10\n",
      Eigen::Vector3d(0.010, 0, 0));
  ASSERT_EQ(program.blocks.size(), 3u);
  // G17: (10, 0) -> (0, 10) about (0, 0).
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kArcCcw);
  EXPECT_EQ(program.blocks[0].plane, Plane::kXY);
  ExpectMm(program.blocks[0].center_m, 0, 0, 0);
  // G18 from (0, 10, 0): (x 0, z 0) -> (x 10, z 10) about (x 10, z 0).
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kArcCw);
  EXPECT_EQ(program.blocks[1].plane, Plane::kZX);
  ExpectMm(program.blocks[1].center_m, 10, 10, 0);
  ExpectMm(program.blocks[1].end_m, 10, 10, 10);
  // G19 from (10, 10, 10): (y 10, z 10) -> (y 10, z 10) is a full circle about (y 10, z 20).
  EXPECT_EQ(program.blocks[2].plane, Plane::kYZ);
  ExpectMm(program.blocks[2].center_m, 10, 10, 20);
  EXPECT_EQ(program.blocks[2].end_m, program.blocks[2].start_m);
}

// Tests arcs by R: the centre of (0,0) -> (6,0) with |R| 5 is (3, -4) for G2 R5 and
// G3 R-5, (3, 4) for G3 R5 and G2 R-5 (3-4-5 triangle on the chord's midpoint).
TEST(GcodeParserTest, ArcsByR) {
  const Program program = ParseGcode(
      "G2 X6 R5\n"
      "G0 X0\n"
      "G3 X6 R5\n"
      "G0 X0\n"
      "G2 X6 R-5\n"
      "G0 X0\n"
      "G3 X6 R-5\n");
  ASSERT_EQ(program.blocks.size(), 7u);
  ExpectMm(program.blocks[0].center_m, 3, -4, 0);
  ExpectMm(program.blocks[2].center_m, 3, 4, 0);
  ExpectMm(program.blocks[4].center_m, 3, 4, 0);
  ExpectMm(program.blocks[6].center_m, 3, -4, 0);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kArcCw);
  EXPECT_EQ(program.blocks[6].kind, MotionKind::kArcCcw);
}

// Tests a full circle by I/J and a helix (Z changes along an XY arc).
TEST(GcodeParserTest, FullCircleAndHelix) {
  const Program program = ParseGcode(
      "G2 I10 J0\n"               // full circle about (10, 0)
      "G3 X0 Y0 Z-5 I0 J7.5\n");  // full helical turn about (0, 7.5), down 5
  ASSERT_EQ(program.blocks.size(), 2u);
  ExpectMm(program.blocks[0].center_m, 10, 0, 0);
  EXPECT_EQ(program.blocks[0].end_m, program.blocks[0].start_m);
  ExpectMm(program.blocks[1].end_m, 0, 0, -5);
  ExpectMm(program.blocks[1].center_m, 0, 7.5, 0);
}

// Tests G4 with P in milliseconds and X in seconds, also written G04.
TEST(GcodeParserTest, DwellPAndX) {
  const Program program = ParseGcode("G4 P250\nG04 X1.5\ng4p0\n");
  ASSERT_EQ(program.blocks.size(), 3u);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(program.blocks[0].dwell_s, 0.25);
  EXPECT_DOUBLE_EQ(program.blocks[1].dwell_s, 1.5);
  EXPECT_DOUBLE_EQ(program.blocks[2].dwell_s, 0.0);
}

// Tests the two-digit forms G00-G04 and G17, G21, G90.
TEST(GcodeParserTest, TwoDigitGCodes) {
  const Program program = ParseGcode(
      "G21 G17 G90\n"
      "G00 X1\n"
      "G01 X2\n"
      "G02 X4 I1\n"
      "G03 X2 I-1\n"
      "G04 P1\n");
  ASSERT_EQ(program.blocks.size(), 5u);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kRapid);
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kLinear);
  EXPECT_EQ(program.blocks[2].kind, MotionKind::kArcCw);
  ExpectMm(program.blocks[2].center_m, 3, 0, 0);
  EXPECT_EQ(program.blocks[3].kind, MotionKind::kArcCcw);
  ExpectMm(program.blocks[3].center_m, 3, 0, 0);
  EXPECT_EQ(program.blocks[4].kind, MotionKind::kDwell);
}

// Tests that comments, blank lines, `%` lines and CRLF line ends are skipped, and
// source_line counts every line.
TEST(GcodeParserTest, CommentsBlankLinesPercentAndCrlf) {
  const Program program = ParseGcode(
      "%\r\n"
      "(a program; with a semicolon in a comment)\r\n"
      "\r\n"
      "G1 (move) X10 ; to X10 (not a comment start)\r\n"
      "  ; only a comment\n"
      "\t(only) (comments)\n"
      "Y5;\n"
      "% (end)\n"
      "\n"
      "(after the end)\n");
  ASSERT_EQ(program.blocks.size(), 2u);
  ExpectMm(program.blocks[0].end_m, 10, 0, 0);
  EXPECT_EQ(program.blocks[0].source_line, 4);
  ExpectMm(program.blocks[1].end_m, 10, 5, 0);
  EXPECT_EQ(program.blocks[1].source_line, 7);
}

// Tests lowercase letters, words without spaces, spaces between letter and number, and
// the number forms .5, 5., +3, -0.5.
TEST(GcodeParserTest, LowercaseSpacingAndNumberForms) {
  const Program program = ParseGcode(
      "g1x10y-5.5f600\n"
      "X 20 Y\t-1\n"
      "x.5 y5. z+3\n"
      "G91X-0.5\n");
  ASSERT_EQ(program.blocks.size(), 4u);
  ExpectMm(program.blocks[0].end_m, 10, -5.5, 0);
  EXPECT_DOUBLE_EQ(program.blocks[0].feed_m_s, 0.01);
  ExpectMm(program.blocks[1].end_m, 20, -1, 0);
  ExpectMm(program.blocks[2].end_m, 0.5, 5, 3);
  ExpectMm(program.blocks[3].end_m, 0, 5, 3);
}

// Tests that an empty text, or only comments, gives an empty program.
TEST(GcodeParserTest, EmptyProgram) {
  EXPECT_TRUE(ParseGcode("").blocks.empty());
  EXPECT_TRUE(ParseGcode("%\n(nothing)\n%\n").blocks.empty());
}

// Tests unsupported words at their line and the letter's column; the part-program words
// the parser would drop (M, S, T, G54, O) under strict options, G41 refused as cutter
// compensation (tests/controller/gcode_ignored_words_test.cc has the rest).
TEST(GcodeParserTest, UnsupportedWords) {
  ExpectError("G1 X10\nG1 X20 G68\n", 2, 8,
              "unsupported word 'G68' is not read by the bench (dialect fanuc); allowed: G0-G3, "
              "G4 with P (ms, no decimal point) or X/U (s), G17-G19, G20, G21, G28, G30");
  ExpectError("N10 Q1000\n", 1, 5, "'Q1000': Q is allowed only with linuxcnc's G64 P");
  GcodeOptions strict;
  strict.strict = true;
  auto strict_error = [&](const std::string& text) {
    try {
      ParseGcode(text, Eigen::Vector3d::Zero(), {}, strict);
    } catch (const ProgramError& error) {
      return error;
    }
    ADD_FAILURE() << "no ProgramError for:\n" << text;
    return ProgramError(0, 0, -1, "");
  };
  auto expect_strict = [&](const std::string& text, int line, int column, const std::string& part) {
    const ProgramError error = strict_error(text);
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_EQ(error.column(), column) << error.what();
    EXPECT_NE(error.message().find(part), std::string::npos) << error.what();
  };
  expect_strict("G1 X10\nG1 X20 M3\n", 2, 8, "'M3' is not modelled by the bench");
  expect_strict("N10 S1000\n", 1, 5, "'S1000' is not modelled");
  ExpectError("\n\nG41 X1\n", 3, 1, "'G41' (cutter radius compensation)");
  expect_strict("T1\n", 1, 1, "'T1' is not modelled");
  expect_strict("G54\n", 1, 1, "'G54' is not modelled");
  expect_strict("O1000\n", 1, 1, "'O1000' is not modelled");
  expect_strict("x1 m03\n", 1, 4, "'M03' is not modelled");
  ExpectError("G1 X1 #1=5\n", 1, 7, "'#' (an RS274NGC parameter or expression) is LinuxCNC's");
  ExpectError("/G1 X1\n", 1, 1, "unexpected character '/'");
}

// Tests malformed numbers at the word's letter.
TEST(GcodeParserTest, MalformedNumbers) {
  ExpectError("G1 X1.2.3\n", 1, 4, "malformed number 'X1.2.3'");
  ExpectError("G0\nG1 X\n", 2, 4, "malformed number: 'X' has no number");
  ExpectError("G1 X (comment)\n", 1, 4, "malformed number: 'X' has no number");
  ExpectError("G1 X10 Y-\n", 1, 8, "malformed number 'Y-'");
  ExpectError("G1 Xabc\n", 1, 4, "malformed number: 'X' is followed by 'a', not a number");
  ExpectError("G1.5 X1\n", 1, 1, "unsupported word 'G1.5'");
  ExpectError("G1.2.3 X1\n", 1, 1, "malformed number 'G1.2.3': G takes an unsigned number");
  ExpectError("G-1\n", 1, 1, "malformed number 'G-1'");
  ExpectError("N1.5 X1\n", 1, 1, "malformed number 'N1.5'");
  ExpectError("X1-2\n", 1, 1, "malformed number 'X1-2'");
  ExpectError("X.\n", 1, 1, "malformed number 'X.'");
  ExpectError("X 1 0\n", 1, 5, "unexpected character '0'");
}

// Tests the arc errors at their word: K in G17, R with I, end off the circle, R full circle.
TEST(GcodeParserTest, ArcErrors) {
  ExpectError("G17\nG2 X10 Y0 K5\n", 2, 11,
              "'K5' is not a centre word of G17 (XY plane); allowed: I, J");
  ExpectError("G2 X10 Y0 I5 R5\n", 1, 14, "an arc takes its centre as I/J/K or as R, not both");
  ExpectError("G1 X1\nG2 X10 Y0 I5\n", 2, 11,
              "arc end point is not on the circle: start radius 5 mm, end radius 4 mm");
  ExpectError("G2 X0 Y0 R5\n", 1, 10, "R cannot describe a full circle");
  ExpectError("G2 X10\n", 1, 1, "an arc (G2) needs its centre");
}

// Tests a repeated word and an unclosed comment at their line and column.
TEST(GcodeParserTest, RepeatedWordUnclosedComment) {
  ExpectError("G1 X10 Y2 X20\n", 1, 11, "word X repeated in one block ('X10' and 'X20')");
  ExpectError("G1 G01 X1\n", 1, 4, "word 'G01' repeated");
  ExpectError("G1 G2 X1 I1\n", 1, 4, "'G1' and 'G2' in one block");
  ExpectError("G1 X10\nG1 X20 (no end\n", 2, 8, "unclosed comment");
}

// Tests that `%` may only open and close the program.
TEST(GcodeParserTest, PercentErrors) {
  ExpectError("G1 X1 %\n", 1, 7, "'%' must stand alone on its line");
  ExpectError("% G1 X1\n", 1, 1, "'%' must stand alone on its line");
  ExpectError("%\nX1\n%\nX2\n", 4, 1, "a block after the closing '%' of line 3");
  ExpectError("X1\n%\n%\n", 3, 1, "'%' after the closing '%' of line 2");
}

// Tests the G4 and feed errors from the text.
TEST(GcodeParserTest, DwellAndFeedErrors) {
  ExpectError("G4 P-10\n", 1, 4, "dwell must be >= 0");
  ExpectError("G4 P10 Y1\n", 1, 8, "'Y1' is not allowed in a G4 (dwell) block");
  ExpectError("G1 X1 F0\n", 1, 7, "F must be > 0");
  ExpectError("G1 X1 P5\n", 1, 7, "P is allowed only with G4 (dwell)");
}

}  // namespace
}  // namespace shapebench::controller
