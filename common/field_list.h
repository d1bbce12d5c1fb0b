// Field lists: each config struct names its keys once, in the spirit of Drake's
// Serialize(Archive*):
//
//   template <typename Archive>
//   void Serialize(Archive* a) {
//     a->Visit("frequency_hz", &frequency_hz);
//     a->Visit("type", &type, TypeChoices());       // an enum and its YAML names
//     a->Visit("modes", &modes, kMaxModes);         // a list of structs with Serialize
//   }
//
// Archives walk it: the YAML reader (bench/config/field_reader.h) reads the keys and
// allows exactly them; --set and the sweep's fast path find a number by name
// (NumberField); messages name a field from its member (FieldName). A key's name is
// written in the field list and nowhere else.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace shapebench {

// YAML names of an enum's values.
template <typename E>
using Choices = std::vector<std::pair<std::string, E>>;

namespace field_list_detail {

// Collects the names of the visited fields.
struct NameCollector {
  std::vector<std::string> names;
  template <typename T, typename... Rest>
  void Visit(const char* name, T*, const Rest&...) {
    names.emplace_back(name);
  }
};

// Finds the name of the field at `address`.
struct NameFinder {
  const void* address = nullptr;
  std::string name;
  template <typename T, typename... Rest>
  void Visit(const char* field_name, T* field, const Rest&...) {
    if (static_cast<const void*>(field) == address) name = field_name;
  }
};

// Finds the double field named `name`.
struct NumberFinder {
  std::string name;
  double* field = nullptr;
  void Visit(const char* field_name, double* number) {
    if (name == field_name) field = number;
  }
  template <typename T, typename... Rest>
  void Visit(const char*, T*, const Rest&...) {}
};

// Collects the names of the visited lists of structs.
struct ListCollector {
  std::vector<std::string> names;
  template <typename T>
  void Visit(const char* name, std::vector<T>*, std::size_t) {
    names.emplace_back(name);
  }
  template <typename T, typename... Rest>
  void Visit(const char*, T*, const Rest&...) {}
};

// Finds element `index` of the list named `list` and, in it, the double field `name`.
struct ListNumberFinder {
  std::string list;
  std::size_t index = 0;
  std::string name;
  double* field = nullptr;
  template <typename T>
  void Visit(const char* list_name, std::vector<T>* elements, std::size_t) {
    if (list != list_name || index >= elements->size()) return;
    NumberFinder finder{name};
    (*elements)[index].Serialize(&finder);
    field = finder.field;
  }
  template <typename T, typename... Rest>
  void Visit(const char*, T*, const Rest&...) {}
};

// Whether the entries of the list named `list` have a double field `name`.
struct ListFieldChecker {
  std::string list;
  std::string name;
  bool found = false;
  template <typename T>
  void Visit(const char* list_name, std::vector<T>*, std::size_t) {
    if (list != list_name) return;
    T entry;
    NumberFinder finder{name};
    entry.Serialize(&finder);
    found = finder.field != nullptr;
  }
  template <typename T, typename... Rest>
  void Visit(const char*, T*, const Rest&...) {}
};

}  // namespace field_list_detail

// The keys of `Config`, in its field list's order.
template <typename Config>
std::vector<std::string> FieldNames() {
  Config config;
  field_list_detail::NameCollector collector;
  config.Serialize(&collector);
  return collector.names;
}

// The key of one field: FieldName(&ModalMode::gain) is "gain".
template <typename Config, typename T>
std::string FieldName(T Config::*member) {
  Config config;
  field_list_detail::NameFinder finder{&(config.*member), {}};
  config.Serialize(&finder);
  return finder.name;
}

// The number field `name` of `config`; nullptr when it has none (or it is not a number).
template <typename Config>
double* NumberField(Config* config, const std::string& name) {
  field_list_detail::NumberFinder finder{name};
  config->Serialize(&finder);
  return finder.field;
}

// The names of `Config`'s lists of structs ("modes"; "bodies", "elements").
template <typename Config>
std::vector<std::string> ListNames() {
  Config config;
  field_list_detail::ListCollector collector;
  config.Serialize(&collector);
  return collector.names;
}

// The number field `name` of element `index` of `config`'s list `list`; nullptr when
// there is none.
template <typename Config>
double* ListNumberField(Config* config, const std::string& list, std::size_t index, const std::string& name) {
  field_list_detail::ListNumberFinder finder{list, index, name};
  config->Serialize(&finder);
  return finder.field;
}

// Whether the entries of `Config`'s list `list` have a number field `name`.
template <typename Config>
bool ListHasNumberField(const std::string& list, const std::string& name) {
  Config config;
  field_list_detail::ListFieldChecker checker{list, name};
  config.Serialize(&checker);
  return checker.found;
}

}  // namespace shapebench
