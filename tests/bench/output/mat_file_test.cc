// MAT files: version 5 as MatFile writes it directly is byte for byte what libmatio writes
// (the oracle here: libmatio itself), and results.mat reads results.csv as CsvReader and
// strtod do.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>
#include <matio.h>

#include "bench/output/mat_file.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench::mat_file_test {
namespace {

using testing::ReadText;
using testing::ScratchDir;

// A variable for the oracle: numbers, or strings when `texts` is set.
struct OracleVariable {
  std::string name;
  std::vector<double> numbers;
  std::vector<std::string> texts;
  bool strings = false;
};

// The file libmatio writes of `variables` (version 5, uncompressed, the header MatFile
// writes): what MatFile wrote through libmatio before it wrote version 5 itself.
void WriteWithMatio(const std::string& path, std::vector<OracleVariable> variables) {
  mat_t* mat = Mat_CreateVer(path.c_str(), "shapebench", MAT_FT_MAT5);
  ASSERT_NE(mat, nullptr);
  for (OracleVariable& variable : variables) {
    matvar_t* var = nullptr;
    if (variable.strings) {
      std::size_t dims[2] = {variable.texts.size(), 1};
      var = Mat_VarCreate(variable.name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
      for (std::size_t i = 0; i < variable.texts.size(); ++i) {
        std::size_t text_dims[2] = {1, variable.texts[i].size()};
        Mat_VarSetCell(var, static_cast<int>(i), Mat_VarCreate(nullptr, MAT_C_CHAR, MAT_T_UINT8, 2, text_dims,
                                                               variable.texts[i].data(), 0));
      }
    } else {
      std::size_t dims[2] = {variable.numbers.size(), 1};
      var = Mat_VarCreate(variable.name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, variable.numbers.data(),
                          MAT_F_DONT_COPY_DATA);
    }
    ASSERT_NE(var, nullptr);
    EXPECT_EQ(Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE), 0) << variable.name;
    Mat_VarFree(var);
  }
  ASSERT_EQ(Mat_Close(mat), 0);
}

// MatFile's file of the same variables.
void WriteWithMatFile(const std::string& path, const std::vector<OracleVariable>& variables) {
  MatFile mat(path, 1024);
  for (const OracleVariable& variable : variables) {
    if (variable.strings) {
      mat.WriteStrings(variable.name, std::vector<std::string_view>(variable.texts.begin(), variable.texts.end()));
    } else {
      mat.WriteColumn(variable.name, variable.numbers);
    }
  }
  mat.Commit(Durability::kUnsynced);
}

OracleVariable Numbers(const std::string& name, std::vector<double> numbers) {
  return {name, std::move(numbers), {}, false};
}
OracleVariable Strings(const std::string& name, std::vector<std::string> texts) {
  return {name, {}, std::move(texts), true};
}

// The double strtod reads from `text` (what results.mat's numbers are).
double Strtod(const char* text) { return std::strtod(text, nullptr); }

// Tests that MatFile writes version 5 byte for byte as libmatio does: names in the small
// element format (up to 4 bytes) and padded to 8 beyond, empty and one-row columns, NaN, -0
// and infinities, strings empty, of 8 bytes, longer, with non-ASCII UTF-8, an empty cell.
TEST(MatFileTest, Version5IsByteForByteWhatLibmatioWrites) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<OracleVariable> variables = {
      Numbers("a", {1.5}), Numbers("abcd", {}), Numbers("abcde", {nan, -0.0, inf, -inf, 4.9e-324}),
      Numbers("eight_ch", {1, 2, 3}), Numbers(std::string(63, 'x'), {0.1}),
      Strings("s", {"ok"}), Strings("none", {}), Strings("strings_of_all_sizes",
          {"", "12345678", "123456789", "caf\xc3\xa9 \xe2\x82\xac", "with,comma and \"quotes\"\nand a newline"}),
      Strings("columns", {"a", "abcd"})};
  ScratchDir dir;
  WriteWithMatio(dir.File("matio.mat"), variables);
  WriteWithMatFile(dir.File("matfile.mat"), variables);
  const std::string expected = ReadText(dir.File("matio.mat"));
  ASSERT_GT(expected.size(), 128u);
  EXPECT_TRUE(ReadText(dir.File("matfile.mat")) == expected);
}

