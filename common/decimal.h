// Numbers typed on the command line as people write them: decimal only. strtod also reads
// hexadecimal ("0x10" is 16: a --gate of 1600%), "inf", "nan" and leading blanks, none of
// which a user means in a band or a tolerance.
#pragma once

#include <string_view>

namespace shapebench {

// True, with *value, when `text` is a whole decimal number: [+-] digits [. digits]
// [(e|E) [+-] digits], at least one digit before the exponent, nothing else, finite.
bool ParseDecimal(std::string_view text, double* value);

}  // namespace shapebench
