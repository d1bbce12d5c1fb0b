// ProgramBuilder: the modal state of a Fanuc-style control applied to blocks of words.
// Expected end points and centres are worked by hand in mm (comments show the geometry);
// positions are compared within 1e-12 m, far below the 1e-16 m rounding of the mm -> m
// conversion and far above it for the square roots of the R centre.
#include "controller/program_builder.h"

#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace shapebench::controller {
namespace {

constexpr double kBuilderTolM = 1e-12;

// A block of words; the i-th word sits at column 1 + 10 i, so errors can name it.
Block B(std::initializer_list<std::pair<char, double>> words, int line = 1) {
  Block block;
  block.source_line = line;
  int i = 0;
  for (const auto& [letter, value] : words) {
    Word word;
    word.letter = letter;
    word.value = value;
    word.column = 1 + 10 * i++;
    block.words.push_back(word);
  }
  return block;
}

Program Build(const std::vector<Block>& blocks,
              const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero()) {
  ProgramBuilder builder(start_m);
  for (const Block& block : blocks) builder.Apply(block);
  return builder.TakeProgram();
}

ProgramError ErrorOf(const std::vector<Block>& blocks) {
  ProgramBuilder builder;
  try {
    for (const Block& block : blocks) builder.Apply(block);
  } catch (const ProgramError& error) {
    return error;
  }
  ADD_FAILURE() << "no ProgramError";
  return ProgramError(0, 0, -1, "");
}

void ExpectBuildError(const ProgramError& error, int line, int column, int word_index,
                 const std::string& message_part) {
  EXPECT_EQ(error.line(), line) << error.what();
  EXPECT_EQ(error.column(), column) << error.what();
  EXPECT_EQ(error.word_index(), word_index) << error.what();
  EXPECT_NE(error.message().find(message_part), std::string::npos) << error.what();
}

// Position in mm, compared in metres.
void ExpectBuiltMm(const Eigen::Vector3d& actual_m, double x_mm, double y_mm, double z_mm) {
  EXPECT_NEAR(actual_m.x(), x_mm * 1e-3, kBuilderTolM);
  EXPECT_NEAR(actual_m.y(), y_mm * 1e-3, kBuilderTolM);
  EXPECT_NEAR(actual_m.z(), z_mm * 1e-3, kBuilderTolM);
}

// Tests that the power-up state is G1, G17, G90 and no feed: coordinates alone move linearly.
TEST(ProgramBuilderTest, PowerUpStateIsG1G17G90WithoutFeed) {
  ProgramBuilder builder;
  EXPECT_EQ(builder.motion(), MotionKind::kLinear);
  EXPECT_EQ(builder.plane(), Plane::kXY);
  EXPECT_FALSE(builder.incremental());
  EXPECT_TRUE(std::isnan(builder.feed_m_s()));
  builder.Apply(B({{'X', 10}, {'Y', -5}}, 7));
  const Program& program = builder.program();
  ASSERT_EQ(program.blocks.size(), 1u);
  const ProgramBlock& block = program.blocks[0];
  EXPECT_EQ(block.kind, MotionKind::kLinear);
  ExpectBuiltMm(block.start_m, 0, 0, 0);
  ExpectBuiltMm(block.end_m, 10, -5, 0);
  EXPECT_EQ(block.plane, Plane::kXY);
  EXPECT_TRUE(std::isnan(block.feed_m_s));
  EXPECT_EQ(block.source_line, 7);
}

// Tests that the program starts where the builder was told and unprogrammed axes stay.
TEST(ProgramBuilderTest, StartPositionAndUnprogrammedAxes) {
  const Eigen::Vector3d start(0.1, 0.2, 0.3);
  const Program program = Build({B({{'Y', 50}})}, start);
  EXPECT_EQ(program.start_m, start);
  ASSERT_EQ(program.blocks.size(), 1u);
  EXPECT_EQ(program.blocks[0].start_m, start);
  ExpectBuiltMm(program.blocks[0].end_m, 100, 50, 300);
}

// Tests that G91 adds to the position, stays in force, and G90 returns to absolute.
TEST(ProgramBuilderTest, AbsoluteAndIncrementalAreModal) {
  const Program program = Build({B({{'G', 91}, {'X', 10}, {'Y', 5}}),  // (10, 5)
                                 B({{'X', 10}, {'Z', -2}}),             // (20, 5, -2)
                                 B({{'G', 90}, {'X', 0}}),              // (0, 5, -2)
                                 B({{'Y', 7}})});                       // (0, 7, -2)
  ASSERT_EQ(program.blocks.size(), 4u);
  ExpectBuiltMm(program.blocks[0].end_m, 10, 5, 0);
  ExpectBuiltMm(program.blocks[1].end_m, 20, 5, -2);
  ExpectBuiltMm(program.blocks[2].end_m, 0, 5, -2);
  ExpectBuiltMm(program.blocks[3].end_m, 0, 7, -2);
  // Each block starts where the previous one ended, bit for bit.
  for (std::size_t i = 1; i < program.blocks.size(); ++i) {
    EXPECT_EQ(program.blocks[i].start_m, program.blocks[i - 1].end_m);
  }
}

// Tests that F is converted from mm/min to m/s, is modal, and an F-only block moves nothing.
TEST(ProgramBuilderTest, FeedIsModalInMetresPerSecond) {
  const Program program = Build({B({{'X', 1}}),                 // no F yet
                                 B({{'F', 6000}}),              // 6000 mm/min = 0.1 m/s
                                 B({{'X', 2}}),
                                 B({{'G', 0}, {'X', 3}}),       // rapid keeps the F
                                 B({{'G', 1}, {'X', 4}, {'F', 1200}})});  // 0.02 m/s
  ASSERT_EQ(program.blocks.size(), 4u);
  EXPECT_TRUE(std::isnan(program.blocks[0].feed_m_s));
  EXPECT_DOUBLE_EQ(program.blocks[1].feed_m_s, 0.1);
  EXPECT_DOUBLE_EQ(program.blocks[2].feed_m_s, 0.1);
  EXPECT_DOUBLE_EQ(program.blocks[3].feed_m_s, 0.02);
}

// Tests that the motion G is modal: G0 stays rapid until G1.
TEST(ProgramBuilderTest, MotionIsModal) {
  const Program program = Build({B({{'G', 0}, {'X', 10}}), B({{'X', 20}}),
                                 B({{'G', 1}, {'X', 30}}), B({{'X', 40}})});
  ASSERT_EQ(program.blocks.size(), 4u);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kRapid);
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kRapid);
  EXPECT_EQ(program.blocks[2].kind, MotionKind::kLinear);
  EXPECT_EQ(program.blocks[3].kind, MotionKind::kLinear);
}

