// Dotted key paths into a YAML tree, as used by --set, error messages and
// ValidationError::field(): "machine.modes[0].frequency_hz".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace shapebench::bench {

// One step of a path: a mapping key, or (when `index` is set) a sequence index.
struct PathElement {
  std::string key;
  std::optional<std::size_t> index;
};

// Strict parse for user input (--set): keys are [A-Za-z0-9_-]+ or any text but '"' in
// double quotes (taken as written: "a.b[0]" is one key), indices [digits].
// Returns nullopt when the text is not such a path.
std::optional<std::vector<PathElement>> ParseKeyPath(const std::string& path);

// Lenient parse for paths produced by code (ValidationError fields): never fails;
// whatever cannot be read as an index is kept as a key.
std::vector<PathElement> SplitKeyPath(const std::string& path);

std::string ChildPath(const std::string& parent, const std::string& key);
std::string IndexPath(const std::string& parent, std::size_t index);

// True when `path` is `prefix` or lies below it ("a.b" is below "a", "a[0]" below "a",
// "ab" is not below "a"). The empty prefix is the root, above everything.
bool IsPathPrefix(const std::string& prefix, const std::string& path);

}  // namespace shapebench::bench
