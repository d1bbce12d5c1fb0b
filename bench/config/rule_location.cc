#include "bench/config/rule_location.h"

#include <vector>

#include "bench/config/key_path.h"

namespace shapebench::bench {
namespace {

// Whether the document holds a value at `path` (a key never written is at its default).
bool Written(const ConfigDocument& document, const std::string& path) {
  YAML::Node node;
  node.reset(document.root());
  for (const PathElement& element : SplitKeyPath(path)) {
    const YAML::Node& parent = node;
    YAML::Node child;
    if (element.index) {
      if (!parent.IsSequence() || *element.index >= parent.size()) return false;
      child.reset(parent[static_cast<int>(*element.index)]);
    } else {
      if (!parent.IsMap()) return false;
      bool found = false;
      for (const auto& entry : parent) {
        if (entry.first.IsScalar() && entry.first.Scalar() == element.key) {
          child.reset(entry.second);
          found = true;
          break;
        }
      }
      if (!found) return false;
    }
    node.reset(child);
  }
  return true;
}

}  // namespace

std::string OverrideMention(int index) { return std::string(kOverrideSource) + ":" + std::to_string(index); }

ConfigError LocateRuleError(const ConfigDocument& document, const KeyRuleError& error) {
  const std::vector<RuleKey>& keys = error.keys();
  std::vector<bool> written(keys.size());
  std::vector<int> set_by(keys.size(), 0);
  for (std::size_t j = 0; j < keys.size(); ++j) {
    written[j] = Written(document, keys[j].field);
    if (written[j]) set_by[j] = document.OriginOf(keys[j].field).override_index;
  }
  std::size_t blamed = 0;
  bool found = false;
  for (std::size_t j = 0; j < keys.size(); ++j) {  // the last --set
    if (set_by[j] > 0 && (!found || set_by[j] > set_by[blamed])) {
      blamed = j;
      found = true;
    }
  }
  for (std::size_t j = 0; j < keys.size() && !found; ++j) {  // else the first written
    if (written[j]) {
      blamed = j;
      found = true;
    }
  }
  const auto where = [&](std::size_t j) -> std::string {
    if (!written[j]) return "not written, so its default";
    if (set_by[j] > 0) return OverrideMention(set_by[j]);
    const ConfigError at = document.ErrorAtPath(keys[j].field, "");
    return at.file() + ":" + std::to_string(at.line()) + ":" + std::to_string(at.column());
  };
  return document.ErrorAtPath(keys[blamed].field, error.MessageFor(blamed, where));
}

}  // namespace shapebench::bench
