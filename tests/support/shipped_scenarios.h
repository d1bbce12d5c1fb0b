// The shipped scenarios (configs/demo.yaml and configs/scenarios/*.yaml), sorted: what the
// golden set runs and the tests that go over every shipped case take.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace shapebench::bench::testing {

inline std::vector<std::string> ShippedScenarios() {
  const std::string top = SHAPEBENCH_SOURCE_DIR;
  std::vector<std::string> files = {top + "/configs/demo.yaml"};
  for (const auto& entry : std::filesystem::directory_iterator(top + "/configs/scenarios")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace shapebench::bench::testing
