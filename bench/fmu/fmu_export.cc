#include "bench/fmu/fmu_export.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <zip.h>

#include "bench/config/config_error.h"
#include "bench/fmu/fmu_instance.h"
#include "bench/fmu/model_description.h"
#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench::fmu {
namespace {

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw ConfigError(path, 0, 0, "", "cannot read the FMU library");
  return bytes.str();
}

// The scenario as it will be packed (its machine file spliced in, the --set applied), and
// the same text loaded back from a directory of its own, as the FMU will load it: a file it
// refers to by a relative path (a G-code program, a modal file) is then not found.
std::string PackedScenario(const ExportRequest& request, Scenario* packed) {
  YAML::Emitter out;
  out << BuildScenarioTree(request.scenario_path, request.overrides);
  const std::string text = std::string(out.c_str()) + "\n";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("shapebench-fmu-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / kScenarioResource).string();
  std::ofstream(path) << text;
  try {
    *packed = LoadScenario(path, {});
  } catch (const std::exception& e) {
    std::filesystem::remove_all(dir);
    throw ConfigError(request.scenario_path, 0, 0, "",
                      std::string("the FMU packs the scenario alone, and alone it does not load (a file it refers to "
                                  "stays behind: give the program and modes inline): ") + e.what());
  }
  std::filesystem::remove_all(dir);
  return text;
}

}  // namespace

const char* PlatformFolder(int fmi_version) { return fmi_version == 3 ? "x86_64-linux" : "linux64"; }

std::string LibraryBesideExecutable() {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return (exe.parent_path() / "libshapebench_fmu.so").string();
}

void WriteZip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& entries) {
  int code = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  if (zip == nullptr) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw std::runtime_error(path + ": cannot write the FMU: " + why);
  }
  for (const auto& [name, bytes] : entries) {
    zip_source_t* source = zip_source_buffer(zip, bytes.data(), bytes.size(), 0);  // lives until zip_close
    if (source == nullptr || zip_file_add(zip, name.c_str(), source, ZIP_FL_ENC_UTF_8) < 0) {
      if (source != nullptr) zip_source_free(source);
      const std::string why = zip_strerror(zip);
      zip_discard(zip);
      throw std::runtime_error(path + ": cannot add " + name + ": " + why);
    }
  }
  if (zip_close(zip) != 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    throw std::runtime_error(path + ": cannot write the FMU: " + why);
  }
}

ExportResult ExportFmu(const ExportRequest& request) {
  LoadScenario(request.scenario_path, request.overrides);  // located errors first
  Scenario scenario;
  const std::string text = PackedScenario(request, &scenario);
  const Layout layout = MakeLayout(scenario, request.part);
  if (!std::filesystem::is_regular_file(request.library_path)) {
    throw ConfigError(request.library_path, 0, 0, "",
                      "the FMU library is missing: shapebench packs libshapebench_fmu.so from beside its executable "
                      "(build it with the shapebench target)");
  }
  ExportResult result;
  result.model_identifier = ModelIdentifier(std::filesystem::path(request.out_path).stem().string());
  DescriptionInfo info;
  info.model_name = std::filesystem::path(request.scenario_path).stem().string();
  info.model_identifier = result.model_identifier;
  info.token = InstantiationToken(text, request.part, request.fmi_version);
  info.description = std::string("shapebench ") + PartName(request.part) + " of " + request.scenario_path;
  info.generation_tool = request.generation_tool;
  info.fmi_version = request.fmi_version;
  result.model_description = WriteModelDescription(layout, info);
  result.variables = layout.variables.size();
  for (const std::string& problem : CheckModelDescription(result.model_description)) {
    throw std::logic_error("modelDescription.xml: " + problem);  // a bug of the writer
  }
  const std::string identity = std::string("part: ") + PartName(request.part) + "\nfmi_version: " +
                               std::to_string(request.fmi_version) + "\ntoken: \"" + info.token + "\"\n";
  WriteZip(request.out_path,
           {{"modelDescription.xml", result.model_description},
            {std::string("binaries/") + PlatformFolder(request.fmi_version) + "/" + result.model_identifier + ".so",
             ReadBytes(request.library_path)},
            {std::string("resources/") + kScenarioResource, text},
            {std::string("resources/") + kIdentityResource, identity}});
  return result;
}

}  // namespace shapebench::bench::fmu