// Tests that a second variable of a name is refused (libmatio refused it too), naming it.
TEST(MatFileTest, RefusesASecondVariableOfTheSameName) {
  ScratchDir dir;
  MatFile mat(dir.File("twice.mat"), 1024);
  mat.WriteColumn("a_b", {1.0});
  try {
    mat.WriteStrings("a_b", {"x"});
    FAIL() << "a second a_b was written";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("two variables named a_b"), std::string::npos) << error.what();
  }
}

// Tests that results.mat reads results.csv's fields as CsvReader does (quoted fields with
// commas, doubled quotes and newlines; CR dropped outside quotes; missing fields empty; a
// torn last record left out) and each as strtod reads it (a sign '+', hex, inf, nan,
// overflow, underflow, a subnormal; empty is NaN; a leading space, even in the last row,
// makes the column text), byte for byte as libmatio writes the same variables.
TEST(MatFileTest, ResultsMatReadsTheCsvAsCsvReaderAndStrtod) {
  ScratchDir dir;
  const std::string csv = dir.Write("results.csv",
      "plain,quoted,signs,turns,text\n"
      "1.5,\"3\",+1,1,\"a \"\"quoted\"\" word\"\n"
      ",\"2.25\",0x10,2,\"line\nbreak\"\r\n"
      "-0,\"-1e3\",-inf,3,multi\r\n"
      ".5,4,nan,4,\"with,comma\"\n"
      "5.,5,1e-400,5\n"
      "1e400,6,4.9e-324, 7,\n"
      "9,9,9,9,torn");
  WriteResultsMat(csv, dir.File("results.mat"), Durability::kUnsynced);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WriteWithMatio(dir.File("expected.mat"),
                 {Numbers("plain", {1.5, nan, Strtod("-0"), 0.5, 5.0, Strtod("1e400")}),
                  Numbers("quoted", {3, 2.25, -1000, 4, 5, 6}),
                  Numbers("signs", {1, 16, Strtod("-inf"), Strtod("nan"), Strtod("1e-400"), Strtod("4.9e-324")}),
                  Strings("turns", {"1", "2", "3", "4", "5", " 7"}),
                  Strings("text", {"a \"quoted\" word", "line\nbreak", "multi", "with,comma", "", ""}),
                  Strings("columns", {"plain", "quoted", "signs", "turns", "text"})});
  EXPECT_TRUE(ReadText(dir.File("results.mat")) == ReadText(dir.File("expected.mat")));
}

// Tests that a file whose largest variable is over version 5's 2 GiB is version 7.3, written
// by libmatio loaded then (not linked), and reads back: a column of doubles and of strings.
TEST(MatFileTest, OverVersion5sLimitIsVersion73ThroughLibmatio) {
  ScratchDir dir;
  const std::string path = dir.File("large.mat");
  {
    MatFile mat(path, std::uint64_t{3} << 30);
    mat.WriteColumn("values", {1.5, -2.0});
    mat.WriteStrings("names", {"ok", ""});
    mat.Commit(Durability::kUnsynced);
  }
  mat_t* mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
  ASSERT_NE(mat, nullptr);
  EXPECT_EQ(Mat_GetVersion(mat), MAT_FT_MAT73);
  matvar_t* values = Mat_VarRead(mat, "values");
  ASSERT_NE(values, nullptr);
  ASSERT_EQ(values->class_type, MAT_C_DOUBLE);
  EXPECT_EQ(values->dims[0], 2u);
  EXPECT_EQ(static_cast<const double*>(values->data)[0], 1.5);
  EXPECT_EQ(static_cast<const double*>(values->data)[1], -2.0);
  Mat_VarFree(values);
  matvar_t* names = Mat_VarRead(mat, "names");
  ASSERT_NE(names, nullptr);
  EXPECT_EQ(names->class_type, MAT_C_CELL);
  matvar_t* first = Mat_VarGetCell(names, 0);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->class_type, MAT_C_CHAR);
  EXPECT_EQ(first->dims[1], 2u);  // "ok" (read back as 16-bit characters)
  Mat_VarFree(names);
  Mat_Close(mat);
}

}  // namespace
}  // namespace shapebench::bench::mat_file_test
