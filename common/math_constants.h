// The constants every room shares.
#pragma once

namespace shapebench {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace shapebench