// Tests that N, modal-only blocks, a lone G2 and a move to where the tool is produce nothing.
TEST(ProgramBuilderTest, BlocksWithoutMotionProduceNoProgramBlock) {
  ProgramBuilder builder;
  builder.Apply(B({{'N', 10}}));
  builder.Apply(B({{'G', 17}, {'G', 90}, {'G', 21}, {'F', 500}}));
  builder.Apply(B({{'G', 1}, {'X', 0}, {'Y', 0}}));  // already at (0, 0)
  builder.Apply(B({{'G', 91}, {'X', 0}}));           // moves by 0
  builder.Apply(B({{'G', 2}}));                      // modal change only
  EXPECT_TRUE(builder.program().blocks.empty());
  EXPECT_EQ(builder.motion(), MotionKind::kArcCw);
  EXPECT_TRUE(builder.incremental());
  EXPECT_DOUBLE_EQ(builder.feed_m_s(), 500.0 / 60000.0);
}

// Tests that G17 I/J give the centre as offsets from the start, G3 is counter-clockwise.
TEST(ProgramBuilderTest, ArcByIJInG17) {
  // From (10, 0) a quarter circle about the origin to (0, 10).
  const Program program =
      Build({B({{'X', 10}}), B({{'G', 3}, {'X', 0}, {'Y', 10}, {'I', -10}, {'J', 0}})});
  ASSERT_EQ(program.blocks.size(), 2u);
  const ProgramBlock& arc = program.blocks[1];
  EXPECT_EQ(arc.kind, MotionKind::kArcCcw);
  EXPECT_EQ(arc.plane, Plane::kXY);
  ExpectBuiltMm(arc.start_m, 10, 0, 0);
  ExpectBuiltMm(arc.end_m, 0, 10, 0);
  ExpectBuiltMm(arc.center_m, 0, 0, 0);
}

