// The FE modal export reader (bench/measured/modal_file_reader.h) through the built CLI: every
// bad file exits 2 with `error: FILE.csv:LINE:COLUMN: COLUMN: ...` naming what is allowed;
// and what a good file may vary (column order, CR line ends, spaces, comments, an empty
// mode unit).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/measured/modal_file_reader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::RunCli;
using testing::ScratchDir;

const std::string kHeader =
    "mode,frequency_hz,damping_ratio,participation_x,participation_y,participation_z,shape_x,shape_y,shape_z\n";
const std::string kUnits = "-,Hz,1,sqrt(kg),sqrt(kg),sqrt(kg),1/sqrt(kg),1/sqrt(kg),1/sqrt(kg)\n";
const std::string kRow = "1,25,0.03,0,1,0,0,1,0\n";  // fields start at columns 1 3 6 11 13 15 17 19 21

struct BadFile {
  const char* what;
  std::string text;
  int line;
  int column;
  std::string key;
  std::string message;
};

std::string ManyModes(int count) {
  std::string text = kHeader + kUnits;
  for (int i = 1; i <= count; ++i) text += std::to_string(i) + ",25,0.03,0,1,0,0,1,0\n";
  return text;
}

// Tests that each bad FE export is refused with exit 2 at its file, line and column, naming
// the column (or header, units) and what is allowed: an empty file, a missing or wrong unit
// row, a missing, duplicate or unknown column, numbers that are not plain decimals (text,
// NaN, inf, out of range), a negative frequency or damping, a short row, a duplicate or
// non-integer mode number, too many modes, a NUL (shown as \x00, the message whole).
TEST(ModalFile, BadFilesAreRefusedAtLineAndColumn) {
  const std::vector<BadFile> cases = {
      {"empty", "", 1, 1, "header", "no header row"},
      {"no units", kHeader, 2, 1, "units", "missing: the second row names each column's unit"},
      {"unit row missing", kHeader + kRow, 2, 1, "mode", "missing unit row"},
      {"unknown unit", kHeader + "-,kHz,1,sqrt(kg),sqrt(kg),sqrt(kg),1/sqrt(kg),1/sqrt(kg),1/sqrt(kg)\n" + kRow, 2,
       3, "frequency_hz", "unit 'kHz' is not this column's; allowed: 'Hz'"},
      {"wrong unit", kHeader + "-,Hz,1,1/sqrt(kg),sqrt(kg),sqrt(kg),1/sqrt(kg),1/sqrt(kg),1/sqrt(kg)\n" + kRow, 2, 8,
       "participation_x", "allowed: 'sqrt(kg)'"},
      {"text", kHeader + kUnits + "1,25,0.03,0,1,0,abc,1,0\n", 3, 17, "shape_x",
       "expected a finite plain decimal number in '1/sqrt(kg)', got 'abc'"},
      {"nan", kHeader + kUnits + "1,nan,0.03,0,1,0,0,1,0\n", 3, 3, "frequency_hz", "got 'nan'"},
      {"inf", kHeader + kUnits + "1,25,0.03,0,inf,0,0,1,0\n", 3, 13, "participation_y", "got 'inf'"},
      {"out of range", kHeader + kUnits + "1,25,0.03,0,1,0,0,1e999,0\n", 3, 19, "shape_y", "got '1e999'"},
      {"negative frequency", kHeader + kUnits + "1,-25,0.03,0,1,0,0,1,0\n", 3, 3, "frequency_hz", "must be > 0 Hz"},
      {"negative damping", kHeader + kUnits + "1,25,-0.03,0,1,0,0,1,0\n", 3, 6, "damping_ratio",
       "must be in [0, 1)"},
      {"missing column",
       "mode,frequency_hz,damping_ratio,participation_x,participation_y,participation_z,shape_x,shape_y\n", 1, 1,
       "header", "missing column 'shape_z'"},
      {"duplicate column", kHeader.substr(0, kHeader.size() - 1) + ",mode\n", 1,
       static_cast<int>(kHeader.size()) + 1, "header", "duplicate column 'mode'"},
      {"unknown column",
       "mode,frequency_hz,damping_ratio,participation_x,participation_y,participation_z,shape_x,shape_y,shape_w\n",
       1, 97, "header", "unknown column 'shape_w'; allowed: mode,frequency_hz"},
      {"short row", kHeader + kUnits + "1,25,0.03,0,1,0,0,1\n", 3, 1, "mode", "has 8 fields; expected 9"},
      {"duplicate mode", kHeader + kUnits + kRow + kRow, 4, 1, "mode", "duplicate mode 1"},
      {"mode not an integer", kHeader + kUnits + "first,25,0.03,0,1,0,0,1,0\n", 3, 1, "mode",
       "expected a positive integer"},
      {"too many modes", ManyModes(101), 103, 1, "mode", "at most 100 modes"},
      // A NUL shown, and the message not cut there (issue 32 item 16).
      {"NUL in a column name",
       std::string("mode,frequency_hz") + '\0' +
           "x,damping_ratio,participation_x,participation_y,participation_z,shape_x,shape_y,shape_z\n",
       1, 6, "header", "unknown column 'frequency_hz\\x00x'; allowed: mode,frequency_hz"},
  };
  ScratchDir dir;
  dir.Write("m.yaml", "modal_file: bad.csv\n");
  for (const BadFile& c : cases) {
    SCOPED_TRACE(c.what);
    dir.Write("bad.csv", c.text);
    const testing::CliResult result = RunCli({"modes", "m.yaml"}, dir.path().string());
    EXPECT_EQ(result.exit_code, 2) << result.err;
    // Relative to m.yaml, given relative to the working directory.
    const std::string located = "error: bad.csv:" + std::to_string(c.line) + ":" + std::to_string(c.column) +
                                ": " + c.key + ": ";
    EXPECT_EQ(result.err.rfind(located, 0), 0u) << result.err << "expected: " << located;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
  }
}

// Tests that a good export may order its columns freely, end lines in CR LF, pad fields with
// spaces, carry comment and blank lines and leave the mode's unit empty: the modes read are
// the file's numbers, each coupled.
TEST(ModalFile, ReadsWhatAnExportMayVary) {
  const std::string text =
      "# exported by an FE program\r\n"
      "\r\n"
      "shape_z, shape_y ,shape_x,participation_z,participation_y,participation_x,damping_ratio,frequency_hz,mode\r\n"
      "1/sqrt(kg),1/sqrt(kg),1/sqrt(kg),sqrt(kg),sqrt(kg),sqrt(kg),1,Hz,\r\n"
      "6e-4, 8e-4 ,1.5e-3,0,12,3,0.04,38,2\r\n";
  const std::vector<model::ModalMode> modes = ParseModalFile(text, "f.csv");
  ASSERT_EQ(modes.size(), 1u);
  const model::ModalMode& mode = modes[0];
  EXPECT_EQ(mode.frequency_hz, 38.0);
  EXPECT_EQ(mode.damping_ratio, 0.04);
  ASSERT_TRUE(mode.participation && mode.shape);
  EXPECT_EQ(mode.participation->x, 3.0);
  EXPECT_EQ(mode.participation->y, 12.0);
  EXPECT_EQ(mode.shape->x, 1.5e-3);
  EXPECT_EQ(mode.shape->y, 8e-4);
  EXPECT_EQ(mode.shape->z, 6e-4);
}

}  // namespace
}  // namespace shapebench::bench
