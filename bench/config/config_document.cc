#include "bench/config/config_document.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "common/shown_text.h"
#include "bench/config/key_path.h"

namespace shapebench::bench {
namespace {

std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return "a scalar";
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Map: return "a mapping";
    default: return "empty";
  }
}

std::string ElementCount(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " element" : " elements");
}

}  // namespace

bool ReadInputFile(const std::string& path, std::string* text, std::string* error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    *error = std::string("cannot open file: ") +
             (ec ? ec.message() : std::string(std::strerror(ENOENT)));
    return false;
  }
  if (fs::is_directory(status)) {
    *error = "cannot read file: it is a directory";
    return false;
  }
  if (!fs::is_regular_file(status)) {
    *error = "cannot read file: not a regular file (a device, FIFO or socket)";
    return false;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxInputFileBytes) {
    *error = "cannot read file: " + std::to_string(size) + " bytes, more than the " +
             std::to_string(kMaxInputFileBytes >> 20) + " MiB an input file may have";
    return false;
  }
  // read(2) itself, so that a failure keeps its errno (an ifstream would read it as the end).
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    *error = std::string("cannot open file: ") + std::strerror(errno);
    return false;
  }
  std::string bytes;
  char buffer[65536];
  for (;;) {
    const ssize_t size = read(fd, buffer, sizeof buffer);
    if (size < 0 && errno == EINTR) continue;
    if (size < 0) {
      *error = std::string("cannot read file: ") + std::strerror(errno);
      close(fd);
      return false;
    }
    if (size == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(size));
    if (bytes.size() > kMaxInputFileBytes) {  // it grew since it was measured
      *error = "cannot read file: more than the " + std::to_string(kMaxInputFileBytes >> 20) +
               " MiB an input file may have";
      close(fd);
      return false;
    }
  }
  close(fd);
  *text = std::move(bytes);
  return true;
}

namespace {

struct ParsedFile {
  std::string path;
  std::string text;
  YAML::Node tree;  // a copy no one else holds
};

thread_local int parse_cache_scopes = 0;
thread_local std::vector<ParsedFile> parse_cache;  // most recently used first

// A key path with [INDEX] written unquoted inside a flow ({...} or [...]) ends the flow at
// its '[': yaml-cpp then says "end of map flow not found". The path it finds near `line`
// (0-based) of `text`, quoted, and how to write it; "" when there is none.
std::string FlowHint(const std::string& message, const std::string& text, int line) {
  if (message.find("flow") == std::string::npos) return "";
  std::vector<std::string> lines(1);
  for (const char c : text) {
    if (c == '\n') {
      lines.emplace_back();
    } else {
      lines.back() += c;
    }
  }
  const auto is_key = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.'; };
  for (int l = std::min(line, static_cast<int>(lines.size()) - 1); l >= 0 && l >= line - 20; --l) {
    const std::string& row = lines[static_cast<std::size_t>(l)];
    for (std::size_t open = row.find('['); open != std::string::npos; open = row.find('[', open + 1)) {
      std::size_t begin = open;
      while (begin > 0 && is_key(row[begin - 1])) --begin;
      std::size_t close = open + 1;
      while (close < row.size() && std::isdigit(static_cast<unsigned char>(row[close])) != 0) ++close;
      if (begin == open || close == open + 1 || close >= row.size() || row[close] != ']') continue;
      if (begin > 0 && (row[begin - 1] == '"' || row[begin - 1] == '\'')) continue;
      std::size_t end = close + 1;
      while (end < row.size() && (is_key(row[end]) || row[end] == '[' || row[end] == ']')) ++end;
      const std::string path = ClippedForMessage(row.substr(begin, end - begin));
      return "; a key path with [INDEX] inside { } or [ ] must be quoted: write \"" + path + "\" (or use the "
             "block form, one key a line)";
    }
  }
  return "";
}

}  // namespace

ParseCacheScope::ParseCacheScope() { ++parse_cache_scopes; }
ParseCacheScope::~ParseCacheScope() { --parse_cache_scopes; }

YAML::Node ConfigDocument::ParseFile(const std::string& path) {
  std::string text;
  std::string error;
  if (!ReadInputFile(path, &text, &error)) throw ConfigError(path, 0, 0, "", error);
  const bool cached = parse_cache_scopes > 0;
  if (cached) {
    for (std::size_t i = 0; i < parse_cache.size(); ++i) {
      if (parse_cache[i].path == path && parse_cache[i].text == text) {
        std::rotate(parse_cache.begin(), parse_cache.begin() + static_cast<std::ptrdiff_t>(i),
                    parse_cache.begin() + static_cast<std::ptrdiff_t>(i) + 1);
        return YAML::Clone(parse_cache.front().tree);
      }
    }
  }
  try {
    YAML::Node tree = YAML::Load(text);
    if (cached) {
      constexpr std::size_t kKept = 8;
      if (parse_cache.size() == kKept) parse_cache.pop_back();
      parse_cache.insert(parse_cache.begin(), ParsedFile{path, std::move(text), YAML::Clone(tree)});
    }
    return tree;
  } catch (const YAML::ParserException& e) {
    throw ConfigError(path, e.mark.line + 1, e.mark.column + 1, "",
                      "malformed YAML: " + e.msg + FlowHint(e.msg, text, e.mark.line));
  }
}

ConfigDocument::ConfigDocument(YAML::Node root, std::string file) : root_(std::move(root)) {
  origins_.push_back({"", Origin{std::move(file), 0}});
}

