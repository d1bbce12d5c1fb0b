// A sweep file in a scratch directory, its base the SDOF scenario of the test data.
#pragma once

#include <string>
#include <vector>

#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench::testing {

class SweepFile {
 public:
  explicit SweepFile(const std::string& body) {
    path_ = dir_.Write("sweep.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") + "\n" + body);
  }
  const std::string& path() const { return path_; }
  Sweep Load(const std::vector<Override>& sets = {}, const SweepLoadOptions& options = {}) const {
    return LoadSweep(path_, sets, options);
  }

 private:
  ScratchDir dir_;
  std::string path_;
};

}  // namespace shapebench::bench::testing
