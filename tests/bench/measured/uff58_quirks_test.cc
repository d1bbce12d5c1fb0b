// Real writers' quirks the UFF 58 reader (bench/measured/uff58_reader.h) reads with a
// warning when the data proves them, and values that are not finite, which the
// identification (bench/measured/frf_identification.h) ignores outside its band only.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bench/config/config_error.h"
#include "bench/measured/frf_identification.h"
#include "bench/measured/uff58_reader.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/uff58_writer.h"

namespace shapebench::bench {
namespace {

using testing::ScratchDir;
using testing::SyntheticAccelerance;
using testing::UffFrf;

// A 58b of complex doubles whose identifier line announces half its data's bytes, as
// pyuff's writer does; `keep_bytes` of the data are kept (all: the quirk; half: a
// file whose length matches the count it announces).
std::string HalfCountBinary(const UffFrf& frf, std::size_t keep_bytes) {
  std::string text = testing::Uff58Binary(frf, /*big_endian=*/false);
  const std::size_t identifier = text.find('\n') + 1;  // after the opening "    -1"
  const std::size_t bytes = frf.values.size() * 16;
  char field[16];
  std::snprintf(field, sizeof field, "%12zu", bytes / 2);
  text.replace(identifier + 31, 12, field);
  const std::size_t data = text.size() - std::string("    -1\n").size() - bytes;
  return text.substr(0, data + keep_bytes) + "    -1\n";
}

// Tests that pyuff's half byte count for complex doubles is read when the full data and
// "    -1" follow (the same values as the correct file, a warning at the identifier line's
// byte count), and refused when the file holds only the bytes it announces.
TEST(Uff58Quirks, HalfByteCountOfComplexDoubles) {
  UffFrf frf = SyntheticAccelerance(0.01, 3);
  const std::size_t bytes = frf.values.size() * 16;
  const Uff58File quirk = ParseUff58(HalfCountBinary(frf, bytes), "pyuff.uff");
  const Uff58File correct = ParseUff58(testing::Uff58Binary(frf, false), "right.uff");
  ASSERT_EQ(quirk.records.size(), 1u);
  EXPECT_EQ(quirk.records[0].values, correct.records[0].values);
  EXPECT_EQ(quirk.records[0].frequency_hz, correct.records[0].frequency_hz);
  ASSERT_EQ(quirk.warnings.size(), 1u);
  EXPECT_EQ(quirk.warnings[0].rfind("pyuff.uff:2:32: record 58b: 6408 bytes of data announced, half the 12816", 0), 0u)
      << quirk.warnings[0];
  EXPECT_TRUE(correct.warnings.empty());
  try {
    ParseUff58(HalfCountBinary(frf, bytes / 2), "short.uff");
    FAIL() << "a file of the announced half length was read";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("short.uff:2:32: record 58b: 6408 bytes of data: record 7 announces 801 "
                                             "values, 12816 bytes"),
              std::string::npos)
        << error.what();
  }
}

// Tests that NaN and inf values are kept and listed with their point, line and column
// (ASCII) or value number (58b), once per point, and that a non-finite abscissa is refused.
TEST(Uff58Quirks, NonFiniteValuesAreListed) {
  UffFrf frf = SyntheticAccelerance(0.0, 1);
  frf.values[0] = {std::nan(""), std::nan("")};
  frf.values[5] = {1.0, INFINITY};
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "58b" : "ASCII");
    const Uff58File file =
        ParseUff58(binary ? testing::Uff58Binary(frf, false) : testing::Uff58Ascii(frf), "n.uff");
    const std::vector<Uff58NonFinite>& listed = file.records[0].non_finite;
    ASSERT_EQ(listed.size(), 2u);
    EXPECT_EQ(listed[0].point, 0u);
    EXPECT_EQ(listed[1].point, 5u);
    EXPECT_EQ(listed[1].line, binary ? 14 : 16);
    EXPECT_EQ(listed[1].column, binary ? 1 : 61);
    EXPECT_EQ(listed[1].text, binary ? "binary value 12" : "inf");
    EXPECT_TRUE(std::isnan(file.records[0].values[0].real()));
  }
  UffFrf uneven = frf;
  uneven.values[0] = 1.0;
  uneven.values[5] = 1.0;
  uneven.even = false;
  uneven.frequency_hz[3] = std::nan("");
  EXPECT_THROW(ParseUff58(testing::Uff58Ascii(uneven), "x.uff"), ConfigError);
}

// Tests that the identification ignores a NaN outside its band with a warning naming the
// record's line and refuses one inside it at its line and column; a file whose quirk is
// read carries the reader's warning and the same modes as the correct file.
TEST(Uff58Quirks, IdentificationUsesTheBand) {
  ScratchDir dir;
  UffFrf frf = SyntheticAccelerance(0.0, 1);
  frf.values[0] = {std::nan(""), 0.0};  // 0 Hz: outside every band
  FrfSelection selection;
  const IdentifiedFrfs frfs = IdentifyFrfFile(dir.Write("zero.uff", testing::Uff58Ascii(frf)), selection);
  ASSERT_EQ(frfs.warnings.size(), 1u);
  EXPECT_NE(frfs.warnings[0].find("zero.uff:14:1: record 12: 1 line with a value that is not a finite number (nan at "
                                  "0 Hz) outside the band [0, inf] Hz: ignored"),
            std::string::npos)
      << frfs.warnings[0];
  EXPECT_EQ(frfs.identification.modes.size(), 3u);
  frf.values[0] = 0.0;
  frf.values[400] = {0.0, std::nan("")};  // 50 Hz
  const std::string inside = dir.Write("inside.uff", testing::Uff58Ascii(frf));
  try {
    IdentifyFrfFile(inside, selection);
    FAIL() << "a NaN inside the band was identified";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("inside.uff:214:21: record 12: value nan at 50 Hz is not a finite number"),
              std::string::npos)
        << error.what();
  }
  selection.max_frequency_hz = 45.0;
  EXPECT_EQ(IdentifyFrfFile(inside, selection).warnings.size(), 1u);
  const UffFrf clean = SyntheticAccelerance(0.01, 3);
  const IdentifiedFrfs quirk = IdentifyFrfFile(dir.Write("q.uff", HalfCountBinary(clean, clean.values.size() * 16)), {});
  const IdentifiedFrfs right = IdentifyFrfFile(dir.Write("r.uff", testing::Uff58Binary(clean, false)), {});
  ASSERT_EQ(quirk.warnings.size(), 1u);
  ASSERT_EQ(quirk.identification.modes.size(), right.identification.modes.size());
  for (std::size_t r = 0; r < right.identification.modes.size(); ++r) {
    EXPECT_EQ(quirk.identification.modes[r].frequency_hz, right.identification.modes[r].frequency_hz);
  }
}

}  // namespace
}  // namespace shapebench::bench
