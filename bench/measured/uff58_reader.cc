// The dataset 58 / 58b reader (bench/measured/uff58_reader.h).
#include "bench/measured/uff58_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/config/config_document.h"
#include "bench/config/config_error.h"
#include "bench/measured/uff58_units.h"
#include "common/decimal.h"
#include "common/math_constants.h"

namespace shapebench::bench {
namespace {

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(" \t");
  return text.substr(begin, end - begin + 1);
}

// Columns [begin, begin + width) of a record, blank past its end.
std::string Columns(const std::string& text, std::size_t begin, std::size_t width) {
  if (begin >= text.size()) return "";
  return text.substr(begin, width);
}

// A shown field: printable ASCII kept, the rest as '?', at most 24 characters.
std::string Shown(const std::string& field) {
  std::string shown;
  for (const char c : field.substr(0, 24)) {
    shown += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  return "'" + shown + "'" + (field.size() > 24 ? "..." : "");
}

bool ParseLong(const std::string& field, long* out) {
  const std::string text = Trim(field);
  if (text.empty() || text.size() > 12) return false;
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  *out = value;
  return true;
}

// A Fortran real: decimal, E or D exponent. False when it is not one; *out may then be NaN
// or inf when the text spells one or overflows (the caller says so). strtod alone would
// also read hexadecimal: "0x10" is no Fortran real.
bool ParseReal(const std::string& field, double* out) {
  std::string text = Trim(field);
  if (text.empty() || text.size() > 40) return false;
  for (char& c : text) {
    if (c == 'd' || c == 'D') c = 'E';
  }
  const std::size_t digits = text.find_first_not_of("+-");
  const bool spelled = digits != std::string::npos && (text[digits] == 'i' || text[digits] == 'I' ||
                                                       text[digits] == 'n' || text[digits] == 'N');
  if (!IsDecimalText(text) && !spelled) return false;
  char* end = nullptr;
  *out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

const char* FunctionTypeName(long type) {
  static const char* const kNames[] = {"general or unknown", "time response", "auto spectrum", "cross spectrum",
                                       "frequency response function", "transmissibility", "coherence",
                                       "auto correlation", "cross correlation", "power spectral density"};
  return type >= 0 && type < 10 ? kNames[type] : "another function";
}

struct DataForm {
  long ordinate_type = 0;  // 2, 4 real; 5, 6 complex (single, double)
  long count = 0;          // values (even) or pairs (uneven)
  bool even = true;
  double min_hz = 0.0;
  double increment_hz = 0.0;
  bool Complex() const { return ordinate_type >= 5; }
  bool Double() const { return ordinate_type == 4 || ordinate_type == 6; }
  // Numbers per point in record 12: the abscissa when uneven, then real (and imaginary).
  int PerPoint() const { return (even ? 0 : 1) + (Complex() ? 2 : 1); }
};

class Parser {
 public:
  Parser(const std::string& bytes, std::string file) : bytes_(bytes), file_(std::move(file)) {}
  Uff58File Parse();

 private:
  bool NextLine(std::string* text);
  [[noreturn]] void Fail(int line, int column, const std::string& record, const std::string& message) const {
    throw ConfigError(file_, line, column, record, message);
  }
  std::string HeaderLine(const std::string& record, int opened);
  long IntField(const std::string& text, std::size_t begin, std::size_t width, const std::string& record,
                const std::string& what);
  void ReadDataset58(const std::string& identifier, Uff58Record* record);
  DataForm ReadDataForm(const std::string& text);
  void ReadAsciiValues(const DataForm& form, std::vector<double>* numbers);
  // Record 12 of a 58b as its identifier line and record 7 announce it.
  struct BinaryLayout {
    bool big = false;              // big endian
    bool single_abscissa = false;  // an uneven abscissa stored single beside double values
    std::size_t expected = 0;      // bytes
  };
  BinaryLayout ReadBinaryLayout(const std::string& identifier, const DataForm& form);
  double ReadBinaryNumber(std::size_t width, bool big);
  void ReadBinaryValues(const std::string& identifier, const DataForm& form, std::vector<double>* numbers);
  void StoreValues(const DataForm& form, const std::vector<double>& numbers, double scale, Uff58Record* record);
  void SkipDataset(long number, int line);
  // A NaN or inf ordinate: listed once per point (the abscissa must be finite).
  void NoteNonFinite(const DataForm& form, std::size_t index, int line, int column, const std::string& text);
  bool ClosedAfter(std::size_t bytes) const;

  const std::string& bytes_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 0;  // the line last read
  std::vector<Uff58NonFinite> non_finite_;  // the current record's
  std::vector<std::string> warnings_;
};

void Parser::NoteNonFinite(const DataForm& form, std::size_t index, int line, int column, const std::string& text) {
  const std::size_t point = index / form.PerPoint();
  if (!form.even && index % form.PerPoint() == 0) {
    Fail(line, column, "record 12", "abscissa value " + Shown(text) + " (point " + std::to_string(point + 1) +
                                        ") is not a finite number; an FRF's frequencies must be");
  }
  if (!non_finite_.empty() && non_finite_.back().point == point) return;
  non_finite_.push_back({point, line, column, text});
}

bool Parser::NextLine(std::string* text) {
  if (pos_ >= bytes_.size()) return false;
  std::size_t end = bytes_.find('\n', pos_);
  if (end == std::string::npos) end = bytes_.size();
  *text = bytes_.substr(pos_, end - pos_);
  if (!text->empty() && text->back() == '\r') text->pop_back();
  pos_ = end + 1;
  ++line_;
  return true;
}

// The next header line of a dataset opened at line `opened`; its end there is an error.
std::string Parser::HeaderLine(const std::string& record, int opened) {
  std::string text;
  if (!NextLine(&text) || Trim(text) == "-1") {
    Fail(line_, 1, record, "missing: the dataset 58 opened at line " + std::to_string(opened) +
                               " ends before it (a dataset 58 has 11 header records, then the values)");
  }
  return text;
}

long Parser::IntField(const std::string& text, std::size_t begin, std::size_t width, const std::string& record,
                      const std::string& what) {
  long value = 0;
  const std::string field = Columns(text, begin, width);
  if (Trim(field).empty()) return 0;  // blank: unused
  if (!ParseLong(field, &value)) {
    Fail(line_, static_cast<int>(begin) + 1, record,
         what + ": expected an integer in columns " + std::to_string(begin + 1) + "-" +
             std::to_string(begin + width) + ", got " + Shown(field));
  }
  return value;
}

// Record 7: Format(3I10,3E13.5), read as six blank-separated numbers.
DataForm Parser::ReadDataForm(const std::string& text) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (tokens.size() < 7) {
    i = text.find_first_not_of(" \t", i);
    if (i == std::string::npos) break;
    const std::size_t end = text.find_first_of(" \t", i);
    tokens.push_back(text.substr(i, end == std::string::npos ? std::string::npos : end - i));
    i = end;
  }
  if (tokens.size() < 5) {
    Fail(line_, 1, "record 7", "expected ordinate data type, number of values, abscissa spacing, abscissa "
                               "minimum and increment (Format(3I10,3E13.5)), got " + Shown(text));
  }
  DataForm form;
  long spacing = -1;
  if (!ParseLong(tokens[0], &form.ordinate_type) ||
      (form.ordinate_type != 2 && form.ordinate_type != 4 && form.ordinate_type != 5 && form.ordinate_type != 6)) {
    Fail(line_, 1, "record 7", "ordinate data type " + Shown(tokens[0]) +
                                   ": expected 2 or 4 (real, single or double) or 5 or 6 (complex)");
  }
  if (!ParseLong(tokens[1], &form.count) || form.count < 1 || form.count > 50000000) {
    Fail(line_, 11, "record 7", "number of values " + Shown(tokens[1]) + ": expected an integer >= 1");
  }
  if (!ParseLong(tokens[2], &spacing) || (spacing != 0 && spacing != 1)) {
    Fail(line_, 21, "record 7", "abscissa spacing " + Shown(tokens[2]) + ": expected 0 (uneven) or 1 (even)");
  }
  form.even = spacing == 1;
  if (!ParseReal(tokens[3], &form.min_hz) || !std::isfinite(form.min_hz) ||
      !ParseReal(tokens[4], &form.increment_hz) || !std::isfinite(form.increment_hz)) {
    Fail(line_, 31, "record 7", "abscissa minimum and increment must be finite numbers, got " +
                                    Shown(tokens[3]) + " and " + Shown(tokens[4]));
  }
  if (form.even && !(form.increment_hz > 0.0)) {
    Fail(line_, 44, "record 7", "abscissa increment " + Shown(tokens[4]) + ": must be > 0 for even spacing");
  }
  return form;
}

// Record 12 in ASCII: the Fortran fields of its case, each line starting the format anew,
// until the closing "    -1".
void Parser::ReadAsciiValues(const DataForm& form, std::vector<double>* numbers) {
  std::vector<std::size_t> widths;
  if (!form.Double()) {
    widths = {13};  // 6E13.5
  } else if (form.even) {
    widths = {20};  // 4E20.12
  } else {
    widths = form.Complex() ? std::vector<std::size_t>{13, 20, 20} : std::vector<std::size_t>{13, 20};
  }
  const std::size_t expected = static_cast<std::size_t>(form.count) * form.PerPoint();
  std::string text;
  while (true) {
    if (!NextLine(&text)) Fail(line_, 1, "record 12", "the file ends inside the dataset: expected '    -1' after the values");
    if (Trim(text) == "-1") break;
    std::size_t column = 0;
    for (std::size_t field = 0; column < text.size(); ++field) {
      const std::size_t width = widths[field % widths.size()];
      const std::string cell = Columns(text, column, width);
      if (Trim(cell).empty() && Trim(text.substr(column)).empty()) break;  // the line's end
      double value = 0.0;
      if (!ParseReal(cell, &value)) {
        Fail(line_, static_cast<int>(column) + 1, "record 12",
             "expected a number in columns " + std::to_string(column + 1) + "-" + std::to_string(column + width) +
                 ", got " + Shown(cell));
      }
      if (numbers->size() == expected) {
        Fail(line_, static_cast<int>(column) + 1, "record 12",
             "more values than record 7 announces (" + std::to_string(form.count) + ")");
      }
      if (!std::isfinite(value)) NoteNonFinite(form, numbers->size(), line_, static_cast<int>(column) + 1, Trim(cell));
      numbers->push_back(value);
      column += width;
    }
  }
  if (numbers->size() < expected) {
    Fail(line_, 1, "record 12", "truncated: record 7 announces " + std::to_string(form.count) +
                                    (form.even ? " values" : " pairs") + " (" + std::to_string(expected) +
                                    " numbers), the dataset ends after " + std::to_string(numbers->size()));
  }
}

// The numbers after '58b' on the identifier line: byte order, floating-point format,
// ASCII lines, bytes (as many of them as parse).
std::vector<long> BinaryHeaderFields(const std::string& identifier) {
  std::vector<long> fields;
  std::size_t i = 7;
  while (fields.size() < 4) {
    i = identifier.find_first_not_of(" \t", i);
    if (i == std::string::npos) break;
    const std::size_t end = identifier.find_first_of(" \t", i);
    long value = 0;
    const std::string token = identifier.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (!ParseLong(token, &value)) break;
    fields.push_back(value);
    i = end;
  }
  return fields;
}

// Record 12 of a 58b: `bytes` raw numbers of the record's precision right after record
// 11, in the byte order of the identifier line (1 little, 2 big endian; IEEE 754 only).
// An uneven abscissa may be stored single while the ordinate is double (the ASCII form's
// E13.5): the byte count tells which.
Parser::BinaryLayout Parser::ReadBinaryLayout(const std::string& identifier, const DataForm& form) {
  std::vector<long> fields = BinaryHeaderFields(identifier);
  const int header_line = line_ - 11;
  if (fields.size() < 4) {
    Fail(header_line, 8, "record 58b", "expected byte order, floating-point format, ASCII lines and bytes after '58b'"
                                       " (Format(I6,1A1,I6,I6,I12,I12,...)), got " + Shown(identifier));
  }
  if (fields[0] != 1 && fields[0] != 2) {
    Fail(header_line, 8, "record 58b", "byte order " + std::to_string(fields[0]) + ": expected 1 (little endian) or 2 (big endian)");
  }
  if (fields[1] != 2) {
    Fail(header_line, 14, "record 58b", "floating-point format " + std::to_string(fields[1]) +
                                            ": only 2 (IEEE 754) is read (1 DEC VMS and 3 IBM 370 are not)");
  }
  if (fields[2] != 11) {
    Fail(header_line, 20, "record 58b", std::to_string(fields[2]) + " ASCII lines: dataset 58b has 11 (records 1-11)");
  }
  const std::size_t points = static_cast<std::size_t>(form.count);
  const std::size_t per_point = form.PerPoint();
  const std::size_t size = form.Double() ? 8 : 4;
  const bool single_abscissa = form.Double() && !form.even &&
                               fields[3] == static_cast<long>(points * (4 + (per_point - 1) * 8));
  const std::size_t expected = single_abscissa ? points * (4 + (per_point - 1) * 8) : points * per_point * size;
  // pyuff's 58b writer records half the bytes of complex doubles (it counts the values,
  // not their two parts); pyuff and sdypy read such files. Read when the file proves it:
  // the full data is there and "    -1" follows it.
  if (form.Complex() && form.Double() && !single_abscissa && fields[3] > 0 &&
      2 * static_cast<std::size_t>(fields[3]) == expected && ClosedAfter(expected)) {
    warnings_.push_back(file_ + ":" + std::to_string(header_line) + ":32: record 58b: " + std::to_string(fields[3]) +
                        " bytes of data announced, half the " + std::to_string(expected) + " bytes of record 7's " +
                        std::to_string(points) + " complex double values (pyuff's 58b writer counts so); the file "
                        "holds all " + std::to_string(expected) + " followed by '    -1': read them");
    fields[3] = static_cast<long>(expected);
  }
  if (fields[3] != static_cast<long>(expected)) {
    Fail(header_line, 32, "record 58b", std::to_string(fields[3]) + " bytes of data: record 7 announces " +
                                            std::to_string(points) + (form.even ? " values" : " pairs") + ", " +
                                            std::to_string(expected) + " bytes");
  }
  if (bytes_.size() - std::min(pos_, bytes_.size()) < expected) {
    Fail(line_ + 1, 1, "record 12", "truncated: " + std::to_string(expected) + " bytes of binary data announced, " +
                                        std::to_string(bytes_.size() - std::min(pos_, bytes_.size())) + " left in the file");
  }
  return BinaryLayout{fields[0] == 2, single_abscissa, expected};
}

// Whether `bytes` bytes from pos_ lie in the file and a "    -1" line follows them (after
// an optional line end).
bool Parser::ClosedAfter(std::size_t bytes) const {
  if (bytes_.size() - std::min(pos_, bytes_.size()) < bytes) return false;
  std::size_t at = pos_ + bytes;
  if (at < bytes_.size() && bytes_[at] == '\r') ++at;
  if (at < bytes_.size() && bytes_[at] == '\n') ++at;
  std::size_t end = bytes_.find('\n', at);
  if (end == std::string::npos) end = bytes_.size();
  return Trim(bytes_.substr(at, end - at)) == "-1";
}

// One number of `width` bytes (8: double, 4: single) at pos_, in the file's byte order.
double Parser::ReadBinaryNumber(std::size_t width, bool big) {
  std::uint64_t bits = 0;
  for (std::size_t b = 0; b < width; ++b) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[pos_ + (big ? b : width - 1 - b)]));
    bits = (bits << 8) | byte;
  }
  pos_ += width;
  if (width == 8) {
    double value;
    std::memcpy(&value, &bits, 8);
    return value;
  }
  const auto narrow = static_cast<std::uint32_t>(bits);
  float value;
  std::memcpy(&value, &narrow, 4);
  return static_cast<double>(value);
}

