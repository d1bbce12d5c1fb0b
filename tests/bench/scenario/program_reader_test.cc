// The `program:` list and `program_file:` readers: blocks built by hand-worked geometry,
// and every error a ConfigError "FILE:LINE:COL: key.path: message" at the offending
// YAML value or G-code word. Positions are compared within 1e-12 m (the mm -> m
// conversion rounds at 1e-16 m).
#include "bench/scenario/program_reader.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using controller::MotionKind;
using controller::Program;
using testing::DataPath;
using testing::ErrorOf;
using testing::ExpectError;
using testing::ScratchDir;

constexpr double kTolM = 1e-12;

void ExpectMm(const Eigen::Vector3d& actual_m, double x_mm, double y_mm, double z_mm) {
  EXPECT_NEAR(actual_m.x(), x_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.y(), y_mm * 1e-3, kTolM);
  EXPECT_NEAR(actual_m.z(), z_mm * 1e-3, kTolM);
}

// A YAML file and its top-level reader; the document outlives the readers made from it.
struct Loaded {
  explicit Loaded(const std::string& path)
      : document(ConfigDocument::ParseFile(path), path), top(document, document.root(), "") {}
  NodeReader Key(const std::string& key) const {
    auto child = top.Child(key);
    EXPECT_TRUE(child.has_value()) << key;
    return *child;
  }
  ConfigDocument document;
  NodeReader top;
};

Program ReadList(const std::string& path) {
  const Loaded loaded(path);
  return ReadProgramList(loaded.Key("program"));
}

Program ReadFile(const std::string& path) {
  const Loaded loaded(path);
  return ReadProgramFile(loaded.Key("program_file"));
}



ConfigError ListError(const ScratchDir& dir, const std::string& yaml, std::string* path) {
  *path = dir.Write("s.yaml", yaml);
  return ErrorOf([&] { ReadList(*path); });
}

// Tests that the YAML list gives the blocks: g as an integer or a list, words in mm,
// F in mm/min, P in ms, N and empty entries ignored, source_line the entry index.
TEST(ProgramReaderTest, ReadsTheList) {
  const Program program = ReadList(DataPath("programs/program_list.yaml"));
  ASSERT_EQ(program.blocks.size(), 5u);
  // Entry 0: G1 (0, 0) -> (100, 0) at 6000 mm/min = 0.1 m/s.
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kLinear);
  ExpectMm(program.blocks[0].end_m, 100, 0, 0);
  EXPECT_DOUBLE_EQ(program.blocks[0].feed_m_s, 0.1);
  EXPECT_EQ(program.blocks[0].source_line, 0);
  // Entry 1: G91 G2 by (50, 50) with R50: chord midpoint (125, 25), half chord 35.36 =
  // the distance to the centre; CW of at most 180 degrees: centre on the right, (150, 0).
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kArcCw);
  ExpectMm(program.blocks[1].end_m, 150, 50, 0);
  ExpectMm(program.blocks[1].center_m, 150, 0, 0);
  EXPECT_EQ(program.blocks[1].source_line, 1);
  // Entry 3: G4 P500 = 0.5 s (entry 2, N30, does nothing).
  EXPECT_EQ(program.blocks[2].kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(program.blocks[2].dwell_s, 0.5);
  EXPECT_EQ(program.blocks[2].source_line, 3);
  // Entry 4: G90 G1 back to the origin, feed carried over.
  EXPECT_EQ(program.blocks[3].kind, MotionKind::kLinear);
  ExpectMm(program.blocks[3].end_m, 0, 0, 0);
  EXPECT_DOUBLE_EQ(program.blocks[3].feed_m_s, 0.1);
  // Entry 5 (block style): G3 I10 J0, a full circle about (10, 0).
  EXPECT_EQ(program.blocks[4].kind, MotionKind::kArcCcw);
  ExpectMm(program.blocks[4].center_m, 10, 0, 0);
  EXPECT_EQ(program.blocks[4].end_m, program.blocks[4].start_m);
  EXPECT_EQ(program.blocks[4].source_line, 5);
}

