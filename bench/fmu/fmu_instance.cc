#include "bench/fmu/fmu_instance.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bench/config/override.h"
#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench::fmu {
namespace {

Part ReadIdentity(const std::string& dir, const std::string& token) {
  const std::string path = dir + "/" + kIdentityResource;
  const YAML::Node identity = YAML::LoadFile(path);
  const std::string part = identity["part"].as<std::string>("");
  if (part != "machine" && part != "controller") {
    throw std::runtime_error(path + ": part must be machine or controller (got \"" + part + "\")");
  }
  const std::string packed = identity["token"].as<std::string>("");
  if (packed != token) {
    throw std::runtime_error("instantiation token " + token + " is not this FMU's (" + packed +
                             "): the modelDescription.xml belongs to another FMU");
  }
  return part == "machine" ? Part::kMachine : Part::kController;
}

}  // namespace

std::string ResourceDirFromUri(const std::string& uri) {
  std::string path = uri;
  if (path.rfind("file:", 0) == 0) {
    path = path.substr(5);
    if (path.rfind("///", 0) == 0) {
      path = path.substr(2);
    } else if (path.rfind("//localhost/", 0) == 0) {
      path = path.substr(11);
    }
    std::string decoded;
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (path[i] == '%' && i + 2 < path.size()) {
        decoded += static_cast<char>(std::strtol(path.substr(i + 1, 2).c_str(), nullptr, 16));
        i += 2;
      } else {
        decoded += path[i];
      }
    }
    path = decoded;
  }
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

Instance::Instance(const std::string& resource_dir, const std::string& token, Log log)
    : scenario_path_(resource_dir + "/" + kScenarioResource), log_(std::move(log)) {
  const Part part = ReadIdentity(resource_dir, token);
  layout_ = MakeLayout(LoadScenario(scenario_path_, {}), part);
  Reset();
}

bool Instance::Fail(const std::string& message) const {
  log_(true, message);
  return false;
}

bool Instance::Unsupported(const std::string& what) const {
  return Fail(what + " is not supported by this FMU (shapebench, docs/fmi.md#limits)");
}

void Instance::Reset() {
  values_.assign(layout_.variables.size(), 0.0);
  for (const Variable& v : layout_.variables) {
    if (v.has_start) values_[v.value_reference] = v.start;
  }
  slave_.reset();
  phase_ = Phase::kInstantiated;
  time_ = 0.0;
}

bool Instance::SetReals(const unsigned* refs, std::size_t n, const double* values) {
  for (std::size_t i = 0; i < n; ++i) {
    if (refs[i] >= values_.size()) return Fail("value reference " + std::to_string(refs[i]) + " is no variable of this FMU");
    const Variable& v = layout_.variables[refs[i]];
    const bool before_stepping = phase_ == Phase::kInstantiated || phase_ == Phase::kInitialization;
    const bool settable = v.causality == Causality::kInput ? phase_ != Phase::kTerminated && phase_ != Phase::kFailed
                          : v.causality == Causality::kParameter ? before_stepping
                                                                  : false;
    if (!settable) {
      return Fail("variable " + v.name + " cannot be set " +
                  (v.causality == Causality::kParameter ? "after initialization (a fixed parameter)" : "(not an input or parameter)"));
    }
    values_[refs[i]] = values[i];
  }
  return true;
}

bool Instance::GetReals(const unsigned* refs, std::size_t n, double* values) const {
  for (std::size_t i = 0; i < n; ++i) {
    if (refs[i] >= values_.size()) return Fail("value reference " + std::to_string(refs[i]) + " is no variable of this FMU");
    values[i] = refs[i] == 0 ? time_ : values_[refs[i]];
  }
  return true;
}

bool Instance::EnterInitialization() {
  if (phase_ != Phase::kInstantiated) return Fail("enter initialization mode: only right after instantiation or reset");
  phase_ = Phase::kInitialization;
  return true;
}

// The packed scenario with every parameter the master changed as a --set override (the
// scenario's own validation then applies, e.g. a negative damping ratio is refused).
Scenario Instance::LoadWithParameters() const {
  std::vector<Override> overrides;
  for (const ParameterRef& p : layout_.parameters) {
    const double value = values_[p.value_reference];
    if (value == layout_.variables[p.value_reference].start) continue;
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    overrides.push_back({p.key_path, text});
  }
  return LoadScenario(scenario_path_, overrides);
}

bool Instance::ExitInitialization() {
  if (phase_ != Phase::kInitialization) return Fail("exit initialization mode: not in initialization mode");
  try {
    const Scenario scenario = LoadWithParameters();
    slave_ = layout_.part == Part::kMachine ? MakeMachineSlave(scenario, layout_)
                                            : MakeControllerSlave(scenario, layout_);
    slave_->WriteInitialOutputs(&values_);
  } catch (const std::exception& e) {
    phase_ = Phase::kFailed;
    return Fail(std::string("exit initialization mode: ") + e.what());
  }
  phase_ = Phase::kStepping;
  return true;
}

bool Instance::DoStep(double t, double h) {
  if (phase_ != Phase::kStepping) return Fail("doStep: not in step mode (initialization not done, or terminated)");
  if (!(h > 0.0)) return Fail("doStep: the communication step size must be > 0 (got " + std::to_string(h) + ")");
  try {
    slave_->DoStep(t, h, &values_);
  } catch (const std::exception& e) {
    phase_ = Phase::kFailed;
    return Fail(std::string("doStep at t = ") + std::to_string(t) + " s: " + e.what());
  }
  time_ = t + h;
  return true;
}

}  // namespace shapebench::bench::fmu
