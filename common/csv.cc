#include "common/csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace shapebench {

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string CsvRecord(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += CsvField(fields[i]);
  }
  return line + "\n";
}

bool CsvReader::Next(CsvFields* fields) {
  std::string& text = fields->text_;
  std::vector<std::size_t>& ends = fields->ends_;
  text.clear();
  ends.clear();
  bool quoted = false;       // inside a quoted field
  bool any = false;          // anything read for this record
  std::uint64_t consumed = 0;
  std::streambuf* buffer = in_->rdbuf();
  while (true) {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      torn_ = any;
      in_->setstate(std::ios::eofbit);
      return false;
    }
    ++consumed;
    any = true;
    if (quoted) {
      if (c == '"') {
        if (buffer->sgetc() == '"') {
          buffer->sbumpc();
          ++consumed;
          text += '"';
        } else {
          quoted = false;
        }
      } else {
        text += static_cast<char>(c);
      }
      continue;
    }
    if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      ends.push_back(text.size());
    } else if (c == '\n') {
      ends.push_back(text.size());
      offset_ += consumed;
      return true;
    } else if (c != '\r') {
      text += static_cast<char>(c);
    }
  }
}

bool CsvReader::Next(std::vector<std::string>* fields) {
  fields->clear();
  if (!Next(&scratch_)) return false;
  for (std::size_t i = 0; i < scratch_.size(); ++i) fields->emplace_back(scratch_[i]);
  return true;
}

std::string ShortestDouble(double value) {
  if (std::isnan(value)) return "";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[40];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  // Whole digits are written out ("10", not "1e+01") up to 17 of them.
  const double magnitude = std::abs(value);
  const int whole = magnitude >= 1.0 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
  if (whole > digits && whole <= 17) digits = whole;
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string ExactDouble(double value) {
  if (std::isnan(value)) return "";
  char text[40];
  return std::string(text, AppendExactDouble(text, text + sizeof text, value));
}

char* AppendExactDouble(char* first, char* last, double value) {
  // std::to_chars without a format: the shortest text that reads back as exactly `value`.
  const std::to_chars_result written = std::to_chars(first, last, value);
  return written.ec == std::errc() ? written.ptr : first;
}

}  // namespace shapebench
