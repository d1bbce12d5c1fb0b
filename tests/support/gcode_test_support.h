// What the G-code tests share: options for a dialect, a parse from the origin, and the
// check that a program is refused at a line and column with a message. One definition
// for every test file (unity batches would collide two copies).
#pragma once

#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "controller/gcode_parser.h"

namespace shapebench::controller {

inline GcodeOptions In(Dialect dialect, long max_iterations = 1000000) {
  GcodeOptions options;
  options.program.dialect = dialect;
  options.program.max_iterations = max_iterations;
  return options;
}

inline Program Parse(const std::string& text, const GcodeOptions& options) {
  return ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
}

inline void ExpectError(const std::string& text, const GcodeOptions& options, int line, int column,
                        const std::string& message_part) {
  try {
    Parse(text, options);
    ADD_FAILURE() << "no ProgramError for:\n" << text;
  } catch (const ProgramError& error) {
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_EQ(error.column(), column) << error.what();
    EXPECT_NE(error.message().find(message_part), std::string::npos) << error.what();
  }
}

}  // namespace shapebench::controller
