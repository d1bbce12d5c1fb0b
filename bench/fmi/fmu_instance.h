// One instance of a co-simulation FMU (FMI 2.0 or 3.0), owned: its library dlopen'ed from
// the unpacked FMU, the functions the master calls resolved, the instance made, set up and
// initialised; the destructor terminates it (when it may), frees it and closes the library.
// A status other than OK/Warning throws model::SolverError("FMU_ERROR") naming the
// function, the status in words and the FMU's last logger messages (exit 3).
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/fmi/fmu_archive.h"

namespace shapebench::bench {

class FmuInstance {
 public:
  // dlopen and dlsym: a missing function throws FmuError (a bad FMU, exit 2). Then
  // instantiate, set `parameters` (value reference, value) before initialisation, and
  // initialise for a run from t = 0 to `stop_time_s` (SolverError on a failed status; the
  // inputs keep their start values until the first step sets them).
  FmuInstance(std::shared_ptr<const UnpackedFmu> fmu, const std::vector<std::pair<unsigned, double>>& parameters,
              double stop_time_s);
  ~FmuInstance();
  FmuInstance(const FmuInstance&) = delete;
  FmuInstance& operator=(const FmuInstance&) = delete;

  void SetReal(const std::vector<unsigned>& refs, const double* values);
  void GetReal(const std::vector<unsigned>& refs, double* values);
  // One communication step from t to t + h.
  void DoStep(double t, double h);

  // Called by the logger callbacks.
  void Log(int status, const std::string& category, const std::string& message);

 private:
  struct Api;
  void Resolve();
  void Release();  // terminates (when initialised) and frees the instance, once
  void Instantiate();
  void Initialize(const std::vector<std::pair<unsigned, double>>& parameters, double stop_time_s);
  // Throws SolverError unless `status` is OK or Warning.
  void Check(int status, const char* function, double t = -1.0);

  std::shared_ptr<const UnpackedFmu> fmu_;
  bool v3_ = false;
  struct LibraryCloser {
    void operator()(void* handle) const;
  };
  std::unique_ptr<void, LibraryCloser> library_;  // declared first: closed last
  std::unique_ptr<Api> api_;
  void* instance_ = nullptr;
  bool initialized_ = false;  // terminate is due at the end
  bool failed_ = false;       // after Error: free only; after Fatal: nothing
  bool fatal_ = false;
  std::deque<std::string> log_;  // the last messages, for an error's text
  std::vector<double> scratch_;
};

}  // namespace shapebench::bench
