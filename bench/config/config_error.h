// A configuration error located in the input: a YAML file position or a --set option.
// what() is "FILE:LINE:COL: key.path: message"; the CLI prints
// "error: " + what() and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace shapebench::bench {

class ConfigError : public std::runtime_error {
 public:
  // line/column are 1-based; 0 means "no position" (e.g. a file that cannot be opened),
  // and the position is then left out of what().
  ConfigError(std::string file, int line, int column, std::string key_path,
              std::string message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& key_path() const { return key_path_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string key_path_;
  std::string message_;
};

}  // namespace shapebench::bench
