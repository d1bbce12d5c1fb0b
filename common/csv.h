// CSV as RFC 4180 has it: fields with a comma, a quote, CR or LF are quoted, quotes
// doubled; records end with "\n". The reader is the writer's inverse and tells a
// complete record from a torn one (a file cut short while it was being written).
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace shapebench {

// One field, quoted when it has to be.
std::string CsvField(const std::string& text);
// Fields joined by ',' and ended by '\n'.
std::string CsvRecord(const std::vector<std::string>& fields);

// One record's fields, unquoted, back to back in one buffer that the next record read
// into it reuses (no allocation a field: results.mat reads every row of a sweep).
class CsvFields {
 public:
  std::size_t size() const { return ends_.size(); }
  // Field i, or "" past the record's last field.
  std::string_view operator[](std::size_t i) const {
    if (i >= ends_.size()) return {};
    const std::size_t begin = i == 0 ? 0 : ends_[i - 1];
    return std::string_view(text_).substr(begin, ends_[i] - begin);
  }

 private:
  friend class CsvReader;
  std::string text_;
  std::vector<std::size_t> ends_;  // where each field ends in text_
};

// Reads records one by one from a stream.
class CsvReader {
 public:
  explicit CsvReader(std::istream& in) : in_(&in) {}

  // The next record into *fields. False at the end of the stream, or when the stream
  // ends inside a record (no final '\n' outside quotes): `torn()` then says so and the
  // partial record is not returned.
  bool Next(CsvFields* fields);
  bool Next(std::vector<std::string>* fields);
  bool torn() const { return torn_; }
  // Bytes consumed by the complete records read so far.
  std::uint64_t offset() const { return offset_; }

 private:
  std::istream* in_;
  bool torn_ = false;
  std::uint64_t offset_ = 0;
  CsvFields scratch_;  // Next(vector)'s record
};

// Formats a double so that strtod gives it back exactly, in as few digits as possible
// ("15.1", not "15.099999999999999"); NaN -> "", infinities -> "inf"/"-inf".
std::string ShortestDouble(double value);
// The shortest text that reads back as exactly `value` (std::to_chars: "0.726", not
// "0.72599999999999998"; the same text on every run and thread count); NaN -> "",
// infinities "inf"/"-inf". The number format of the CSV files (results.csv, trace.csv).
std::string ExactDouble(double value);
// ExactDouble's text written at `first` (40 chars are always enough); returns its end.
// NaN writes "nan" (callers of the CSV writers decide what NaN is).
char* AppendExactDouble(char* first, char* last, double value);

}  // namespace shapebench
