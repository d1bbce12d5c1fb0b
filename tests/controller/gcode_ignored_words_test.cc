// ParseGcode on real part programs: the words outside the motion (O, T, S, H, D, M, G43,
// G54...) are dropped with one warning and leave the commanded path exactly as without
// them; words that would change the motion are refused at their line and column;
// GcodeOptions::strict refuses the dropped ones.
#include <string>

#include <gtest/gtest.h>

#include "controller/controller.h"
#include "controller/gcode_parser.h"

namespace shapebench::controller {
namespace {

constexpr double kIgnoredWordsTolM = 1e-12;

// A pocket with a tool-change header, and the same program with only the modelled words.
const char* const kWithHeader =
    "%\n"
    "O1000 (POCKET WITH TOOL CHANGE)\n"
    "N10 G90 G17 G21 G40 G49 G80 G94\n"
    "N20 T1 M6 ; flat end mill\n"
    "N30 G54\n"
    "N40 S8000 M3\n"
    "N50 G0 X10 Y10\n"
    "N60 G43 H1 Z5 M8\n"
    "N70 G1 Z-2 F1000\n"
    "N80 X50 F3000\n"
    "N90 G3 X60 Y20 R10\n"
    "N100 G1 Y30\n"
    "N110 X10\n"
    "N120 G0 Z25 M9\n"
    "N130 M5\n"
    "N140 M30\n"
    "%\n";
const char* const kStripped =
    "%\n"
    "(POCKET WITH TOOL CHANGE)\n"
    "N10 G90 G17 G21\n"
    "N20\n"
    "N30\n"
    "N40\n"
    "N50 G0 X10 Y10\n"
    "N60 Z5\n"
    "N70 G1 Z-2 F1000\n"
    "N80 X50 F3000\n"
    "N90 G3 X60 Y20 R10\n"
    "N100 G1 Y30\n"
    "N110 X10\n"
    "N120 G0 Z25\n"
    "N130\n"
    "N140\n"
    "%\n";

ControllerConfig IgnoredWordsConfig() {
  ControllerConfig c;
  c.feed_mm_min = 6000;
  c.rapid_feed_mm_min = 12000;
  c.accel_time_s = 0.06;
  return c;
}

ProgramError IgnoredWordsParseError(const std::string& text, const GcodeOptions& options = {}) {
  try {
    ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
  } catch (const ProgramError& error) {
    return error;
  }
  ADD_FAILURE() << "no ProgramError for:\n" << text;
  return ProgramError(0, 0, -1, "");
}

void ExpectIgnoredWordsError(const std::string& text, int line, int column, const std::string& message_part,
                 const GcodeOptions& options = {}) {
  const ProgramError error = IgnoredWordsParseError(text, options);
  EXPECT_EQ(error.line(), line) << error.what();
  EXPECT_EQ(error.column(), column) << error.what();
  EXPECT_NE(error.message().find(message_part), std::string::npos) << error.what();
}

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Tests that a program with O, T, M6, S, M3, G43 H, G54, M8/M9, M5 and M30 runs, warns
// once, and commands exactly the motion of the same program stripped of those words.
TEST(GcodeIgnoredWordsTest, HeaderWordsLeaveTheCommandUnchanged) {
  const Program with = ParseGcode(kWithHeader);
  const Program stripped = ParseGcode(kStripped);
  ASSERT_EQ(with.blocks.size(), stripped.blocks.size());
  ASSERT_EQ(with.blocks.size(), 8u);
  for (std::size_t i = 0; i < with.blocks.size(); ++i) {
    EXPECT_EQ(with.blocks[i].kind, stripped.blocks[i].kind);
    EXPECT_LE((with.blocks[i].end_m - stripped.blocks[i].end_m).norm(), kIgnoredWordsTolM);
    EXPECT_LE((with.blocks[i].center_m - stripped.blocks[i].center_m).norm(), kIgnoredWordsTolM);
    EXPECT_EQ(with.blocks[i].source_line, stripped.blocks[i].source_line);
  }
  EXPECT_TRUE(stripped.warnings.empty());
  ASSERT_EQ(with.warnings.size(), 1u);
  EXPECT_EQ(with.warnings[0],
            "ignored words not modelled by the bench: O1000 (line 2), T1 (line 4), M6 (line 4), "
            "G54 (line 5), S8000 (line 6), M3 (line 6), G43 H1 (line 8), M8 (line 8), M9 "
            "(line 14), M5 (line 15), M30 (line 16); tool-length and work offsets do not move "
            "the commanded path (the bench has no tool or offset table)");

  const MultiAxisCommand a = GenerateProgramCommand(IgnoredWordsConfig(), with);
  const MultiAxisCommand b = GenerateProgramCommand(IgnoredWordsConfig(), stripped);
  ASSERT_EQ(a.num_ticks(), b.num_ticks());
  const std::vector<Eigen::Vector3d> pa = a.Positions();
  const std::vector<Eigen::Vector3d> pb = b.Positions();
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t k = 0; k < pa.size(); ++k) EXPECT_LE((pa[k] - pb[k]).norm(), kIgnoredWordsTolM) << k;
  EXPECT_LE((pa.back() - Eigen::Vector3d(10e-3, 30e-3, 25e-3)).norm(), kIgnoredWordsTolM);
  // The one warning reaches the command, where the CLI prints it (bench/cli/main.cc).
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_EQ(a.warnings[0], with.warnings[0]);
  EXPECT_TRUE(b.warnings.empty());
}

// Tests that a word repeated over many blocks is listed once, at its first line, and that
// the offset sentence appears only with an offset word.
TEST(GcodeIgnoredWordsTest, EachWordListedOnce) {
  const Program program = ParseGcode("G1 X1 M8\nX2 M8\nX3 m8\nS100 X4\nS200\n");
  ASSERT_EQ(program.warnings.size(), 1u);
  const std::string& warning = program.warnings[0];
  EXPECT_EQ(warning, "ignored words not modelled by the bench: M8 (line 1), S100 (line 4), "
                     "S200 (line 5)");
  EXPECT_EQ(Count(warning, "M8"), 1u);
  EXPECT_EQ(program.blocks.size(), 4u);
}

// Tests that G40, G49, G80 and G94 (the state the bench models) are accepted without a
// warning and without changing the path.
TEST(GcodeIgnoredWordsTest, ModelledStateWordsAreSilent) {
  const Program program = ParseGcode("G40 G49 G80 G94 G1 X10 F600\nG80 Y5\n");
  EXPECT_TRUE(program.warnings.empty());
  ASSERT_EQ(program.blocks.size(), 2u);
  EXPECT_LE((program.blocks[1].end_m - Eigen::Vector3d(10e-3, 5e-3, 0)).norm(), kIgnoredWordsTolM);
}

// Tests that words changing the motion the bench does not model are refused at their line
// and column, saying why.
TEST(GcodeIgnoredWordsTest, MotionChangingWordsRefusedAtLineAndColumn) {
  ExpectIgnoredWordsError("G1 X10 F600\nG41 D1 X20\n", 2, 1, "cutter radius compensation");
  ExpectIgnoredWordsError("G1 X10 F600\nX20 g42\n", 2, 5, "'G42' (cutter radius compensation)");
  ExpectIgnoredWordsError("G95 G1 X1 F0.1\n", 1, 1, "feed per revolution");
  ExpectIgnoredWordsError("S200 G96 X1\n", 1, 6, "constant surface speed");
  ExpectIgnoredWordsError("G0 X0 Y0\n\nG98 G81 X10 Y10 Z-5 R2 F100\n", 3, 5, "'G81' is a canned cycle");
  ExpectIgnoredWordsError("G53 G0 Z0\n", 1, 1, "machine coordinates");
  ExpectIgnoredWordsError("M98 P1000\n", 1, 5, "M98 calls O1000, which is not in this file");
  ExpectIgnoredWordsError("G1 X1\nM30\n  G1 X2\n", 3, 3, "after the program end (M2/M30) of line 2");
  // Before a motion-changing word, an ignored word in the same block is no excuse.
  ExpectIgnoredWordsError("T1 M6 G41 X1\n", 1, 7, "G41");
}

// Tests that strict options refuse each word the parser would otherwise drop, at its line
// and column, and accept the modelled state words.
TEST(GcodeIgnoredWordsTest, StrictRefusesIgnoredWords) {
  GcodeOptions strict;
  strict.strict = true;
  strict.strict_key = "program_strict";
  ExpectIgnoredWordsError("G1 X1 F600\nT1 M6\n", 2, 1, "'T1' is not modelled by the bench, and "
                                           "program_strict refuses", strict);
  ExpectIgnoredWordsError("G1 X1 F600\nX2 M3\n", 2, 4, "'M3'", strict);
  ExpectIgnoredWordsError("O1000\n", 1, 1, "'O1000'", strict);
  ExpectIgnoredWordsError("G0 X1\nG43 H1 Z5\n", 2, 1, "'G43'", strict);
  ExpectIgnoredWordsError("G55 X1\n", 1, 1, "'G55'", strict);
  EXPECT_TRUE(ParseGcode("G40 G49 G80 G94 G1 X1 F600\n", Eigen::Vector3d::Zero(), {}, strict)
                  .warnings.empty());
}

}  // namespace
}  // namespace shapebench::controller
