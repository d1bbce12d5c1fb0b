// The one definition of pi for every room. The literal is the one each file used to copy,
// so the doubles (and every result built from them) are unchanged.
#pragma once

namespace shapebench {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace shapebench
