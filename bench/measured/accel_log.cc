// The accelerometer log reader (see the header for the format).
#include "bench/measured/accel_log.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/config/config_document.h"
#include "bench/config/config_error.h"
#include "common/format.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

constexpr char kHeader[] = "#time,accel_x,accel_y,accel_z";

// One field of a line: its text without surrounding blanks, and where it starts (1-based).
struct LogField {
  std::string text;
  int column = 1;
};

std::vector<LogField> SplitFields(const std::string& line, std::size_t from) {
  std::vector<LogField> fields;
  std::size_t start = from;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string::npos ? line.size() : comma;
    std::size_t first = start;
    std::size_t last = end;
    while (first < last && (line[first] == ' ' || line[first] == '\t')) ++first;
    while (last > first && (line[last - 1] == ' ' || line[last - 1] == '\t')) --last;
    fields.push_back({line.substr(first, last - first), static_cast<int>(first) + 1});
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

// The column each header field names: 0 time, 1..3 accel_x..z.
std::vector<int> ReadHeader(const std::string& line, int line_number, const std::string& file) {
  auto fail = [&](int column, const std::string& message) {
    return ConfigError(file, line_number, column, "header", message);
  };
  if (line.empty() || line[0] != '#') {
    throw fail(1, "expected the header " + std::string(kHeader) +
                      " (a line starting with '#', as Klipper's raw_data CSV has) before the samples");
  }
  std::vector<int> columns;
  for (const LogField& field : SplitFields(line, 1)) {
    int which = -1;
    if (field.text == "time") which = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (field.text == kAccelColumns[axis]) which = axis + 1;
    }
    if (which < 0) {
      throw fail(field.column, "unknown column '" + ClippedForMessage(field.text) +
                                   "'; expected time, accel_x, accel_y and accel_z (" + kHeader + ")");
    }
    for (const int seen : columns) {
      if (seen == which) throw fail(field.column, "column '" + field.text + "' named twice");
    }
    columns.push_back(which);
  }
  for (int which = 0; which < 4; ++which) {
    bool found = false;
    for (const int seen : columns) found = found || seen == which;
    if (!found) {
      throw fail(1, std::string("missing column '") + (which == 0 ? "time" : kAccelColumns[which - 1]) +
                        "'; expected " + kHeader + " (time in s, accelerations in mm/s^2)");
    }
  }
  return columns;
}

std::string ColumnName(int which) { return which == 0 ? "time" : kAccelColumns[which - 1]; }

double ReadNumber(const LogField& field, int which, int line_number, const std::string& file) {
  const std::string unit = which == 0 ? "s" : "mm/s^2";
  double value = 0.0;
  const char* first = field.text.data();
  const char* last = first + field.text.size();
  // from_chars takes no '+' of its own ("+-1" stays an error).
  if (last - first > 1 && *first == '+' && first[1] != '-' && first[1] != '+') ++first;
  const auto [end, error] = std::from_chars(first, last, value);
  if (field.text.empty() || error == std::errc::invalid_argument || end != last) {
    throw ConfigError(file, line_number, field.column, ColumnName(which),
                      "not a number: '" + ClippedForMessage(field.text) + "'; expected a decimal number (" +
                          unit + ")");
  }
  if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
    throw ConfigError(file, line_number, field.column, ColumnName(which),
                      "not finite: '" + ClippedForMessage(field.text) + "'; expected a finite number (" + unit +
                          ")");
  }
  return value;
}

}  // namespace

AccelLog ParseAccelLog(const std::string& text, const std::string& file) {
  AccelLog log;
  log.file = file;
  std::vector<int> columns;  // empty until the header is read
  int line_number = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    const std::size_t newline = text.find('\n', position);
    std::string line = text.substr(position, newline == std::string::npos ? std::string::npos : newline - position);
    position = newline == std::string::npos ? text.size() : newline + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (columns.empty()) {
      columns = ReadHeader(line, line_number, file);
      continue;
    }
    if (line[0] == '#') continue;  // a comment
    const std::vector<LogField> fields = SplitFields(line, 0);
    if (fields.size() != columns.size()) {
      const bool short_line = fields.size() < columns.size();
      const int column = short_line ? static_cast<int>(line.size()) + 1 : fields[columns.size()].column;
      throw ConfigError(file, line_number, column,
                        short_line ? ColumnName(columns[fields.size()]) : "header",
                        "expected " + std::to_string(columns.size()) + " fields as the header has (" +
                            kHeader + "), got " + std::to_string(fields.size()));
    }
    double values[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < fields.size(); ++i) {
      values[columns[i]] = ReadNumber(fields[i], columns[i], line_number, file);
    }
    int time_column = 1;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (columns[i] == 0) time_column = fields[i].column;
    }
    if (!log.time_s.empty() && !(values[0] > log.time_s.back())) {
      throw ConfigError(file, line_number, time_column, "time",
                        "time " + FormatNumber(values[0]) + " s is not after the previous sample's " +
                            FormatNumber(log.time_s.back()) + " s (line " + std::to_string(log.line.back()) +
                            "); the samples must be in increasing time");
    }
    log.time_s.push_back(values[0]);
    for (int axis = 0; axis < 3; ++axis) log.accel_mm_s2[axis].push_back(values[axis + 1]);
    log.line.push_back(line_number);
    log.last_time_column = time_column;
  }
  if (columns.empty()) {
    throw ConfigError(file, 1, 1, "header",
                      std::string("empty file; expected the header ") + kHeader +
                          " then one sample a line (time in s, accelerations in mm/s^2)");
  }
  if (log.time_s.empty()) {
    throw ConfigError(file, line_number + 1, 1, "time",
                      "no samples after the header; expected one sample a line (time in s, accelerations "
                      "in mm/s^2)");
  }
  return log;
}

// As every input file: a regular file of at most kMaxInputFileBytes (/dev/zero grew to the
// memory cap and a FIFO blocked forever).
AccelLog ReadAccelLog(const std::string& path) {
  std::string text;
  std::string error;
  if (!ReadInputFile(path, &text, &error)) throw ConfigError(path, 0, 0, "", error);
  return ParseAccelLog(text, path);
}

}  // namespace shapebench::bench