// Tests that G18 takes K (Z) and I (X) as the centre, with the arc in the ZX plane.
TEST(ProgramBuilderTest, ArcByKIInG18) {
  // Start (x 0, z 0); centre (x 10, z 0) by I10 K0; end (x 10, z 10): radii 10 and 10.
  const Program program =
      Build({B({{'G', 18}, {'G', 2}, {'X', 10}, {'Z', 10}, {'K', 0}, {'I', 10}})});
  ASSERT_EQ(program.blocks.size(), 1u);
  const ProgramBlock& arc = program.blocks[0];
  EXPECT_EQ(arc.kind, MotionKind::kArcCw);
  EXPECT_EQ(arc.plane, Plane::kZX);
  ExpectBuiltMm(arc.end_m, 10, 0, 10);
  ExpectBuiltMm(arc.center_m, 10, 0, 0);
  // K moves the centre along Z.
  const Program shifted =
      Build({B({{'G', 18}, {'G', 3}, {'X', 0}, {'Z', 10}, {'K', 5}})});  // radii 5, 5
  ASSERT_EQ(shifted.blocks.size(), 1u);
  ExpectBuiltMm(shifted.blocks[0].center_m, 0, 0, 5);
}

// Tests that G19 takes J (Y) and K (Z) as the centre, with the arc in the YZ plane.
TEST(ProgramBuilderTest, ArcByJKInG19) {
  // Start (y 0, z 0); centre (y 0, z 10) by K10; end (y 10, z 10): radii 10 and 10.
  const Program program = Build({B({{'G', 19}, {'G', 3}, {'Y', 10}, {'Z', 10}, {'K', 10}})});
  ASSERT_EQ(program.blocks.size(), 1u);
  EXPECT_EQ(program.blocks[0].plane, Plane::kYZ);
  ExpectBuiltMm(program.blocks[0].center_m, 0, 0, 10);
  // J moves the centre along Y: centre (y 5, z 0), end (y 10, z 0).
  const Program by_j = Build({B({{'G', 19}, {'G', 2}, {'Y', 10}, {'J', 5}})});
  ASSERT_EQ(by_j.blocks.size(), 1u);
  ExpectBuiltMm(by_j.blocks[0].center_m, 0, 5, 0);
}

// Tests the R centre on a 3-4-5 triangle: chord (0,0)-(6,0), R 5, centre at +-4 from the
// chord's midpoint (3, 0); CW short and CCW long on the right (3, -4), the others on the
// left (3, 4).
TEST(ProgramBuilderTest, RCentreCwCcwShortLong) {
  struct Case {
    int g;
    double r;
    double centre_y_mm;
  };
  for (const Case& c : {Case{2, 5, -4}, Case{3, 5, 4}, Case{2, -5, 4}, Case{3, -5, -4}}) {
    const Program program = Build({B({{'G', static_cast<double>(c.g)}, {'X', 6}, {'R', c.r}})});
    ASSERT_EQ(program.blocks.size(), 1u);
    SCOPED_TRACE("G" + std::to_string(c.g) + " R" + std::to_string(c.r));
    EXPECT_EQ(program.blocks[0].kind, c.g == 2 ? MotionKind::kArcCw : MotionKind::kArcCcw);
    ExpectBuiltMm(program.blocks[0].center_m, 3, c.centre_y_mm, 0);
    ExpectBuiltMm(program.blocks[0].end_m, 6, 0, 0);
  }
}

