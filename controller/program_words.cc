#include "controller/program_words.h"

#include <utility>

namespace shapebench::controller {

ProgramError::ProgramError(int line, int column, int word_index, std::string message)
    : std::runtime_error((column > 0 ? std::to_string(line) + ":" + std::to_string(column)
                                     : std::to_string(line)) +
                         ": " + message),
      line_(line),
      column_(column),
      word_index_(word_index),
      message_(std::move(message)) {}

}  // namespace shapebench::controller