// Tests that the program starts at the given position.
TEST(ProgramReaderTest, ListStartPosition) {
  ScratchDir dir;
  const std::string path = dir.Write("s.yaml", "program:\n  - {g: 91, x: 1}\n");
  const Loaded loaded(path);
  const Program program =
      ReadProgramList(loaded.Key("program"), Eigen::Vector3d(0.001, 0.002, 0.003));
  EXPECT_EQ(program.start_m, Eigen::Vector3d(0.001, 0.002, 0.003));
  ASSERT_EQ(program.blocks.size(), 1u);
  ExpectMm(program.blocks[0].end_m, 2, 2, 3);
}

// Tests that a builder error about one word lands on that word's YAML value.
TEST(ProgramReaderTest, WordErrorAtItsValue) {
  const std::string path = DataPath("programs/program_list_error.yaml");
  ExpectError(ErrorOf([&] { ReadList(path); }), path, 4, 23, "program[1].r",
              "R cannot describe a full circle (the end point is the start point); use I/J/K");
  ScratchDir dir;
  std::string file;
  ExpectError(ListError(dir, "program:\n  - g: 2\n    x: 10\n    k: 5\n", &file), file, 4, 8,
              "program[0].k", "'K5' is not a centre word of G17 (XY plane); allowed: I, J");
  ExpectError(ListError(dir, "program:\n  - {g: [91, 64.1], x: 1}\n", &file), file, 2, 14,
              "program[0].g[1]", "unsupported word 'G64.1'");
  ExpectError(ListError(dir, "program:\n  - {g: 41}\n", &file), file, 2, 9, "program[0].g",
              "unsupported word 'G41'");
  ExpectError(ListError(dir, "program:\n  - {g: [1, 1], x: 5}\n", &file), file, 2, 13,
              "program[0].g[1]", "word 'G1' repeated");
  ExpectError(ListError(dir, "program:\n  - {x: 5, f: 0}\n", &file), file, 2, 15,
              "program[0].f", "F must be > 0 (mm/min)");
  // Centre (5, 0), end (10, 1): end radius sqrt(26) = 5.09902.
  ExpectError(ListError(dir, "program:\n  - {g: 2, x: 10, y: 1, i: 5}\n", &file), file, 2, 28,
              "program[0].i", "arc end point is not on the circle: start radius 5 mm");
  ExpectError(ListError(dir, "program:\n  - {g: 2, x: 10, i: 5, r: 5}\n", &file), file, 2, 28,
              "program[0].r", "I/J/K or as R, not both");
}

// Tests that an error about the block as a whole lands on the entry.
TEST(ProgramReaderTest, BlockErrorAtTheEntry) {
  ScratchDir dir;
  std::string file;
  ExpectError(ListError(dir, "program:\n  - {g: 2, x: 10, i: 5}\n  - {x: 20}\n", &file), file, 3,
              5, "program[1]", "an arc (G2) needs its centre");
}

// Tests the YAML shape errors: not a list, an entry not a mapping, an unknown key, a
// quoted number, a non-integer g.
TEST(ProgramReaderTest, ShapeErrors) {
  ScratchDir dir;
  std::string file;
  ExpectError(ListError(dir, "program: {g: 1}\n", &file), file, 1, 10, "program",
              "expected a sequence");
  ExpectError(ListError(dir, "program:\n  - 5\n", &file), file, 2, 5, "program[0]",
              "expected a mapping");
  ExpectError(ListError(dir, "program:\n  - {g: 1, w: 5}\n", &file), file, 2, 12, "program[0].w",
              "unknown key 'w'; allowed: g, x, y, z, i, j, k, r, f, p, q, n");
  ExpectError(ListError(dir, "program:\n  - {x: \"10\"}\n", &file), file, 2, 9, "program[0].x",
              "expected a number");
  ExpectError(ListError(dir, "program:\n  - {g: 1.5}\n", &file), file, 2, 9, "program[0].g",
              "unsupported word 'G1.5'");
  ExpectError(ListError(dir, "program:\n  - {g: [1, x]}\n", &file), file, 2, 13,
              "program[0].g[1]", "expected a number");
}