// Tests the R centre on a diagonal chord: (0,0) to (10,10) with R 10 has its centre at
// (10, 0) (CW quarter from 180 to 90 degrees) or (0, 10) (CCW quarter from -90 to 0).
TEST(ProgramBuilderTest, RCentreOnDiagonalChord) {
  auto centre = [](int g, double r) {
    const Program program =
        Build({B({{'G', static_cast<double>(g)}, {'X', 10}, {'Y', 10}, {'R', r}})});
    EXPECT_EQ(program.blocks.size(), 1u);
    return program.blocks.at(0).center_m;
  };
  ExpectBuiltMm(centre(2, 10), 10, 0, 0);
  ExpectBuiltMm(centre(3, 10), 0, 10, 0);
  ExpectBuiltMm(centre(2, -10), 0, 10, 0);
  ExpectBuiltMm(centre(3, -10), 10, 0, 0);
}

// Tests that R follows the plane's orientation in G18 and G19 (CW seen from +Y and +X).
TEST(ProgramBuilderTest, RCentreInG18AndG19) {
  // G18: plane axes (Z, X). From (z 0, x 0) to (z 6, x 0), R5 CW: centre at the right of
  // the chord direction +Z, i.e. x = -4 (z x x = y points at the viewer).
  const Program zx = Build({B({{'G', 18}, {'G', 2}, {'Z', 6}, {'R', 5}})});
  ASSERT_EQ(zx.blocks.size(), 1u);
  ExpectBuiltMm(zx.blocks[0].center_m, -4, 0, 3);
  // G19: plane axes (Y, Z). From (y 0, z 0) to (y 6, z 0), R5 CCW: centre at the left, z 4.
  const Program yz = Build({B({{'G', 19}, {'G', 3}, {'Y', 6}, {'R', 5}})});
  ASSERT_EQ(yz.blocks.size(), 1u);
  ExpectBuiltMm(yz.blocks[0].center_m, 0, 3, 4);
}

// Tests that R of exactly half the chord (a half circle) puts the centre at the midpoint.
TEST(ProgramBuilderTest, RHalfCircleCentreIsMidpoint) {
  const Program program = Build({B({{'G', 2}, {'X', 10}, {'R', 5}})});
  ASSERT_EQ(program.blocks.size(), 1u);
  ExpectBuiltMm(program.blocks[0].center_m, 5, 0, 0);
  // Within the 1e-3 mm tolerance below half the chord: still the midpoint.
  const Program short_r = Build({B({{'G', 2}, {'X', 10}, {'R', 4.9995}})});
  ASSERT_EQ(short_r.blocks.size(), 1u);
  ExpectBuiltMm(short_r.blocks[0].center_m, 5, 0, 0);
}

// Tests that an I/J arc whose end is its start is a full circle, end exactly the start.
TEST(ProgramBuilderTest, FullCircleByIJ) {
  const Program program = Build({B({{'G', 2}, {'I', 10}}),                   // no end word
                                 B({{'G', 3}, {'X', 0}, {'Y', 0}, {'J', -7}}),  // end = start
                                 B({{'G', 2}, {'X', 0.0000005}, {'I', 10}})});  // 0.5 nm off
  ASSERT_EQ(program.blocks.size(), 3u);
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kArcCw);
  ExpectBuiltMm(program.blocks[0].center_m, 10, 0, 0);
  EXPECT_EQ(program.blocks[0].end_m, program.blocks[0].start_m);
  ExpectBuiltMm(program.blocks[1].center_m, 0, -7, 0);
  EXPECT_EQ(program.blocks[1].end_m, program.blocks[1].start_m);
  EXPECT_EQ(program.blocks[2].end_m, program.blocks[2].start_m);  // snapped to the start
}

