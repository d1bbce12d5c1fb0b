#include "bench/config/input_path.h"

#include <filesystem>

namespace shapebench::bench {

std::string ResolvedFrom(const std::string& file, const std::string& reference) {
  namespace fs = std::filesystem;
  if (fs::path(reference).is_absolute()) return reference;
  return (fs::path(file).parent_path() / reference).lexically_normal().string();
}

std::string ResolvedInputPath(const NodeReader& node) {
  return ResolvedFrom(node.document().FileOf(node.path()), node.AsString());
}

bool IsPathKey(const std::string& key_path) {
  if (key_path == "machine") return true;
  const std::size_t dot = key_path.rfind('.');
  const std::string last = dot == std::string::npos ? key_path : key_path.substr(dot + 1);
  return last == "program_file" || last == "modal_file" || last == "frf_file" || last == "fmu";
}

}  // namespace shapebench::bench