void ConfigDocument::SetOrigin(const std::string& path, Origin origin) {
  // Whatever came from elsewhere below `path` has just been replaced.
  std::vector<std::pair<std::string, Origin>> kept;
  for (auto& entry : origins_) {
    if (!entry.first.empty() && IsPathPrefix(path, entry.first)) continue;
    kept.push_back(std::move(entry));
  }
  kept.push_back({path, std::move(origin)});
  origins_ = std::move(kept);
}

void ConfigDocument::SpliceTopLevel(const std::string& key, const YAML::Node& content,
                                    const std::string& file) {
  root_[key] = content;
  SetOrigin(key, Origin{file, 0});
}

void ConfigDocument::ApplyOverride(const Override& override_value, int index) {
  const std::string& key_path = override_value.key_path;
  auto fail = [&](const std::string& message) {
    return ConfigError(kOverrideSource, index, 1, key_path, message);
  };
  const auto elements = ParseKeyPath(key_path);
  if (!elements) throw fail("not a key path");
  YAML::Node value;
  try {
    value = YAML::Load(override_value.value_yaml);
  } catch (const YAML::ParserException& e) {
    throw fail("malformed YAML value '" + ClippedForMessage(override_value.value_yaml) + "': " + e.msg +
               FlowHint(e.msg, override_value.value_yaml, e.mark.line));
  }

  if (!root_.IsMap()) {
    if (!root_.IsNull()) throw fail("the top level is " + Describe(root_) + ", not a mapping");
    root_ = YAML::Node(YAML::NodeType::Map);
  }
  // Node handles alias the tree: reset() moves a handle, operator= would overwrite data.
  YAML::Node current;
  current.reset(root_);
  std::string path;
  bool created = false;  // `current` is a mapping this override just created
  // The shallowest key it created: all below is the override's, so an error about that key
  // (unknown, misspelt) is located at the option, not in the file.
  std::string created_path;
  for (std::size_t i = 0; i < elements->size(); ++i) {
    const PathElement& element = (*elements)[i];
    const bool last = i + 1 == elements->size();
    if (element.index) {
      if (created) {
        throw fail("cannot index '" + path + "': it does not exist; set the whole sequence, e.g. " +
                   path + "=[...]");
      }
      if (!current.IsSequence()) {
        throw fail("cannot index '" + path + "': it is " + Describe(current) +
                   ", not a sequence");
      }
      if (*element.index >= current.size()) {
        throw fail("index " + std::to_string(*element.index) + " is out of range: '" + path +
                   "' has " + ElementCount(current.size()));
      }
      const int position = static_cast<int>(*element.index);
      if (last) {
        current[position] = value;
        break;
      }
      YAML::Node child = current[position];
      current.reset(child);
      path = IndexPath(path, *element.index);
      continue;
    }
    if (current.IsNull()) current = YAML::Node(YAML::NodeType::Map);  // "key:" left empty
    if (!current.IsMap()) {
      throw fail("cannot set key '" + ClippedForMessage(element.key) + "' in '" + ClippedForMessage(path) +
                 "': it is " +
                 Describe(current) + ", not a mapping");
    }
    if (last) {
      current[element.key] = value;
      break;
    }
    const bool creates = !current[element.key].IsDefined();
    if (creates && !created) created_path = ChildPath(path, element.key);
    created = creates;
    if (created) current[element.key] = YAML::Node(YAML::NodeType::Map);
    YAML::Node child = current[element.key];
    current.reset(child);
    path = ChildPath(path, element.key);
  }
  SetOrigin(created_path.empty() ? key_path : created_path, Origin{"", index});
}

Origin ConfigDocument::OriginOf(const std::string& path) const {
  const std::pair<std::string, Origin>* best = &origins_.front();
  for (const auto& entry : origins_) {
    if (IsPathPrefix(entry.first, path) && entry.first.size() >= best->first.size()) {
      best = &entry;
    }
  }
  return best->second;
}

std::string ConfigDocument::FileOf(const std::string& path) const {
  const Origin origin = OriginOf(path);
  return origin.override_index > 0 ? std::string() : origin.file;
}

ConfigError ConfigDocument::ErrorAt(const YAML::Node& node, const std::string& path,
                                    const std::string& message) const {
  const Origin origin = OriginOf(path);
  if (origin.override_index > 0) {
    return ConfigError(kOverrideSource, origin.override_index, 1, path, message);
  }
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return ConfigError(origin.file, 1, 1, path, message);
  return ConfigError(origin.file, mark.line + 1, mark.column + 1, path, message);
}

ConfigError ConfigDocument::ErrorAtPath(const std::string& path,
                                        const std::string& message) const {
  YAML::Node node;
  node.reset(root_);
  std::string reached;
  for (const PathElement& element : SplitKeyPath(path)) {
    YAML::Node child;
    bool found = false;
    std::string child_path;
    if (element.index) {
      if (!node.IsSequence() || *element.index >= node.size()) break;
      const YAML::Node& parent = node;
      child.reset(parent[static_cast<int>(*element.index)]);
      found = true;
      child_path = IndexPath(reached, *element.index);
    } else {
      if (!node.IsMap()) break;
      for (const auto& entry : node) {
        if (entry.first.IsScalar() && entry.first.Scalar() == element.key) {
          child.reset(entry.second);
          found = true;
          break;
        }
      }
      child_path = ChildPath(reached, element.key);
    }
    if (!found) break;
    node.reset(child);
    reached = child_path;
  }
  // Locate at the node reached, but keep the full path in the message. The origin is
  // the reached node's: a default that was never written sits in its parent's source.
  ConfigError located = ErrorAt(node, reached, message);
  return ConfigError(located.file(), located.line(), located.column(), path, message);
}

}  // namespace shapebench::bench
