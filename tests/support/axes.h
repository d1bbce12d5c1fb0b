// The axis indices of the tests (x, y, z: the machine's columns), one definition for every
// test file: the test executables compile their files in unity batches, where two files'
// copies would collide.
#pragma once

namespace shapebench {

inline constexpr int kX = 0;
inline constexpr int kY = 1;
inline constexpr int kZ = 2;

}  // namespace shapebench
