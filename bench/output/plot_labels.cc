// FitLegend, DifferingParts, WriteCaption (bench/output/plot_labels.h).
#include "bench/output/plot_labels.h"

#include <map>
#include <utility>

#include <yaml-cpp/yaml.h>

#include "bench/output/gnuplot.h"

namespace shapebench::bench {
namespace {

// Characters, not bytes: a UTF-8 continuation byte does not count.
std::size_t Chars(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += (static_cast<unsigned char>(c) & 0xc0) != 0x80 ? 1 : 0;
  return n;
}

// The first `chars` characters of `text`, never a split UTF-8 sequence.
std::string FirstChars(const std::string& text, std::size_t chars) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xc0) != 0x80 && n++ == chars) return text.substr(0, i);
  }
  return text;
}

using Entries = std::vector<std::pair<std::string, std::string>>;

// The entries of a YAML flow mapping, values as flow text; false when `text` is none.
bool MappingEntries(const std::string& text, Entries* entries) {
  try {
    const YAML::Node node = YAML::Load(text);
    if (!node.IsMap()) return false;
    for (const auto& entry : node) {
      YAML::Emitter out;
      out << YAML::Flow << entry.second;
      entries->emplace_back(entry.first.as<std::string>(), out.c_str());
    }
    return !entries->empty();
  } catch (const YAML::Exception&) {
    return false;
  }
}

}  // namespace

FittedLegend FitLegend(const std::vector<std::string>& names, const std::vector<std::string>& full_names,
                       std::size_t max_chars) {
  FittedLegend legend;
  std::size_t tag = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& full = i < full_names.size() ? full_names[i] : names[i];
    const bool cut = Chars(names[i]) > max_chars;
    if (!cut && names[i] == full) {
      legend.titles.push_back(names[i]);
      continue;
    }
    const std::string mark = "[" + std::to_string(++tag) + "] ";
    legend.titles.push_back(cut ? mark + FirstChars(names[i], max_chars - Chars(mark) - 1) + "…"
                                : (names[i].empty() ? mark : names[i]));
    legend.caption.push_back(cut ? mark + full : (names[i].empty() ? mark : names[i] + " — ") + full);
  }
  return legend;
}

std::vector<std::string> DifferingParts(const std::vector<std::string>& values) {
  std::vector<Entries> mappings(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!MappingEntries(values[i], &mappings[i])) return values;
  }
  // A key differs when some mapping lacks it or holds another value.
  std::map<std::string, std::string> first;
  std::map<std::string, std::size_t> count;
  std::map<std::string, bool> differs;
  for (const Entries& entries : mappings) {
    for (const auto& [key, value] : entries) {
      if (count[key]++ == 0) first[key] = value;
      if (first[key] != value) differs[key] = true;
    }
  }
  for (auto& [key, n] : count) {
    if (n != values.size()) differs[key] = true;
  }
  const bool any_differs = !differs.empty();
  std::vector<std::string> parts;
  for (const Entries& entries : mappings) {
    std::string part;
    for (const auto& [key, value] : entries) {
      if (any_differs && differs.count(key) == 0) continue;
      part += (part.empty() ? "" : ", ") + key + ": " + value;
    }
    parts.push_back(part);
  }
  return parts;
}

double CaptionHeight(std::size_t rows, int height_px) {
  return rows == 0 ? 0.0 : (14.0 * static_cast<double>(rows) + 6.0) / static_cast<double>(height_px);
}

std::size_t WriteCaption(std::FILE* gnuplot, const std::vector<std::string>& caption, int height_px) {
  for (std::size_t r = 0; r < caption.size(); ++r) {
    const double y = CaptionHeight(caption.size() - r, height_px) - 10.0 / height_px;
    std::fprintf(gnuplot, "set label %s at screen 0.01, screen %.6f left font 'sans,8' tc rgb '#333333'\n",
                 GnuplotQuoted(caption[r]).c_str(), y);
  }
  return caption.size();
}

}  // namespace shapebench::bench
