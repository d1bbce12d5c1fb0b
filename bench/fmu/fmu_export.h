// `shapebench fmu`: an FMI co-simulation FMU of a scenario's machine or controller
// (docs/fmi.md): a zip with modelDescription.xml, the FMU library (the build's
// libshapebench_fmu.so, renamed to the model identifier) and the scenario under resources/.
#pragma once

#include <string>
#include <vector>

#include "bench/config/override.h"
#include "bench/fmu/fmu_layout.h"

namespace shapebench::bench::fmu {

struct ExportRequest {
  std::string scenario_path;
  std::vector<Override> overrides;  // --set, applied before packing
  Part part = Part::kMachine;
  int fmi_version = 2;              // 2 or 3
  std::string out_path;             // NAME.fmu; NAME gives the model identifier
  std::string library_path;         // the FMU library to pack
  std::string generation_tool = "shapebench";
};

struct ExportResult {
  std::string model_identifier;
  std::string model_description;  // the XML written
  std::size_t variables = 0;
};

// Throws ConfigError (the scenario, a file it refers to that the FMU cannot carry, the
// library missing) or std::runtime_error (the zip cannot be written).
ExportResult ExportFmu(const ExportRequest& request);

// The FMU library beside the running executable (/proc/self/exe's directory).
std::string LibraryBesideExecutable();

// The binaries/ folder of the platform for an FMI version: linux64 (2.0), x86_64-linux (3.0).
const char* PlatformFolder(int fmi_version);

// Writes a zip of (name, bytes) entries; throws std::runtime_error naming the path.
void WriteZip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace shapebench::bench::fmu
