// ParseDecimal (common/decimal.h): what a command-line number may be.
#include "common/decimal.h"

#include <gtest/gtest.h>

namespace shapebench {
namespace {

// Tests that decimal numbers are read as strtod reads them, and that hexadecimal, inf,
// nan, blanks, a lone sign or dot, a dangling exponent and overflow are refused.
TEST(ParseDecimal, DecimalOnly) {
  double value = 0.0;
  for (const auto& [text, expected] : {std::pair<const char*, double>{"5", 5.0}, {"-0.25", -0.25}, {"+3.", 3.0},
                                       {".5", 0.5}, {"1e-3", 1e-3}, {"2.5E+2", 250.0}, {"0.1", 0.1}}) {
    ASSERT_TRUE(ParseDecimal(text, &value)) << text;
    EXPECT_EQ(value, expected) << text;
  }
  for (const char* text : {"0x10", "0X1p3", "inf", "-inf", "nan", " 5", "5 ", "", "-", ".", "1e", "1e+", "5:", "1e999",
                           "1,5"}) {
    value = 42.0;
    EXPECT_FALSE(ParseDecimal(text, &value)) << text;
    EXPECT_EQ(value, 42.0) << text;
  }
}

}  // namespace
}  // namespace shapebench
