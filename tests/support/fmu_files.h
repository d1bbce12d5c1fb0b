// Exported FMUs in tests: unpacking one with libzip, its modelDescription.xml, and the
// schema check with xmllint against the standard's schema files (tests/data/fmi/).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <zip.h>

#include "tests/support/bench_test_support.h"

namespace shapebench::bench::testing {

// Unpacks `fmu` into `dir` (created); false when the zip cannot be read.
inline bool UnpackFmu(const std::string& fmu, const std::filesystem::path& dir) {
  int code = 0;
  zip_t* zip = zip_open(fmu.c_str(), ZIP_RDONLY, &code);
  if (zip == nullptr) return false;
  const zip_int64_t entries = zip_get_num_entries(zip, 0);
  for (zip_int64_t i = 0; i < entries; ++i) {
    const std::string name = zip_get_name(zip, static_cast<zip_uint64_t>(i), 0);
    zip_file_t* file = zip_fopen_index(zip, static_cast<zip_uint64_t>(i), 0);
    if (file == nullptr) continue;
    const std::filesystem::path out = dir / name;
    std::filesystem::create_directories(out.parent_path());
    std::ofstream stream(out, std::ios::binary);
    char buffer[65536];
    for (zip_int64_t n; (n = zip_fread(file, buffer, sizeof buffer)) > 0;) stream.write(buffer, n);
    zip_fclose(file);
  }
  zip_close(zip);
  return true;
}

// xmllint's verdict on `xml_file` against the FMI 2.0 or 3.0 schema: exit code 0 when valid.
inline CliResult ValidateAgainstSchema(const std::string& xml_file, int fmi_version) {
  const std::string schema = std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/data/fmi/" +
                             (fmi_version == 3 ? "fmi3/fmi3ModelDescription.xsd" : "fmi2/fmi2ModelDescription.xsd");
  return RunCapturing("xmllint --noout --schema " + ShellQuoted(schema) + " " + ShellQuoted(xml_file));
}

}  // namespace shapebench::bench::testing
