// Klipper's PSD files (see the header).
#include "bench/measured/klipper_psd_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include "bench/config/config_error.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

constexpr char kAxesHeader[] = "freq,psd_x,psd_y,psd_z,psd_xyz";

struct PsdLine {
  std::string text;
  int number = 0;
};

// The lines that are neither blank nor (before the header) '#' comments; CRLF trimmed.
std::vector<PsdLine> ContentLines(const std::string& text) {
  std::vector<PsdLine> lines;
  int number = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    const std::size_t newline = text.find('\n', position);
    std::string line = text.substr(position, newline == std::string::npos ? std::string::npos : newline - position);
    position = newline == std::string::npos ? text.size() : newline + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    lines.push_back({line, number});
  }
  return lines;
}

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t first = field.find_first_not_of(" \t");
    const std::size_t last = field.find_last_not_of(" \t");
    fields.push_back(first == std::string::npos ? std::string() : field.substr(first, last - first + 1));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

// A field's value: empty is 0 (numpy's filling_values), otherwise a finite number.
double Number(const std::string& field, const PsdLine& line, std::size_t index, const std::string& column,
              const std::string& file) {
  if (field.empty()) return 0.0;
  std::size_t column_at = 1;  // after the index-th comma
  std::size_t seen = 0;
  for (std::size_t i = 0; i < line.text.size() && seen < index; ++i) {
    if (line.text[i] != ',') continue;
    column_at = i + 2;
    ++seen;
  }
  double value = 0.0;
  const char* first = field.data();
  const char* last = first + field.size();
  if (*first == '+') ++first;
  const auto [end, error] = std::from_chars(first, last, value);
  if (error != std::errc() || end != last || !std::isfinite(value)) {
    throw ConfigError(file, line.number, static_cast<int>(column_at), column,
                      "not a finite number: '" + ClippedForMessage(field) + "'; expected a decimal number");
  }
  return value;
}

}  // namespace

bool IsKlipperPsdFile(const std::string& text) {
  const std::vector<PsdLine> lines = ContentLines(text);
  return !lines.empty() && lines[0].text.rfind("freq,", 0) == 0;
}

std::string ForeignFileKind(const std::string& text) {
  const std::vector<PsdLine> lines = ContentLines(text);
  if (lines.empty()) return "";
  const std::string& first = lines[0].text;
  const std::string trimmed = first.substr(first.find_first_not_of(" \t"));
  if (trimmed == "-1") return "a UFF (universal file format) file: `shapebench identify` reads it";
  if (first.rfind("frequency_hz,psd", 0) == 0) {
    return "the psd.csv `shapebench recommend --out` writes (its own output), not a log";
  }
  if (first.rfind("frequency_hz", 0) == 0 || first.rfind("mode", 0) == 0) {
    return "a modal file (modes by frequency): a scenario's machine.modal_file reads it";
  }
  if (first.find(';') != std::string::npos && first.find(',') == std::string::npos) {
    return "a semicolon-separated table: Klipper's files and logs are comma-separated";
  }
  return "";
}

KlipperSpectrum ParseKlipperPsdFile(const std::string& text, const std::string& file) {
  const std::vector<PsdLine> lines = ContentLines(text);
  const PsdLine& header = lines.at(0);
  const std::vector<std::string> names = Split(header.text);
  KlipperSpectrum spectrum;
  spectrum.normalized_in_file = header.text.find(",shapers:") != std::string::npos;
  spectrum.source = spectrum.normalized_in_file ? "calibration_data csv" : "resonances csv";
  const bool axes = header.text.rfind(kAxesHeader, 0) == 0;
  std::size_t sets = 0;  // the data set columns after freq
  while (1 + sets < names.size() && names[1 + sets] != "shapers:") ++sets;
  if (axes) sets = 1;
  if (sets == 0) {
    throw ConfigError(file, header.number, 1, "header",
                      "no PSD column after 'freq'; expected " + std::string(kAxesHeader) +
                          " (resonances_*.csv) or freq,NAME,... (calibration_data_*.csv)");
  }
  spectrum.datasets.resize(sets);
  for (std::size_t d = 0; d < sets; ++d) spectrum.datasets[d].name = axes ? file : names[1 + d];
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> fields = Split(lines[i].text);
    const std::size_t needed = axes ? 5 : 1 + sets;
    if (fields.size() < needed) {
      throw ConfigError(file, lines[i].number, static_cast<int>(lines[i].text.size()) + 1,
                        names[std::min(fields.size(), names.size() - 1)],
                        "expected " + std::to_string(needed) + " fields as the header has, got " +
                            std::to_string(fields.size()));
    }
    std::vector<double> values;
    for (std::size_t f = 0; f < fields.size(); ++f) {
      values.push_back(Number(fields[f], lines[i], f, f < names.size() ? names[f] : "field", file));
    }
    for (std::size_t d = 0; d < sets; ++d) {
      KlipperPsd& psd = spectrum.datasets[d];
      psd.frequency_hz.push_back(values[0]);
      psd.psd_sum.push_back(axes ? values[4] : values[1 + d]);
      if (axes) {
        for (int a = 0; a < 3; ++a) psd.psd_axis[a].push_back(values[1 + a]);
      }
    }
  }
  if (spectrum.datasets[0].frequency_hz.size() < 2) {
    throw ConfigError(file, header.number, 1, "freq", "fewer than two rows of PSD after the header");
  }
  if (!spectrum.normalized_in_file) {
    for (KlipperPsd& psd : spectrum.datasets) NormalizeToFrequencies(&psd);
  }
  return spectrum;
}

}  // namespace shapebench::bench
