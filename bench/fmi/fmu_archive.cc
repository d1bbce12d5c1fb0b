#include "bench/fmi/fmu_archive.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>
#include <vector>

#include <zip.h>

namespace shapebench::bench {
namespace fs = std::filesystem;
namespace {

// A member name that stays inside the directory: relative, no "..", no empty name.
bool SafeMemberName(const std::string& name) {
  if (name.empty() || name[0] == '/' || name.find('\\') != std::string::npos) return false;
  for (const auto& part : fs::path(name)) {
    if (part == "..") return false;
  }
  return true;
}

struct ZipCloser {
  void operator()(zip_t* archive) const { zip_discard(archive); }
};
struct ZipFileCloser {
  void operator()(zip_file_t* file) const { zip_fclose(file); }
};

}  // namespace

UnpackedFmu::UnpackedFmu(const std::string& fmu_path) : fmu_path_(fmu_path) {
  std::string pattern = (fs::temp_directory_path() / "shapebench-fmu-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw FmuError("cannot create a temporary directory for " + fmu_path);
  dir_ = pattern;
  try {
    Unzip();
    const std::string md = dir_ + "/modelDescription.xml";
    if (!fs::exists(md)) throw FmuError(fmu_path + ": no modelDescription.xml at the archive's top level");
    description_ = ParseModelDescription(md, fmu_path + ":modelDescription.xml");
    const char* platform = description_.version == FmiVersion::k2 ? "linux64" : "x86_64-linux";
    const std::string member =
        std::string("binaries/") + platform + "/" + description_.model_identifier + ".so";
    binary_ = dir_ + "/" + member;
    if (!fs::exists(binary_)) {
      throw FmuError(fmu_path + ": no " + member + " (FMI " + description_.fmi_version +
                     ": the master runs the x86_64 Linux binary of the co-simulation model identifier)");
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
    throw;
  }
}

UnpackedFmu::~UnpackedFmu() {
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

void UnpackedFmu::Unzip() {
  int code = 0;
  std::unique_ptr<zip_t, ZipCloser> archive(zip_open(fmu_path_.c_str(), ZIP_RDONLY, &code));
  if (!archive) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw FmuError(fmu_path_ + ": cannot be opened as an FMU (a zip archive): " + why);
  }
  const zip_int64_t n = zip_get_num_entries(archive.get(), 0);
  std::vector<char> buffer(1 << 16);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* raw = zip_get_name(archive.get(), static_cast<zip_uint64_t>(i), 0);
    const std::string name = raw == nullptr ? "" : raw;
    if (!SafeMemberName(name)) throw FmuError(fmu_path_ + ": member \"" + name + "\" would unpack outside the FMU");
    const fs::path target = fs::path(dir_) / name;
    if (name.back() == '/') {
      fs::create_directories(target);
      continue;
    }
    fs::create_directories(target.parent_path());
    std::unique_ptr<zip_file_t, ZipFileCloser> in(zip_fopen_index(archive.get(), static_cast<zip_uint64_t>(i), 0));
    if (!in) throw FmuError(fmu_path_ + ": member \"" + name + "\" cannot be read: " + zip_strerror(archive.get()));
    std::ofstream out(target, std::ios::binary);
    zip_int64_t got = 0;
    while ((got = zip_fread(in.get(), buffer.data(), buffer.size())) > 0) out.write(buffer.data(), got);
    if (got < 0) throw FmuError(fmu_path_ + ": member \"" + name + "\" is damaged (" + zip_file_strerror(in.get()) + ")");
    if (!out) throw FmuError("cannot write " + target.string() + " while unpacking " + fmu_path_);
  }
}

}  // namespace shapebench::bench
