// The YAML tree a run is read from, merged from several sources (the scenario file, a
// referenced machine file, --set options), remembering where each subtree came from so
// that any key path can be reported as FILE:LINE:COL or --set:N:1.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bench/config/config_error.h"
#include "bench/config/override.h"

namespace shapebench::bench {

// A source of YAML: a file (its marks are positions in it) or the N-th --set option.
struct Origin {
  std::string file;
  int override_index = 0;  // > 0: the N-th --set; `file` is then unused
};

// Input files (scenarios, machine files, sweeps, G-code) must be regular files of at
// most this many bytes: a path to /dev/zero, a FIFO or a terminal would otherwise block
// or fill the memory.
inline constexpr std::uintmax_t kMaxInputFileBytes = 64u << 20;

// Reads a whole input file into *text. False with *error ("cannot open file: ...", "it is
// a directory", "not a regular file", "larger than 64 MiB") when it cannot.
bool ReadInputFile(const std::string& path, std::string* text, std::string* error);

// While one is alive on a thread, ConfigDocument::ParseFile keeps what it parses there
// (the last few files, keyed by path and bytes: never stale) and hands out copies. Copies
// carry no source positions (yaml-cpp's Clone drops the marks): a loader that fails inside
// a scope must load again outside one to locate its error. For the points of a sweep, which
// read the same base scenario (and machine file) thousands of times (RunPoint).
class ParseCacheScope {
 public:
  ParseCacheScope();
  ~ParseCacheScope();
  ParseCacheScope(const ParseCacheScope&) = delete;
  ParseCacheScope& operator=(const ParseCacheScope&) = delete;
};

class ConfigDocument {
 public:
  // Reads and parses a file. A missing file or malformed YAML throws ConfigError
  // (the latter at yaml-cpp's mark). Within a ParseCacheScope: see there.
  static YAML::Node ParseFile(const std::string& path);

  ConfigDocument(YAML::Node root, std::string file);

  const YAML::Node& root() const { return root_; }

  // Replaces the value of the top-level key `key` by `content`, parsed from `file`.
  void SpliceTopLevel(const std::string& key, const YAML::Node& content,
                      const std::string& file);

  // Applies the index-th --set: missing mapping keys are created, out-of-range indices
  // and paths through scalars are errors located at --set:index:1.
  void ApplyOverride(const Override& override_value, int index);

  // An error at `node`, which sits at `path`.
  ConfigError ErrorAt(const YAML::Node& node, const std::string& path,
                      const std::string& message) const;
  // An error about `path`, located at its node or, if absent, its nearest existing parent.
  ConfigError ErrorAtPath(const std::string& path, const std::string& message) const;

  Origin OriginOf(const std::string& path) const;
  // The file the value at `path` was read from (a relative path it names is relative to
  // that file's folder), or "" for a value a --set gave (a path given on the command line
  // is relative to the current directory: bench/config/input_path.h).
  std::string FileOf(const std::string& path) const;

 private:
  void SetOrigin(const std::string& path, Origin origin);

  YAML::Node root_;
  // (subtree path, origin); the longest matching prefix wins.
  std::vector<std::pair<std::string, Origin>> origins_;
};

}  // namespace shapebench::bench
