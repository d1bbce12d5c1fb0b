// Every input the fuzz targets found (fuzz/regressions/TARGET/*) goes through the
// target's body again (fuzz/fuzz_targets.h) and is accepted or refused with a located
// error: no exception escapes, no invariant breaks (and, in the sanitized build, no
// sanitizer report).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "fuzz/fuzz_targets.h"

namespace shapebench::fuzz {
namespace {

std::string Bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void Replay(const std::string& target, const std::function<void(const std::string&)>& body) {
  const std::filesystem::path dir = std::filesystem::path(SHAPEBENCH_SOURCE_DIR) / "fuzz/regressions" / target;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    try {
      body(Bytes(file));
    } catch (const Violation& violation) {
      ADD_FAILURE() << violation.what;
    } catch (const std::exception& error) {
      ADD_FAILURE() << "escaped: " << error.what();
    }
  }
}

// Tests that the scenario loader's findings load or fail with a located ConfigError.
TEST(FuzzRegressions, Scenario) { Replay("scenario", ScenarioTarget); }
// Tests that the --set parser's findings load or fail with a located ConfigError.
TEST(FuzzRegressions, Set) { Replay("set", SetTarget); }
// Tests that the sweep loader's findings load or fail with a located ConfigError.
TEST(FuzzRegressions, Sweep) { Replay("sweep", SweepTarget); }
// Tests that the G-code parser's findings parse or fail with a located ProgramError.
TEST(FuzzRegressions, Gcode) { Replay("gcode", GcodeTarget); }
// Tests that the manifest.json readers of resume and merge take the manifest findings or
// refuse them naming the file, and that what they take is what merge needs.
TEST(FuzzRegressions, Manifest) { Replay("manifest", ManifestTarget); }
// Tests that the results rows readers of resume and merge keep the rows findings' good
// rows or refuse them naming the file, and agree with each other.
TEST(FuzzRegressions, Rows) { Replay("rows", RowsTarget); }
// Tests that the UFF 58 reader's findings read or fail with a ConfigError at a line, and
// that what it reads is finite and identifies within its band.
TEST(FuzzRegressions, Uff58) { Replay("uff58", Uff58Target); }
// Tests that the accelerometer log reader's findings are taken, with a finite spectrum
// and fit, or refused with a ConfigError at a line and column.
TEST(FuzzRegressions, AccelLog) { Replay("accel_log", AccelLogTarget); }
// Tests that the FE modal export reader's hostile inputs (empty, no unit row, NaN, inf and
// overflowing numbers, too many modes or fields) parse or fail with a located ConfigError.
TEST(FuzzRegressions, ModalFile) { Replay("modal_file", ModalFileTarget); }

}  // namespace
}  // namespace shapebench::fuzz