// Tests that a helix changes the normal axis while the centre keeps the start's Z.
TEST(ProgramBuilderTest, Helix) {
  // From (10, 0, 0) half a turn about the Z axis to (-10, 0) while Z rises 4 mm.
  const Program program =
      Build({B({{'X', 10}}), B({{'G', 3}, {'X', -10}, {'Y', 0}, {'Z', 4}, {'I', -10}})});
  ASSERT_EQ(program.blocks.size(), 2u);
  const ProgramBlock& helix = program.blocks[1];
  ExpectBuiltMm(helix.end_m, -10, 0, 4);
  ExpectBuiltMm(helix.center_m, 0, 0, 0);
  // A full helical turn: end equals start in the plane only.
  const Program turn = Build({B({{'G', 2}, {'Z', -3}, {'I', 5}})});
  ASSERT_EQ(turn.blocks.size(), 1u);
  ExpectBuiltMm(turn.blocks[0].end_m, 0, 0, -3);
  ExpectBuiltMm(turn.blocks[0].center_m, 5, 0, 0);
}

// Tests that G4 dwells P milliseconds or X seconds, in place, and is one-shot.
TEST(ProgramBuilderTest, DwellByPAndX) {
  const Program program = Build({B({{'X', 5}, {'F', 600}}),
                                 B({{'G', 4}, {'P', 500}}),      // 0.5 s
                                 B({{'G', 91}, {'G', 4}, {'X', 1.5}}),  // 1.5 s, not a move
                                 B({{'X', 1}}),                  // linear again, incremental
                                 B({{'G', 4}, {'P', 0}})});      // 0 s is allowed
  ASSERT_EQ(program.blocks.size(), 5u);
  const ProgramBlock& p = program.blocks[1];
  EXPECT_EQ(p.kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(p.dwell_s, 0.5);
  ExpectBuiltMm(p.start_m, 5, 0, 0);
  ExpectBuiltMm(p.end_m, 5, 0, 0);
  EXPECT_DOUBLE_EQ(p.feed_m_s, 0.01);
  EXPECT_EQ(program.blocks[2].kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(program.blocks[2].dwell_s, 1.5);
  ExpectBuiltMm(program.blocks[2].end_m, 5, 0, 0);
  EXPECT_EQ(program.blocks[3].kind, MotionKind::kLinear);
  ExpectBuiltMm(program.blocks[3].end_m, 6, 0, 0);
  EXPECT_DOUBLE_EQ(program.blocks[4].dwell_s, 0.0);
}

// Tests that a G4 block takes the modal words it shares (F, G18, N) before it dwells: the
// dwell carries them and sits at the position (start, end and centre); they stay in force.
TEST(ProgramBuilderTest, DwellTakesTheModalWordsOfItsBlock) {
  ProgramBuilder builder(Eigen::Vector3d(0.001, 0.0, 0.0));
  builder.Apply(B({{'X', 5}, {'Y', 2}}));
  builder.Apply(B({{'F', 1200}, {'G', 4}, {'G', 18}, {'P', 250}, {'N', 7}}, 3));
  ASSERT_EQ(builder.program().blocks.size(), 2u);
  const ProgramBlock& dwell = builder.program().blocks[1];
  EXPECT_EQ(dwell.kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(dwell.dwell_s, 0.25);
  EXPECT_EQ(dwell.plane, Plane::kZX);
  EXPECT_DOUBLE_EQ(dwell.feed_m_s, 0.02);
  EXPECT_EQ(dwell.source_line, 3);
  ExpectBuiltMm(dwell.start_m, 5, 2, 0);
  ExpectBuiltMm(dwell.end_m, 5, 2, 0);
  ExpectBuiltMm(dwell.center_m, 5, 2, 0);
  EXPECT_EQ(builder.plane(), Plane::kZX);
  EXPECT_DOUBLE_EQ(builder.feed_m_s(), 0.02);
  EXPECT_EQ(builder.motion(), MotionKind::kLinear);
}

// Tests that the radius check accepts 1e-3 mm of difference and refuses more, and that
// above 1 m of radius the bound is 1e-6 of the radius.
TEST(ProgramBuilderTest, ArcRadiusTolerance) {
  // Centre (10, 0): end (20.0009, 0) has radius 10.0009.
  EXPECT_NO_THROW(Build({B({{'G', 2}, {'X', 20.0009}, {'I', 10}})}));
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 20.0011}, {'I', 10}})}), 1, 21, 2,
              "arc end point is not on the circle: start radius 10 mm, end radius 10.0011 mm");
  // Radius 2000 mm: bound 0.002 mm.
  EXPECT_NO_THROW(Build({B({{'G', 2}, {'X', 4000.0015}, {'I', 2000}})}));
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 4000.0025}, {'I', 2000}})}), 1, 21, 2,
              "allowed: at most 0.002 mm");
}

