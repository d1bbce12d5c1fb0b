// An FMU archive unpacked into a private temporary directory for as long as the object
// lives (removed, whatever happens, by its destructor): modelDescription.xml, the binary
// for this platform, resources/.
#pragma once

#include <string>

#include "bench/fmi/model_description.h"

namespace shapebench::bench {

class UnpackedFmu {
 public:
  // Unpacks `fmu_path` (a zip) and parses its modelDescription.xml. Throws FmuError: not a
  // zip, a member that would land outside the directory, no modelDescription.xml, no
  // binary for this platform (binaries/linux64 for 2.0, binaries/x86_64-linux for 3.0).
  explicit UnpackedFmu(const std::string& fmu_path);
  ~UnpackedFmu();
  UnpackedFmu(const UnpackedFmu&) = delete;
  UnpackedFmu& operator=(const UnpackedFmu&) = delete;

  const std::string& fmu_path() const { return fmu_path_; }
  const std::string& dir() const { return dir_; }
  const ModelDescription& description() const { return description_; }
  // The shared library for this platform and the resources folder (as a path and as the
  // file:// URI FMI 2.0 wants).
  const std::string& binary() const { return binary_; }
  std::string resources_dir() const { return dir_ + "/resources"; }
  std::string resources_uri() const { return "file://" + dir_ + "/resources"; }

 private:
  void Unzip();
  std::string fmu_path_;
  std::string dir_;
  ModelDescription description_;
  std::string binary_;
};

}  // namespace shapebench::bench