// Tests that program_file is read relative to the scenario's directory, comments, `%`
// and modal words included.
TEST(ProgramReaderTest, ReadsTheFile) {
  const Program program = ReadFile(DataPath("programs/program_file.yaml"));
  ASSERT_EQ(program.blocks.size(), 5u);
  // N30 G1 X20 F3000: 3000 mm/min = 0.05 m/s.
  EXPECT_EQ(program.blocks[0].kind, MotionKind::kLinear);
  ExpectMm(program.blocks[0].end_m, 20, 0, 0);
  EXPECT_DOUBLE_EQ(program.blocks[0].feed_m_s, 0.05);
  EXPECT_EQ(program.blocks[0].source_line, 5);
  // N40 G3 X30 Y10 R10 from (20, 0): chord (10, 10), centre on the left: (20, 10).
  EXPECT_EQ(program.blocks[1].kind, MotionKind::kArcCcw);
  ExpectMm(program.blocks[1].center_m, 20, 10, 0);
  ExpectMm(program.blocks[2].end_m, 30, 20, 0);
  EXPECT_EQ(program.blocks[3].kind, MotionKind::kDwell);
  EXPECT_DOUBLE_EQ(program.blocks[3].dwell_s, 0.2);
  ExpectMm(program.blocks[4].end_m, 0, 20, 0);  // G91 X-30
  EXPECT_EQ(program.blocks[4].source_line, 9);
}

// Tests that an error inside the G-code file is located in that file, key program_file
// (the scenario's program_strict refuses the M3 the parser would otherwise drop).
TEST(ProgramReaderTest, FileErrorInTheGcodeFile) {
  const std::string gcode = fs::path(DataPath("programs/bad_word.nc")).lexically_normal().string();
  const ConfigError error =
      ErrorOf([&] { LoadScenario(DataPath("programs/bad_program_file.yaml"), {}); });
  ExpectError(error, gcode, 3, 8, "program_file", "'M3' is not modelled by the bench");
  EXPECT_EQ(std::string(error.what()),
            gcode + ":3:8: program_file: 'M3' is not modelled by the bench, and program_strict "
                    "refuses the words it would otherwise ignore (O, T, S, H, D, M, G43, G44, "
                    "G54-G59)");
  // A malformed number in a file in a subdirectory.
  ScratchDir dir;
  dir.Write("parts/p.nc", "G1 X1\n\n  G1 X1.2.3\n");
  const std::string path = dir.Write("s.yaml", "program_file: parts/p.nc\n");
  ExpectError(ErrorOf([&] { ReadFile(path); }), dir.File("parts/p.nc"), 3, 6, "program_file",
              "malformed number 'X1.2.3'");
}

// Tests that a missing G-code file is reported at the program_file value, naming the
// resolved path.
TEST(ProgramReaderTest, MissingFileAtTheKey) {
  const std::string path = DataPath("programs/missing_program_file.yaml");
  const std::string resolved =
      fs::path(DataPath("programs/missing.nc")).lexically_normal().string();
  ExpectError(ErrorOf([&] { ReadFile(path); }), path, 2, 15, "program_file",
              "G-code file 'missing.nc' (" + resolved + "): cannot open file");
  ScratchDir dir;
  dir.Write("sub/keep", "");
  const std::string directory = dir.Write("s.yaml", "program_file: sub\n");
  ExpectError(ErrorOf([&] { ReadFile(directory); }), directory, 1, 15, "program_file",
              "it is a directory");
}

// Tests that an absolute program_file path is used as it is.
TEST(ProgramReaderTest, AbsoluteFilePath) {
  ScratchDir dir;
  const std::string gcode = dir.Write("abs.nc", "G1 X7\n");
  const std::string path = dir.Write("elsewhere/s.yaml", "program_file: " + gcode + "\n");
  const Program program = ReadFile(path);
  ASSERT_EQ(program.blocks.size(), 1u);
  ExpectMm(program.blocks[0].end_m, 7, 0, 0);
}

}  // namespace
}  // namespace shapebench::bench