// Tests that K in G17 (and J in G18, I in G19) is refused at that word.
TEST(ProgramBuilderTest, CentreWordOutsideThePlane) {
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'K', 5}}, 4)}), 4, 21, 2,
              "'K5' is not a centre word of G17 (XY plane); allowed: I, J");
  ExpectBuildError(ErrorOf({B({{'G', 18}, {'G', 2}, {'X', 10}, {'J', 5}})}), 1, 31, 3,
              "allowed: K, I");
  ExpectBuildError(ErrorOf({B({{'G', 19}, {'G', 2}, {'Y', 10}, {'I', 5}})}), 1, 31, 3,
              "allowed: J, K");
}

// Tests the arc errors: R with I, no centre, R of a full circle, R zero or too short,
// zero radius by I/J, end off the circle.
TEST(ProgramBuilderTest, ArcErrors) {
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'I', 5}, {'R', 5}})}), 1, 31, 3,
              "I/J/K or as R, not both");
  ExpectBuildError(ErrorOf({B({{'G', 3}, {'X', 10}, {'Y', 5}})}), 1, 1, 0,
              "an arc (G3) needs its centre: I/J/K offsets or a radius R");
  // Modal G2 from an earlier block: the block as a whole is wrong.
  ExpectBuildError(ErrorOf({B({{'G', 2}}), B({{'N', 5}, {'X', 10}}, 2)}), 2, 1, -1,
              "an arc (G2) needs its centre");
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'R', 5}})}), 1, 11, 1,
              "R cannot describe a full circle (the end point is the start point); use I/J/K");
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'R', 0}})}), 1, 21, 2, "R must not be 0");
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'R', -4.99}})}), 1, 21, 2,
              "'R-4.99' is shorter than half the chord (5 mm); allowed: |R| >= 5 mm");
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'I', 0}, {'J', 0}})}), 1, 21, 2,
              "arc radius is 0");
  // Centre (5, 0) by I5; end (10, 1) has radius |(5, 1)| = 5.09902.
  ExpectBuildError(ErrorOf({B({{'G', 2}, {'X', 10}, {'Y', 1}, {'I', 5}})}), 1, 31, 3,
              "arc end point is not on the circle: start radius 5 mm, end radius 5.09902 mm");
}

// Tests that I/J/K and R outside an arc are refused at the word.
TEST(ProgramBuilderTest, CentreWordsOnlyInArcs) {
  ExpectBuildError(ErrorOf({B({{'G', 1}, {'X', 10}, {'I', 5}})}), 1, 21, 2,
              "'I5' belongs to an arc (G2/G3); the active motion is G1");
  ExpectBuildError(ErrorOf({B({{'G', 0}, {'X', 10}, {'R', 5}})}), 1, 21, 2,
              "the active motion is G0");
}

