// One instance of an exported FMU, whatever the FMI version: the packed scenario read from
// the FMU's resources at instantiation, the variables' values by value reference, the
// standard's state machine (instantiated, initialization, stepping), and the slave. The
// C functions (fmi2_exports.cc, fmi3_exports.cc) translate to and from it.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench/fmu/fmu_layout.h"
#include "bench/fmu/slave.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench::fmu {

// The files `shapebench fmu` packs under resources/ (docs/fmi.md).
inline constexpr const char* kScenarioResource = "scenario.yaml";
inline constexpr const char* kIdentityResource = "shapebench_fmu.yaml";  // part, token

class Instance {
 public:
  using Log = std::function<void(bool error, const std::string& message)>;
  // `resource_dir`: a directory path. Throws std::exception when the resources cannot be
  // read, the scenario is refused, or `token` is not the packed one (another FMU's).
  Instance(const std::string& resource_dir, const std::string& token, Log log);

  // Each returns false after logging why (an unknown value reference, a variable that
  // cannot be set now, a call out of order, a step the slave refuses).
  bool SetReals(const unsigned* refs, std::size_t n, const double* values);
  bool GetReals(const unsigned* refs, std::size_t n, double* values) const;
  bool EnterInitialization();
  bool ExitInitialization();
  bool DoStep(double t, double h);
  void Terminate() { phase_ = Phase::kTerminated; }
  void Reset();
  // Logs that `what` is not supported by this FMU and returns false.
  bool Unsupported(const std::string& what) const;
  Part part() const { return layout_.part; }
  double time() const { return time_; }

 private:
  enum class Phase { kInstantiated, kInitialization, kStepping, kTerminated, kFailed };
  bool Fail(const std::string& message) const;
  Scenario LoadWithParameters() const;

  std::string scenario_path_;
  Log log_;
  Layout layout_;
  std::vector<double> values_;
  std::unique_ptr<Slave> slave_;
  Phase phase_ = Phase::kInstantiated;
  double time_ = 0.0;
};

// The directory of an FMI 2.0 fmuResourceLocation URI ("file:///dir", "file:/dir",
// "file://localhost/dir", percent-encoded); a plain path is taken as it is.
std::string ResourceDirFromUri(const std::string& uri);

}  // namespace shapebench::bench::fmu
