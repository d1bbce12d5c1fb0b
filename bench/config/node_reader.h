// Typed, strict reading of one node of a ConfigDocument: every error names the node's
// key path and its own FILE:LINE:COL (or --set:N:1).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "bench/config/config_document.h"
#include "common/closest_name.h"

namespace shapebench::bench {

// YAML 1.2 core-schema decimal numbers only: no hex, no .inf/.nan, no quoted strings. The
// whole text matches [-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?: what NodeReader reads as a number.
bool IsNumberText(const std::string& text);

// Joins names for "allowed: a, b, c".
std::string JoinNames(const std::vector<std::string>& names, const std::string& separator);

class NodeReader {
 public:
  NodeReader(const ConfigDocument& document, YAML::Node node, std::string path);

  const std::string& path() const { return path_; }
  const ConfigDocument& document() const { return *document_; }
  const YAML::Node& node() const { return node_; }
  bool IsNull() const { return node_.IsNull(); }
  bool IsScalar() const { return node_.IsScalar(); }
  bool IsMap() const { return node_.IsMap(); }

  // Requires a mapping whose keys are all in `allowed` (each at most once).
  void ExpectMap(const std::vector<std::string>& allowed) const;
  bool Has(const std::string& key) const;
  // The value at `key`, or nullopt when the key is absent.
  std::optional<NodeReader> Child(const std::string& key) const;
  // Requires a mapping; its (key, value) entries in document order.
  std::vector<std::pair<std::string, NodeReader>> Entries() const;
  // Requires a sequence; its elements in order.
  std::vector<NodeReader> Elements() const;

  double AsNumber() const;      // a finite plain number: 25, -0.5, 1.0e-8
  long AsInteger() const;       // a plain integer
  std::string AsString() const; // any non-empty scalar
  // One of `choices` (the scalar's text as written, so 1 and "1" are the same);
  // else "expected one of a|b|c".
  template <typename T>
  T AsChoice(const std::vector<std::pair<std::string, T>>& choices) const {
    const std::string text = node_.IsScalar() ? node_.Scalar() : std::string();
    for (const auto& choice : choices) {
      if (node_.IsScalar() && choice.first == text) return choice.second;
    }
    std::vector<std::string> names;
    for (const auto& choice : choices) names.push_back(choice.first);
    throw Error("expected one of " + JoinNames(names, "|") + ", got " + Shown() +
                (node_.IsScalar() ? DidYouMean(text, names) : std::string()));
  }

  // Reads the optional key into *out, leaving the default when the key is absent.
  void Read(const std::string& key, double* out) const;
  void Read(const std::string& key, long* out) const;
  void Read(const std::string& key, int* out) const;
  void Read(const std::string& key, std::string* out) const;
  template <typename T>
  void Read(const std::string& key, const std::vector<std::pair<std::string, T>>& choices,
            T* out) const {
    if (auto child = Child(key)) *out = child->AsChoice(choices);
  }

  ConfigError Error(const std::string& message) const;

 private:
  // How the value looks in a message: 'text' for a scalar, "a mapping", ...
  std::string Shown() const;

  const ConfigDocument* document_;
  YAML::Node node_;
  std::string path_;
};


}  // namespace shapebench::bench
