// The field a config's validate() names, for the controller tests.
#pragma once

#include <string>

#include "common/validation_error.h"

namespace shapebench::controller::testing {

// The field of the ValidationError `config.validate()` throws, or "(valid)".
template <typename Config>
std::string FieldOf(const Config& config) {
  try {
    config.validate();
  } catch (const ValidationError& error) {
    return error.field();
  }
  return "(valid)";
}

}  // namespace shapebench::controller::testing
