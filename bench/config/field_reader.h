// Reads a config struct from YAML through its field list (common/field_list.h): the keys
// allowed are the field list's, each read by its type; a list of structs reads each entry
// the same way, bounded by the list's maximum length.
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "bench/config/node_reader.h"
#include "common/field_list.h"
#include "controller/pattern_config.h"

namespace shapebench::bench {

// The pattern's own reader (controller_reader.cc): its keys depend on each other.
void ReadSection(const NodeReader& node, controller::PatternConfig* config);

class FieldReader {
 public:
  explicit FieldReader(const NodeReader& node) : node_(node) {}

  // A number, an integer or a string; any other type is a section (a nested mapping)
  // read by ReadSection.
  template <typename T>
  void Visit(const char* name, T* field) {
    if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
      node_.Read(name, field);
    } else if (auto section = node_.Child(name)) {
      ReadSection(*section, field);
    }
  }
  template <typename E>
  void Visit(const char* name, E* field, const Choices<E>& choices) {
    node_.Read<E>(name, choices, field);
  }
  void Visit(const char* name, std::vector<double>* numbers) {
    if (auto list = node_.Child(name)) {
      numbers->clear();
      for (const NodeReader& n : list->Elements()) numbers->push_back(n.AsNumber());
    }
  }
  template <typename T>
  void Visit(const char* name, std::vector<T>* entries, std::size_t max_entries);

 private:
  const NodeReader& node_;
};

// A section reads through its field list unless an overload says otherwise (the pattern:
// bench/scenario/controller_reader.h).
template <typename Config>
void ReadSection(const NodeReader& node, Config* config);
// An optional section (a mode's `participation:`): set when its key is given.
template <typename Config>
void ReadSection(const NodeReader& node, std::optional<Config>* config);

// Reads every key of `config`'s field list present in `node`, which may hold only those
// and `extra_keys` (read by the caller).
template <typename Config>
void ReadFields(const NodeReader& node, Config* config, const std::vector<std::string>& extra_keys = {}) {
  std::vector<std::string> allowed = FieldNames<Config>();
  allowed.insert(allowed.end(), extra_keys.begin(), extra_keys.end());
  node.ExpectMap(allowed);
  FieldReader reader(node);
  config->Serialize(&reader);
}

template <typename Config>
void ReadSection(const NodeReader& node, Config* config) {
  ReadFields(node, config);
}

template <typename Config>
void ReadSection(const NodeReader& node, std::optional<Config>* config) {
  config->emplace();
  ReadFields(node, &**config);
}

template <typename T>
void FieldReader::Visit(const char* name, std::vector<T>* entries, std::size_t max_entries) {
  const auto list = node_.Child(name);
  if (!list) return;
  if (list->node().IsSequence() && list->node().size() > max_entries) {
    throw list->Error("at most " + std::to_string(max_entries) + " " + name + " per axis (got " +
                      std::to_string(list->node().size()) + ")");
  }
  entries->clear();
  for (const NodeReader& entry : list->Elements()) {
    T value;
    ReadFields(entry, &value);
    entries->push_back(value);
  }
}

}  // namespace shapebench::bench
