#include "bench/config/key_path.h"

#include <cctype>

namespace shapebench::bench {
namespace {

bool IsKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
}

}  // namespace

std::optional<std::vector<PathElement>> ParseKeyPath(const std::string& path) {
  std::vector<PathElement> elements;
  std::size_t i = 0;
  const std::size_t n = path.size();
  while (true) {
    if (i < n && path[i] == '"') {
      // A quoted key, taken as written: a name with dots or brackets of its own, as an
      // FMU's structured variable names have (machine.fmu_parameters."modes[0].f").
      const std::size_t close = path.find('"', i + 1);
      if (close == std::string::npos || close == i + 1) return std::nullopt;
      elements.push_back({path.substr(i + 1, close - i - 1), std::nullopt});
      i = close + 1;
    } else {
      const std::size_t key_begin = i;
      while (i < n && IsKeyChar(path[i])) ++i;
      if (i == key_begin) return std::nullopt;  // empty key: "", "a..b", ".a", "[0]"
      elements.push_back({path.substr(key_begin, i - key_begin), std::nullopt});
    }
    while (i < n && path[i] == '[') {
      const std::size_t digits_begin = ++i;
      while (i < n && std::isdigit(static_cast<unsigned char>(path[i])) != 0) ++i;
      if (i == digits_begin || i >= n || path[i] != ']' || i - digits_begin > 9) {
        return std::nullopt;
      }
      elements.push_back({"", std::stoul(path.substr(digits_begin, i - digits_begin))});
      ++i;
    }
    if (i == n) return elements;
    if (path[i] != '.') return std::nullopt;
    ++i;
  }
}

std::vector<PathElement> SplitKeyPath(const std::string& path) {
  std::vector<PathElement> elements;
  std::string key;
  auto flush = [&] {
    if (!key.empty()) elements.push_back({key, std::nullopt});
    key.clear();
  };
  for (std::size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (c == '.') {
      flush();
    } else if (c == '[') {
      const std::size_t close = path.find(']', i);
      const std::string inner =
          close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
      const bool numeric = !inner.empty() && inner.size() <= 9 &&
                           inner.find_first_not_of("0123456789") == std::string::npos;
      if (!numeric) {
        key += c;
        continue;
      }
      flush();
      elements.push_back({"", std::stoul(inner)});
      i = close;
    } else {
      key += c;
    }
  }
  flush();
  return elements;
}

std::string ChildPath(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string IndexPath(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

bool IsPathPrefix(const std::string& prefix, const std::string& path) {
  if (prefix.empty()) return true;
  if (path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' ||
         path[prefix.size()] == '[';
}

}  // namespace shapebench::bench