// Tests the G4 errors: no time, both P and X, negative, a motion word in the block.
TEST(ProgramBuilderTest, DwellErrors) {
  ExpectBuildError(ErrorOf({B({{'G', 4}})}), 1, 1, 0, "G4 needs its dwell time: P in ms");
  ExpectBuildError(ErrorOf({B({{'G', 4}, {'P', 5}, {'X', 1}})}), 1, 21, 2,
                   "as one of P (ms), X (s) and U (s)");
  ExpectBuildError(ErrorOf({B({{'G', 4}, {'P', -5}})}), 1, 11, 1, "dwell must be >= 0");
  ExpectBuildError(ErrorOf({B({{'G', 4}, {'X', -0.5}})}), 1, 11, 1, "dwell must be >= 0");
  ExpectBuildError(ErrorOf({B({{'G', 4}, {'P', 5}, {'Y', 1}})}), 1, 21, 2,
              "'Y1' is not allowed in a G4 (dwell) block");
  ExpectBuildError(ErrorOf({B({{'G', 1}, {'G', 4}, {'P', 5}})}), 1, 1, 0,
              "G4 (dwell) cannot share a block with 'G1'");
  ExpectBuildError(ErrorOf({B({{'G', 1}, {'X', 5}, {'P', 5}})}), 1, 21, 2,
              "P is allowed only with G4 (dwell)");
}

// Tests the word errors: unsupported G and letters, repeated words, two motion words,
// two words of one modal group, non-integer G, F <= 0.
TEST(ProgramBuilderTest, WordErrors) {
  ExpectBuildError(ErrorOf({B({{'X', 1}, {'G', 41}})}), 1, 11, 1,
              "unsupported word 'G41' is not read by the bench (dialect fanuc); allowed: G0-G3, "
              "G4 with P (ms, no decimal point) or X/U (s), G17-G19, G20, G21, G28, G30, G61, "
              "G64, G90, G91, G40, G43, G44, G49, G54-G59, G80, G94, F, X, Y, Z, I, J, K, R, N, "
              "and O, T, S, H, D, M (read and ignored)");
  ExpectBuildError(ErrorOf({B({{'M', 3}})}), 1, 1, 0, "unsupported word 'M3'");
  ExpectBuildError(ErrorOf({B({{'X', 1}, {'Y', 2}, {'X', 3}})}), 1, 21, 2,
              "word X repeated in one block ('X1' and 'X3')");
  ExpectBuildError(ErrorOf({B({{'G', 1}, {'G', 1}})}), 1, 11, 1, "word 'G1' repeated");
  ExpectBuildError(ErrorOf({B({{'G', 0}, {'G', 2}, {'X', 1}})}), 1, 11, 1,
              "'G0' and 'G2' in one block; one motion word (G0-G3) per block");
  ExpectBuildError(ErrorOf({B({{'G', 90}, {'G', 91}})}), 1, 11, 1, "one of G90 (absolute)");
  ExpectBuildError(ErrorOf({B({{'G', 17}, {'G', 18}})}), 1, 11, 1, "one plane word");
  ExpectBuildError(ErrorOf({B({{'G', 1.25}})}), 1, 1, 0, "G takes an integer or one decimal");
  ExpectBuildError(ErrorOf({B({{'G', 1.5}})}), 1, 1, 0, "unsupported word 'G1.5'");
  ExpectBuildError(ErrorOf({B({{'X', 1}, {'F', 0}})}), 1, 11, 1, "F must be > 0 (mm/min)");
  ExpectBuildError(ErrorOf({B({{'F', -100}})}), 1, 1, 0, "F must be > 0");
}

// Tests that a word's text as written is what the messages quote.
TEST(ProgramBuilderTest, MessagesQuoteTheWrittenText) {
  Block block = B({{'G', 41}});
  block.words[0].text = "G041";
  ExpectBuildError(ErrorOf({block}), 1, 1, 0, "unsupported word 'G041'");
}

// Tests that what() is "LINE:COL: message", or "LINE: message" without a column.
TEST(ProgramBuilderTest, ErrorWhat) {
  EXPECT_STREQ(ProgramError(3, 7, 1, "R must not be 0").what(), "3:7: R must not be 0");
  EXPECT_STREQ(ProgramError(3, 0, -1, "bad").what(), "3: bad");
}

}  // namespace
}  // namespace shapebench::controller
