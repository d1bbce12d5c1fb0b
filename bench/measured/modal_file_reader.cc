// The FE modal export reader (modal_file_reader.h).
#include "bench/measured/modal_file_reader.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>

#include "bench/config/config_document.h"
#include "bench/config/config_error.h"
#include "bench/config/input_path.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

// The columns, their units (the allowed spellings; the first is the one to write) and
// where each number goes.
enum Column { kMode, kFrequency, kDamping, kParticipationX, kParticipationY, kParticipationZ,
              kShapeX, kShapeY, kShapeZ, kNumColumns };

struct ColumnSpec {
  const char* name;
  std::vector<std::string> units;
};

const std::array<ColumnSpec, kNumColumns>& Columns() {
  static const std::array<ColumnSpec, kNumColumns> kColumns = {{
      {"mode", {"-", ""}},
      {"frequency_hz", {"Hz"}},
      {"damping_ratio", {"1"}},
      {"participation_x", {"sqrt(kg)"}},
      {"participation_y", {"sqrt(kg)"}},
      {"participation_z", {"sqrt(kg)"}},
      {"shape_x", {"1/sqrt(kg)"}},
      {"shape_y", {"1/sqrt(kg)"}},
      {"shape_z", {"1/sqrt(kg)"}},
  }};
  return kColumns;
}

// A field's text as a message quotes it.
std::string QuotedForMessage(const std::string& text) { return "'" + ClippedForMessage(text) + "'"; }

std::string ColumnNames() {
  std::string names;
  for (const ColumnSpec& spec : Columns()) names += (names.empty() ? "" : ",") + std::string(spec.name);
  return names;
}

std::string UnitNames(const ColumnSpec& spec) {
  std::string names;
  for (const std::string& unit : spec.units) {
    names += (names.empty() ? "" : " or ") + (unit.empty() ? std::string("empty") : "'" + unit + "'");
  }
  return names;
}

// One field of a line: its text (trimmed, one pair of surrounding quotes removed) and
// its 1-based column.
struct ModalField {
  std::string text;
  int column = 1;
};

std::vector<ModalField> SplitLine(const std::string& line) {
  std::vector<ModalField> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = std::min(line.find(',', start), line.size());
    std::size_t first = start;
    std::size_t last = end;
    while (first < last && (line[first] == ' ' || line[first] == '\t')) ++first;
    while (last > first && (line[last - 1] == ' ' || line[last - 1] == '\t')) --last;
    if (last - first >= 2 && line[first] == '"' && line[last - 1] == '"') {
      ++first;
      --last;
    }
    fields.push_back({line.substr(first, last - first), static_cast<int>(first) + 1});
    if (end == line.size()) break;
    start = end + 1;
  }
  return fields;
}

// The file's lines that carry data: number (1-based) and text (no CR, no comment lines).
struct Line {
  int number = 0;
  std::string text;
};

std::vector<Line> DataLines(const std::string& text) {
  std::vector<Line> lines;
  std::size_t start = 0;
  int number = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string line = text.substr(start, end - start);
    ++number;
    start = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    lines.push_back({number, std::move(line)});
  }
  return lines;
}

class ModalFileParser {
 public:
  ModalFileParser(const std::string& text, std::string file) : lines_(DataLines(text)), file_(std::move(file)) {}

  std::vector<model::ModalMode> Parse() {
    if (lines_.empty()) {
      throw ConfigError(file_, 1, 1, "header", "the file has no header row; expected the columns " + ColumnNames() +
                                                   ", a row of their units, then one row per mode");
    }
    ReadHeader(lines_[0]);
    if (lines_.size() < 2) {
      throw ConfigError(file_, lines_[0].number + 1, 1, "units",
                        "missing: the second row names each column's unit (" + UnitRow() + ")");
    }
    ReadUnits(lines_[1]);
    if (lines_.size() < 3) {
      throw ConfigError(file_, lines_[1].number + 1, 1, "mode", "no modes: give at least one row after the units");
    }
    std::vector<model::ModalMode> modes;
    for (std::size_t i = 2; i < lines_.size(); ++i) {
      if (modes.size() == model::kMaxModelEntries) {
        throw ConfigError(file_, lines_[i].number, 1, "mode",
                          "at most " + std::to_string(model::kMaxModelEntries) + " modes (got more)");
      }
      modes.push_back(ReadMode(lines_[i]));
    }
    return modes;
  }

 private:
  static std::string UnitRow() {
    std::string row;
    for (const ColumnSpec& spec : Columns()) row += (row.empty() ? "" : ",") + spec.units.front();
    return row;
  }

  ConfigError Error(const Line& line, int column, const std::string& key, const std::string& message) const {
    return ConfigError(file_, line.number, column, key, message);
  }

  std::vector<ModalField> Fields(const Line& line, const char* what) const {
    std::vector<ModalField> fields = SplitLine(line.text);
    if (fields.size() != kNumColumns) {
      throw Error(line, 1, what,
                  "has " + std::to_string(fields.size()) + " fields; expected " +
                      std::to_string(kNumColumns) + ", one per column of the header (" + ColumnNames() + ")");
    }
    return fields;
  }

