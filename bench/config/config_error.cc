#include "bench/config/config_error.h"

#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

std::string Format(const std::string& file, int line, int column,
                   const std::string& key_path, const std::string& message) {
  std::string text = file;
  if (line > 0) text += ":" + std::to_string(line) + ":" + std::to_string(column);
  text += ": ";
  if (!key_path.empty()) text += ClippedForMessage(key_path) + ": ";  // a 10 MB key
  text += message;
  // what() is a C string: a NUL quoted from a file would cut the message there (the rest
  // of the field, what is allowed). Shown as \x00, as TerminalSafe shows other controls.
  for (std::size_t at = text.find('\0'); at != std::string::npos; at = text.find('\0', at + 4)) {
    text.replace(at, 1, "\\x00");
  }
  return text;
}

}  // namespace

ConfigError::ConfigError(std::string file, int line, int column, std::string key_path,
                         std::string message)
    : std::runtime_error(Format(file, line, column, key_path, message)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      key_path_(std::move(key_path)),
      message_(std::move(message)) {}

}  // namespace shapebench::bench
