// The one exception type that config structs' validate() and planners throw for
// physically invalid input. `field` is a dotted key path (e.g. "modes[0].frequency_hz"),
// relative to the struct that threw; callers prefix it with where the struct sits in the
// scenario, and the YAML loader turns it into FILE:LINE:COL.
#pragma once

#include <stdexcept>
#include <string>

namespace shapebench {

class ValidationError : public std::invalid_argument {
 public:
  ValidationError(std::string field, std::string message)
      : std::invalid_argument(field + ": " + message),
        field_(std::move(field)),
        message_(std::move(message)) {}

  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

  // The same error seen from one level up: "modes[0].gain" -> "machine.modes[0].gain".
  ValidationError Prefixed(const std::string& prefix) const {
    if (prefix.empty()) return *this;
    return ValidationError(field_.empty() ? prefix : prefix + "." + field_, message_);
  }

 private:
  std::string field_;
  std::string message_;
};

}  // namespace shapebench
