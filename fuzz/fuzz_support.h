// Shared by the libFuzzer targets (fuzz/README.md): the input as a file (the loaders
// read files, resolve paths against them and report FILE:LINE:COL), and what counts as
// an acceptable outcome. A target returns normally when the input is accepted or refused
// with the error type the loader documents; anything else (another exception, a crash,
// a sanitizer report, a hang) is a finding.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace shapebench::fuzz {

// A scratch directory per process (libFuzzer runs inputs one after another in one
// process), removed at exit. Files the targets write there are overwritten per input.
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "shapebench_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(ScratchDir(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

// Writes the bytes to the file `path` (replacing it).
inline void WriteBytes(const std::string& path, const std::string& bytes) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) std::abort();
  std::fclose(file);
}

// Writes the bytes to `name` in the scratch directory and returns its path.
inline std::string WriteInput(const std::string& name, const std::string& bytes) {
  const std::string path = (ScratchDir() / name).string();
  WriteBytes(path, bytes);
  return path;
}

// The corpus inputs are small YAML and G-code files; much larger inputs only slow the
// search down (the CLI reads whatever size it is given).
constexpr std::size_t kMaxInput = 64 * 1024;

}  // namespace shapebench::fuzz

namespace shapebench::fuzz {

// The scratch directory laid out like configs/: machines/, programs/, scenarios/ (copies
// of the shipped files), so that a seed's `machine: ../machines/moving_column.yaml`,
// `program_file:` and a sweep's `base: ../scenarios/...` resolve as in the repository.
inline const std::filesystem::path& ConfigsCopy() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path source = std::filesystem::path(SHAPEBENCH_SOURCE_DIR) / "configs";
    for (const char* sub : {"machines", "programs", "scenarios"}) {
      std::filesystem::copy(source / sub, ScratchDir() / sub,
                            std::filesystem::copy_options::recursive |
                                std::filesystem::copy_options::overwrite_existing);
    }
    std::filesystem::copy_file(source / "demo.yaml", ScratchDir() / "demo.yaml",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::create_directories(ScratchDir() / "sweeps");
    return ScratchDir();
  }();
  return dir;
}

}  // namespace shapebench::fuzz
