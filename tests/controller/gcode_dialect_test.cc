// ParseGcode under each program_dialect (controller/gcode_dialect.h): dwell units, G20,
// arc-centre modes, the arc-end tolerance, path modes, G28/G30 and the messages that name
// the dialect. Expected values are worked by hand in mm and s (comments show them) from
// the manuals' definitions (docs/gcode.md); positions within 1e-12 m.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "controller/gcode_parser.h"
#include "tests/support/gcode_test_support.h"

namespace shapebench::controller {
namespace gcode_dialect_test {
namespace {

constexpr double kTolM = 1e-12;

void ExpectMm(const Eigen::Vector3d& actual_m, double x_mm, double y_mm, double z_mm) {
  EXPECT_NEAR(actual_m.x(), x_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.y(), y_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.z(), z_mm * 1e-3, kTolM);
}

// Tests G4's time per dialect: Fanuc P in ms (no decimal point) or X/U in s; LinuxCNC and
// grbl P in s; a decimal P in fanuc refused naming the dialects that read seconds.
TEST(GcodeDialectTest, DwellUnitsPerDialect) {
  const GcodeOptions fanuc = In(Dialect::kFanuc);
  EXPECT_DOUBLE_EQ(Parse("G4 P500\n", fanuc).blocks.at(0).dwell_s, 0.5);
  EXPECT_DOUBLE_EQ(Parse("G04 X1.5\n", fanuc).blocks.at(0).dwell_s, 1.5);
  EXPECT_DOUBLE_EQ(Parse("G4 U2\n", fanuc).blocks.at(0).dwell_s, 2.0);
  EXPECT_DOUBLE_EQ(Parse("G4 P0.5\n", In(Dialect::kLinuxcnc)).blocks.at(0).dwell_s, 0.5);
  EXPECT_DOUBLE_EQ(Parse("G4 P2\n", In(Dialect::kGrbl)).blocks.at(0).dwell_s, 2.0);
  ExpectError("G4 P0.5\n", fanuc, 1, 4, "linuxcnc and grbl read a decimal P in seconds");
  ExpectError("G4 X1\n", In(Dialect::kLinuxcnc), 1, 1, "P in s (e.g. P0.5) in the linuxcnc");
  ExpectError("G4 U1\n", In(Dialect::kGrbl), 1, 4, "U is allowed only as fanuc's G4");
}

// Tests that LinuxCNC and grbl run G4 and G0 in one block as a dwell, then the move, and
// that fanuc refuses the block.
TEST(GcodeDialectTest, DwellThenMoveInOneBlock) {
  for (const Dialect dialect : {Dialect::kLinuxcnc, Dialect::kGrbl}) {
    const Program program = Parse("G0 G4 P1 X10\n", In(dialect));
    ASSERT_EQ(program.blocks.size(), 2u);
    EXPECT_EQ(program.blocks[0].kind, MotionKind::kDwell);
    EXPECT_DOUBLE_EQ(program.blocks[0].dwell_s, 1.0);
    EXPECT_EQ(program.blocks[1].kind, MotionKind::kRapid);
    ExpectMm(program.blocks[1].end_m, 10, 0, 0);
  }
  ExpectError("G0 G4 P1 X10\n", In(Dialect::kFanuc), 1, 1, "cannot share a block with 'G0'");
}

// Tests G20/G21 in any block: lengths, centres and F scaled by 25.4 under G20.
TEST(GcodeDialectTest, InchAndMmInAnyBlock) {
  const Program program =
      Parse("G1 X1 F100\nG20 X1 F10\nG2 X3 Y0 I1\nG21 G1 Y1\n", In(Dialect::kFanuc));
  ASSERT_EQ(program.blocks.size(), 4u);
  ExpectMm(program.blocks[0].end_m, 1, 0, 0);
  ExpectMm(program.blocks[1].end_m, 25.4, 0, 0);
  EXPECT_NEAR(program.blocks[1].feed_m_s, 10 * 25.4e-3 / 60, 1e-15);  // 10 in/min
  ExpectMm(program.blocks[2].end_m, 76.2, 0, 0);  // X3 in
  ExpectMm(program.blocks[2].center_m, 50.8, 0, 0);  // 1 in + I1 in
  ExpectMm(program.blocks[3].end_m, 76.2, 1, 0);  // G21: Y1 is 1 mm
}

// Tests G90.1 (absolute I/J/K) in linuxcnc, G91.1 in linuxcnc and grbl, and the refusals
// naming the dialects that read them.
TEST(GcodeDialectTest, ArcCentreModes) {
  // From (10, 0), centre (0, 0) absolute: a quarter circle to (0, 10).
  const Program program = Parse("G0 X10\nG90.1 G3 X0 Y10 I0 J0\n", In(Dialect::kLinuxcnc));
  ExpectMm(program.blocks.at(1).center_m, 0, 0, 0);
  const Program incremental = Parse("G0 X10\nG91.1 G3 X0 Y10 I-10 J0\n", In(Dialect::kGrbl));
  ExpectMm(incremental.blocks.at(1).center_m, 0, 0, 0);
  ExpectError("G90.1\n", In(Dialect::kFanuc), 1, 1,
              "'G90.1' is not in the fanuc dialect; linuxcnc read it (program_dialect: linuxcnc)");
  ExpectError("G90.1\n", In(Dialect::kGrbl), 1, 1, "is not in the grbl dialect; linuxcnc");
  ExpectError("G91.1\n", In(Dialect::kFanuc), 1, 1, "linuxcnc and grbl read it");
  ExpectError("G0 X10\nG90.1 G3 X0 Y10 I0\n", In(Dialect::kLinuxcnc), 2, 17,
              "under G90.1 (absolute arc centre) an arc needs both centre words");
}

// Tests the arc-end tolerance: fanuc's 1 um; LinuxCNC's and grbl's 0.005 mm, or 0.1 % of
// the radius up to 0.5 mm; and a set tolerance.
TEST(GcodeDialectTest, ArcEndTolerancePerDialect) {
  // Centre (5, 0); end (10.002, 0): radii 5 and 5.002, 0.002 mm apart.
  const std::string off_2um = "G2 X10.002 Y0 I5\n";
  ExpectError(off_2um, In(Dialect::kFanuc), 1, 15, "(the fanuc rule; program_arc_tolerance");
  EXPECT_EQ(Parse(off_2um, In(Dialect::kLinuxcnc)).blocks.size(), 1u);
  EXPECT_EQ(Parse(off_2um, In(Dialect::kGrbl)).blocks.size(), 1u);
  // 0.04 mm apart: above 0.005 mm and above 0.1 % of 5.04 mm.
  ExpectError("G2 X10.04 Y0 I5\n", In(Dialect::kLinuxcnc), 1, 14, "allowed: at most 0.00504 mm");
  // 0.04 mm apart on a 50 mm radius: within 0.1 % (0.05004 mm).
  EXPECT_EQ(Parse("G2 X100.04 Y0 I50\n", In(Dialect::kLinuxcnc)).blocks.size(), 1u);
  // 0.55 mm apart on 600 mm: within 0.1 % (0.6 mm) but above 0.5 mm.
  ExpectError("G2 X1200.55 Y0 I600\n", In(Dialect::kGrbl), 1, 16, "allowed: at most 0.5 mm");
  GcodeOptions set = In(Dialect::kFanuc);
  set.program.arc_tolerance = ArcTolerance{0.01, 0.0, 0.0};
  EXPECT_EQ(Parse(off_2um, set).blocks.size(), 1u);
}

// Tests G61/G61.1/G64 where each dialect has them, G64 P/Q in linuxcnc only (blending,
// no warning), and the one warning that fanuc's G64 runs by the corner rule.
TEST(GcodeDialectTest, PathModes) {
  const Program fanuc = Parse("G64 G1 X1 F100\nG61 X2\nG64 X3\n", In(Dialect::kFanuc));
  ASSERT_EQ(fanuc.warnings.size(), 1u);
  EXPECT_NE(fanuc.warnings[0].find("G64 (line 1, cutting mode) runs as G61 does here"),
            std::string::npos);
  EXPECT_EQ(fanuc.blocks.size(), 3u);
  const Program linuxcnc = Parse("G64 P0.01 Q0.005\nG61.1 G1 X1 F100\n", In(Dialect::kLinuxcnc));
  EXPECT_TRUE(linuxcnc.warnings.empty());
  EXPECT_TRUE(Parse("G61 G1 X1 F100\n", In(Dialect::kGrbl)).warnings.empty());
  ExpectError("G64 P0.01\n", In(Dialect::kFanuc), 1, 5, "'P0.01' with G64 (blending tolerance) "
              "is linuxcnc's");
  ExpectError("G64\n", In(Dialect::kGrbl), 1, 1, "'G64' is not in the grbl dialect; fanuc and "
              "linuxcnc read it");
  ExpectError("G61.1\n", In(Dialect::kFanuc), 1, 1, "linuxcnc read it");
  ExpectError("G64 Q0.01\n", In(Dialect::kLinuxcnc), 1, 5, "G64's Q needs a P");
  ExpectError("G1 X1 Q1\n", In(Dialect::kLinuxcnc), 1, 7, "Q is allowed only with");
}

// Tests G28/G30 through the intermediate point to the reference positions: the axes with
// a word (fanuc: none without one; linuxcnc, grbl: all), and the refusal naming the key.
TEST(GcodeDialectTest, ReferenceReturn) {
  GcodeOptions fanuc = In(Dialect::kFanuc);
  ExpectError("G28 G91 Z0\n", fanuc, 1, 1, "returns to the reference position "
              "machine.reference_mm.g28, which is not set");
  fanuc.program.g28_mm = Eigen::Vector3d(0, 0, 50);
  fanuc.program.g30_mm = Eigen::Vector3d(-100, 20, 40);
  // From (10, 10, 5): G91 Z0 keeps the intermediate point there, then Z to 50.
  const Program z = Parse("G1 X10 Y10 Z5 F600\nG28 G91 Z0\nG28\n", fanuc);
  ASSERT_EQ(z.blocks.size(), 2u);  // the second G28 has no axis: nothing moves on Fanuc
  EXPECT_EQ(z.blocks[1].kind, MotionKind::kRapid);
  ExpectMm(z.blocks[1].start_m, 10, 10, 5);
  ExpectMm(z.blocks[1].end_m, 10, 10, 50);
  // Intermediate (20, 10, 5) absolute, then X to G30's -100.
  const Program x = Parse("G1 X10 Y10 Z5 F600\nG30 X20\n", fanuc);
  ASSERT_EQ(x.blocks.size(), 3u);
  ExpectMm(x.blocks[1].end_m, 20, 10, 5);
  ExpectMm(x.blocks[2].end_m, -100, 10, 5);
  GcodeOptions linuxcnc = fanuc;
  linuxcnc.program.dialect = Dialect::kLinuxcnc;
  const Program all = Parse("G1 X10 Y10 Z5 F600\nG28\n", linuxcnc);
  ASSERT_EQ(all.blocks.size(), 2u);
  ExpectMm(all.blocks[1].end_m, 0, 0, 50);
  ExpectError("G28 G1 X1\n", linuxcnc, 1, 5, "both use the axis words");
}

// Tests that LinuxCNC's O-word control flow and parameters are refused outside the
// linuxcnc dialect saying what they are, not as malformed numbers.
TEST(GcodeDialectTest, OWordsAndParametersNamedOutsideLinuxcnc) {
  ExpectError("O100 sub\n", In(Dialect::kFanuc), 1, 1, "O-word control flow ('O100 sub'");
  ExpectError("o<probe> call\n", In(Dialect::kGrbl), 1, 1,
              "is LinuxCNC's; the grbl dialect does not read it; allowed: program_dialect: "
              "linuxcnc");
  ExpectError("o101 repeat [3]\n", In(Dialect::kFanuc), 1, 1, "O-word control flow");
  ExpectError("G1 X#1\n", In(Dialect::kGrbl), 1, 4, "'X' is followed by '#': RS274NGC parameters");
  ExpectError("G1 X1 Y[2]\n", In(Dialect::kFanuc), 1, 7, "'Y' is followed by '['");
}

}  // namespace
}  // namespace gcode_dialect_test
}  // namespace shapebench::controller