void Parser::ReadBinaryValues(const std::string& identifier, const DataForm& form, std::vector<double>* numbers) {
  const BinaryLayout layout = ReadBinaryLayout(identifier, form);
  const std::size_t points = static_cast<std::size_t>(form.count);
  const std::size_t per_point = form.PerPoint();
  const std::size_t size = form.Double() ? 8 : 4;
  const int data_line = line_ + 1;
  for (std::size_t p = 0; p < points; ++p) {
    for (std::size_t n = 0; n < per_point; ++n) {
      const double value = ReadBinaryNumber(layout.single_abscissa && n == 0 ? 4 : size, layout.big);
      if (!std::isfinite(value)) {
        NoteNonFinite(form, numbers->size(), data_line, 1, "binary value " + std::to_string(numbers->size() + 1));
      }
      numbers->push_back(value);
    }
  }
  // The closing "    -1" right after the data (some writers put a line end before it).
  line_ += static_cast<int>(std::count(bytes_.begin() + static_cast<std::ptrdiff_t>(pos_ - layout.expected),
                                       bytes_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
  if (pos_ < bytes_.size() && bytes_[pos_] == '\r') ++pos_;
  if (pos_ < bytes_.size() && bytes_[pos_] == '\n') {
    ++pos_;
    ++line_;
  }
  std::string text;
  const std::size_t at = pos_;
  if (!NextLine(&text) || Trim(text) != "-1") {
    pos_ = at;
    Fail(line_, 1, "record 12", "expected '    -1' right after the " + std::to_string(layout.expected) +
                                    " bytes of binary data (more data than announced, or a truncated file)");
  }
}

// Frequencies and complex values from record 12's numbers, in SI.
void Parser::StoreValues(const DataForm& form, const std::vector<double>& numbers, double scale, Uff58Record* record) {
  const std::size_t per_point = form.PerPoint();
  const std::size_t first = form.even ? 0 : 1;
  for (long p = 0; p < form.count; ++p) {
    const double* point = numbers.data() + static_cast<std::size_t>(p) * per_point;
    const double f = form.even ? form.min_hz + static_cast<double>(p) * form.increment_hz : point[0];
    if (!record->frequency_hz.empty() && !(f > record->frequency_hz.back())) {
      Fail(record->record12_line, 1, "record 12",
           "the abscissa is not ascending: point " + std::to_string(p + 1) + " at " + std::to_string(f) +
               " Hz after " + std::to_string(record->frequency_hz.back()) + " Hz");
    }
    record->frequency_hz.push_back(f);
    const double imaginary = form.Complex() ? point[first + 1] : 0.0;
    record->values.emplace_back(point[first] * scale, imaginary * scale);
  }
}

// A dataset other than 58: its lines up to the closing "    -1" are skipped.
void Parser::SkipDataset(long number, int line) {
  std::string text;
  while (NextLine(&text)) {
    if (Trim(text) == "-1") return;
  }
  Fail(line, 1, "dataset " + std::to_string(number), "not closed: the file ends before its '    -1'");
}

// Records 1-12 of one dataset 58 or 58b (the identifier line read).
void Parser::ReadDataset58(const std::string& identifier, Uff58Record* record) {
  const int opened = line_;
  record->line = opened;
  record->binary = identifier.size() > 6 && identifier[6] == 'b';
  record->id1 = Trim(HeaderLine("record 1", opened));
  for (int r = 2; r <= 5; ++r) HeaderLine("record " + std::to_string(r), opened);
  // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)).
  const std::string dofs = HeaderLine("record 6", opened);
  record->record6_line = line_;
  const long function_type = IntField(dofs, 0, 5, "record 6", "function type");
  if (function_type != 4) {
    Fail(line_, 1, "record 6", "function type " + std::to_string(function_type) + " (" +
                                   FunctionTypeName(function_type) +
                                   ") is not a frequency response function (4); only FRFs are read");
  }
  record->response_node = static_cast<int>(IntField(dofs, 41, 10, "record 6", "response node"));
  record->response_direction = static_cast<int>(IntField(dofs, 51, 4, "record 6", "response direction"));
  record->reference_node = static_cast<int>(IntField(dofs, 66, 10, "record 6", "reference node"));
  record->reference_direction = static_cast<int>(IntField(dofs, 76, 4, "record 6", "reference direction"));
  for (const int direction : {record->response_direction, record->reference_direction}) {
    if (direction < -6 || direction > 6) {
      Fail(line_, direction == record->response_direction ? 52 : 77, "record 6",
           "direction " + std::to_string(direction) + ": expected 0 (scalar) or +-1..+-6 (x, y, z translations, rotations)");
    }
  }
  const DataForm form = ReadDataForm(HeaderLine("record 7", opened));
  record->record7_line = line_;
  UffCharacteristics characteristics[4];  // records 8-11: Format(I10,3I5,2(1X,20A1))
  int lines[4] = {};
  for (int r = 0; r < 4; ++r) {
    const std::string text = HeaderLine("record " + std::to_string(8 + r), opened);
    lines[r] = line_;
    characteristics[r].specific_data_type = IntField(text, 0, 10, "record " + std::to_string(8 + r), "specific data type");
    characteristics[r].axis_label = Trim(Columns(text, 26, 20));
    characteristics[r].units_label = Trim(Columns(text, 47, 20));
  }
  record->record9_line = lines[1];
  const long abscissa = characteristics[0].specific_data_type;
  if (abscissa != 18 && abscissa != 0 && abscissa != 1) {
    Fail(lines[0], 1, "record 8", "abscissa specific data type " + std::to_string(abscissa) +
                                      ": an FRF's abscissa is frequency (18)");
  }
  std::string problem;
  int problem_record = 9;
  const std::optional<FrfUnits> units = UnderstandFrfUnits(characteristics[1], characteristics[2], &problem, &problem_record);
  if (!units) Fail(lines[problem_record - 8], 1, "record " + std::to_string(problem_record), problem);
  record->response = units->response;
  record->excitation = units->excitation;
  record->units = units->shown;
  record->record12_line = line_ + 1;
  std::vector<double> numbers;
  non_finite_.clear();
  numbers.reserve(static_cast<std::size_t>(std::min<long>(form.count, 1 << 20)) * form.PerPoint());
  if (record->binary) {
    ReadBinaryValues(identifier, form, &numbers);
  } else {
    ReadAsciiValues(form, &numbers);
  }
  StoreValues(form, numbers, units->scale, record);
  record->non_finite = non_finite_;
  if (NormalizedUnits(characteristics[0].units_label) == "rad/s") {
    for (double& f : record->frequency_hz) f /= 2.0 * kPi;
  }
}

Uff58File Parser::Parse() {
  Uff58File result;
  result.file = file_;
  std::vector<std::string> others;
  int first_other_line = 0;
  std::string text;
  while (NextLine(&text)) {
    if (Trim(text).empty()) continue;
    if (Trim(text) != "-1") {
      Fail(line_, 1, "dataset", "expected '    -1' opening a dataset, got " + Shown(text));
    }
    const int opened = line_;
    std::string identifier;
    if (!NextLine(&identifier)) Fail(opened, 1, "dataset", "'    -1' at the end of the file opens no dataset");
    long number = 0;
    if (!ParseLong(Columns(identifier, 0, 6), &number)) {
      Fail(line_, 1, "dataset", "expected the dataset number in columns 1-6, got " + Shown(identifier));
    }
    if (number != 58) {
      if (others.empty()) first_other_line = line_;
      if (std::find(others.begin(), others.end(), std::to_string(number)) == others.end()) {
        others.push_back(std::to_string(number));
      }
      SkipDataset(number, line_);
      continue;
    }
    Uff58Record record;
    ReadDataset58(identifier, &record);
    result.records.push_back(std::move(record));
  }
  result.warnings = warnings_;
  if (result.records.empty()) {
    std::string found;
    for (const std::string& number : others) found += (found.empty() ? "" : ", ") + number;
    Fail(others.empty() ? 1 : first_other_line, 1, "dataset",
         others.empty() ? "no dataset in the file: expected dataset 58 (function at nodal DOF) records between "
                          "'    -1' lines"
                        : "no dataset 58 (function at nodal DOF) in the file, only dataset " + found);
  }
  return result;
}

}  // namespace

int Uff58Record::ResponseAxis() const {
  const int axis = std::abs(response_direction);
  return axis >= 1 && axis <= 3 ? axis - 1 : -1;
}

double Uff58Record::DirectionSign() const {
  return (response_direction < 0 ? -1.0 : 1.0) * (reference_direction < 0 ? -1.0 : 1.0);
}

Uff58File ParseUff58(const std::string& bytes, const std::string& file) { return Parser(bytes, file).Parse(); }

Uff58File ReadUff58(const std::string& path) {
  std::string bytes;
  std::string error;
  if (!ReadInputFile(path, &bytes, &error)) throw ConfigError(path, 0, 0, "", error);
  return ParseUff58(bytes, path);
}

}  // namespace shapebench::bench
