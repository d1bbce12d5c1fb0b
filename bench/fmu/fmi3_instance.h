// What an FMI 3.0 fmi3Instance points to in an exported FMU (fmi3_exports.cc and
// fmi3_refusals.cc): the Instance and the master's logger.
#pragma once

#include <memory>
#include <string>

#include "bench/fmi/fmi3_api.h"
#include "bench/fmu/fmu_instance.h"

namespace shapebench::bench::fmu {

struct Fmi3Instance {
  std::unique_ptr<Instance> instance;
  fmi3InstanceEnvironment environment = nullptr;
  fmi3LogMessageCallback log = nullptr;
  bool logging_on = false;

  // Errors always; information only with logging on.
  void Log(bool error, const std::string& message) const {
    if (log == nullptr || (!error && !logging_on)) return;
    log(environment, error ? fmi3Error : fmi3OK, error ? "logStatusError" : "logInfo", message.c_str());
  }
};

}  // namespace shapebench::bench::fmu