  void ReadHeader(const Line& line) {
    const std::vector<ModalField> fields = SplitLine(line.text);
    std::array<bool, kNumColumns> seen{};
    for (const ModalField& field : fields) {
      int found = -1;
      for (int c = 0; c < kNumColumns; ++c) {
        if (field.text == Columns()[c].name) found = c;
      }
      if (found < 0) {
        throw Error(line, field.column, "header",
                    "unknown column " + QuotedForMessage(field.text) + "; allowed: " + ColumnNames());
      }
      if (seen[found]) {
        throw Error(line, field.column, "header", "duplicate column '" + field.text + "'; each column once");
      }
      seen[found] = true;
      order_.push_back(found);
    }
    for (int c = 0; c < kNumColumns; ++c) {
      if (!seen[c]) {
        throw Error(line, 1, "header", std::string("missing column '") + Columns()[c].name +
                                           "'; the header names all of " + ColumnNames());
      }
    }
  }

  void ReadUnits(const Line& line) {
    const std::vector<ModalField> fields = Fields(line, "units");
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const ColumnSpec& spec = Columns()[order_[i]];
      bool known = false;
      for (const std::string& unit : spec.units) known = known || fields[i].text == unit;
      if (known) continue;
      const bool a_number = IsNumberText(fields[i].text) && order_[i] != kDamping;
      throw Error(line, fields[i].column, spec.name,
                  (a_number ? "missing unit row: the second row names each column's unit, got the number "
                            : "unit " + QuotedForMessage(fields[i].text) + " is not this column's; ") +
                      (a_number ? QuotedForMessage(fields[i].text) + "; " : std::string()) + "allowed: " + UnitNames(spec) +
                      " (the unit row: " + UnitRow() + ")");
    }
  }

  double Number(const Line& line, const ModalField& field, const ColumnSpec& spec) const {
    errno = 0;
    const double value = IsNumberText(field.text) ? std::strtod(field.text.c_str(), nullptr) : NAN;
    if (!IsNumberText(field.text) || (errno == ERANGE && std::isinf(value))) {
      throw Error(line, field.column, spec.name,
                  "expected a finite plain decimal number in " + UnitNames(spec) + ", got " +
                      (field.text.empty() ? std::string("an empty field") : QuotedForMessage(field.text)));
    }
    return value;
  }

  model::ModalMode ReadMode(const Line& line) {
    const std::vector<ModalField> fields = Fields(line, "mode");
    std::array<double, kNumColumns> value{};
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const int c = order_[i];
      const ColumnSpec& spec = Columns()[c];
      if (c == kMode) {
        const std::string& text = fields[i].text;
        const bool integer = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
        const long number = integer ? std::strtol(text.c_str(), nullptr, 10) : 0;
        if (number < 1) {
          throw Error(line, fields[i].column, spec.name,
                      "expected a positive integer (the mode's number), got " + QuotedForMessage(text));
        }
        if (!mode_numbers_.insert(number).second) {
          throw Error(line, fields[i].column, spec.name, "duplicate mode " + text + "; each mode once");
        }
        continue;
      }
      value[c] = Number(line, fields[i], spec);
      if (c == kFrequency && !(value[c] > 0.0)) {
        throw Error(line, fields[i].column, spec.name,
                    "must be > 0 Hz (got " + fields[i].text + "; leave rigid-body modes out of the export)");
      }
      if (c == kDamping && !(value[c] >= 0.0 && value[c] < 1.0)) {
        throw Error(line, fields[i].column, spec.name, "must be in [0, 1) (underdamped; got " + fields[i].text + ")");
      }
    }
    model::ModalMode mode;
    mode.frequency_hz = value[kFrequency];
    mode.damping_ratio = value[kDamping];
    mode.participation = model::AxisVector{value[kParticipationX], value[kParticipationY], value[kParticipationZ]};
    mode.shape = model::AxisVector{value[kShapeX], value[kShapeY], value[kShapeZ]};
    return mode;
  }

  std::vector<Line> lines_;
  std::string file_;
  std::vector<int> order_;  // per field of a row, its Column
  std::set<long> mode_numbers_;
};

}  // namespace

std::vector<model::ModalMode> ParseModalFile(const std::string& text, const std::string& file) {
  return ModalFileParser(text, file).Parse();
}

model::ModalMachineConfig ReadModalFile(const NodeReader& modal_file) {
  const std::string reference = modal_file.AsString();
  const std::string file = ResolvedInputPath(modal_file);
  const std::string shown = file == reference ? "'" + reference + "'" : "'" + reference + "' (" + file + ")";
  std::string text;
  std::string error;
  if (!ReadInputFile(file, &text, &error)) throw modal_file.Error("modal file " + shown + ": " + error);
  model::ModalMachineConfig config;
  config.modes = ParseModalFile(text, file);
  config.modal_file = file;
  return config;
}

}  // namespace shapebench::bench
