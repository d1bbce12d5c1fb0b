#include "bench/config/node_reader.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <set>

#include "common/closest_name.h"
#include "common/decimal.h"
#include "common/shown_text.h"
#include "bench/config/key_path.h"

namespace shapebench::bench {
namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

// Skips digits from *i; how many.
std::size_t Digits(const std::string& text, std::size_t* i) {
  const std::size_t start = *i;
  while (*i < text.size() && IsDigit(text[*i])) ++*i;
  return *i - start;
}

// [-+]?\d+, the whole text.
bool IsIntegerText(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  return Digits(text, &i) > 0 && i == text.size();
}

bool IsQuoted(const YAML::Node& node) { return node.Tag() == "!"; }

}  // namespace

// The one decimal grammar of the project (common/decimal.h), also the command line's.
bool IsNumberText(const std::string& text) { return IsDecimalText(text); }

std::string JoinNames(const std::vector<std::string>& names, const std::string& separator) {
  std::string joined;
  for (const auto& name : names) joined += (joined.empty() ? "" : separator) + name;
  return joined;
}

NodeReader::NodeReader(const ConfigDocument& document, YAML::Node node, std::string path)
    : document_(&document), path_(std::move(path)) {
  node_.reset(node);
}

ConfigError NodeReader::Error(const std::string& message) const {
  return document_->ErrorAt(node_, path_, message);
}

std::string NodeReader::Shown() const {
  switch (node_.Type()) {
    case YAML::NodeType::Scalar:
      return IsQuoted(node_) ? "\"" + ClippedForMessage(node_.Scalar()) + "\" (a quoted string)"
                             : "'" + ClippedForMessage(node_.Scalar()) + "'";
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Map: return "a mapping";
    default: return "nothing (empty value)";
  }
}

void NodeReader::ExpectMap(const std::vector<std::string>& allowed) const {
  if (!node_.IsMap()) throw Error("expected a mapping, got " + Shown());
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {
      throw document_->ErrorAt(entry.first, path_, "expected a plain key, got a complex key");
    }
    const std::string key = entry.first.Scalar();
    const std::string key_path = ChildPath(path_, key);
    bool known = false;
    for (const auto& name : allowed) known = known || name == key;
    if (!known) {
      throw document_->ErrorAt(entry.first, key_path,
                               "unknown key '" + ClippedForMessage(key) + "'; allowed: " + JoinNames(allowed, ", ") +
                                   DidYouMean(key, allowed));
    }
    if (!seen.insert(key).second) {
      throw document_->ErrorAt(entry.first, key_path, "duplicate key '" + ClippedForMessage(key) + "'");
    }
  }
}

bool NodeReader::Has(const std::string& key) const { return Child(key).has_value(); }

std::optional<NodeReader> NodeReader::Child(const std::string& key) const {
  if (!node_.IsMap()) return std::nullopt;
  for (const auto& entry : node_) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) {
      return NodeReader(*document_, entry.second, ChildPath(path_, key));
    }
  }
  return std::nullopt;
}

std::vector<std::pair<std::string, NodeReader>> NodeReader::Entries() const {
  if (!node_.IsMap()) throw Error("expected a mapping, got " + Shown());
  std::vector<std::pair<std::string, NodeReader>> entries;
  for (const auto& entry : node_) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
    entries.emplace_back(key, NodeReader(*document_, entry.second, ChildPath(path_, key)));
  }
  return entries;
}

std::vector<NodeReader> NodeReader::Elements() const {
  if (!node_.IsSequence()) throw Error("expected a sequence, got " + Shown());
  std::vector<NodeReader> elements;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    const YAML::Node& sequence = node_;
    elements.emplace_back(*document_, sequence[static_cast<int>(i)], IndexPath(path_, i));
  }
  return elements;
}

double NodeReader::AsNumber() const {
  if (!node_.IsScalar() || IsQuoted(node_) || !IsNumberText(node_.Scalar())) {
    throw Error("expected a number, got " + Shown());
  }
  errno = 0;
  const double value = std::strtod(node_.Scalar().c_str(), nullptr);
  if (errno == ERANGE && std::isinf(value)) throw Error("number out of range: " + Shown());
  return value;
}

long NodeReader::AsInteger() const {
  if (!node_.IsScalar() || IsQuoted(node_) ||
      !IsIntegerText(node_.Scalar())) {
    throw Error("expected an integer, got " + Shown());
  }
  errno = 0;
  const long value = std::strtol(node_.Scalar().c_str(), nullptr, 10);
  if (errno == ERANGE) throw Error("integer out of range: " + Shown());
  return value;
}

std::string NodeReader::AsString() const {
  if (!node_.IsScalar() || node_.Scalar().empty()) {
    throw Error("expected a string, got " + Shown());
  }
  return node_.Scalar();
}

void NodeReader::Read(const std::string& key, double* out) const {
  if (auto child = Child(key)) *out = child->AsNumber();
}

void NodeReader::Read(const std::string& key, long* out) const {
  if (auto child = Child(key)) *out = child->AsInteger();
}

void NodeReader::Read(const std::string& key, int* out) const {
  if (auto child = Child(key)) {
    const long value = child->AsInteger();
    if (value < INT_MIN || value > INT_MAX) throw child->Error("integer out of range");
    *out = static_cast<int>(value);
  }
}

void NodeReader::Read(const std::string& key, std::string* out) const {
  if (auto child = Child(key)) *out = child->AsString();
}

}  // namespace shapebench::bench
