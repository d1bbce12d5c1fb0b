// The HTML report (bench/output/html_report.h).
#include "bench/output/html_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "bench/output/gnuplot.h"
#include "common/atomic_file.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

// Screen and print alike; no web fonts, nothing fetched.
constexpr const char* kStyle = R"(
body { font-family: sans-serif; margin: 2em auto; max-width: 1100px; color: #222; background: #fff; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; margin-top: 1.6em; }
p.subtitle { color: #555; margin-top: 0; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
ul.checks { list-style: none; padding-left: 0; font-family: monospace; }
.pass { color: #176b1c; font-weight: bold; }
.fail { color: #b00020; font-weight: bold; }
pre { background: #f7f7f7; border: 1px solid #ddd; padding: 0.8em; overflow-x: auto; font-size: 0.85em; }
div.plot svg { max-width: 100%; height: auto; }
)";

bool LooksNumeric(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end != nullptr && *end == '\0';
}

void RenderTable(std::ostream& out, const HtmlTable& table) {
  out << "<table>\n<thead><tr>";
  for (const std::string& cell : table.header) out << "<th>" << HtmlEscape(cell) << "</th>";
  out << "</tr></thead>\n<tbody>\n";
  for (const auto& row : table.rows) {
    out << "<tr>";
    for (const std::string& cell : row) {
      out << (LooksNumeric(cell) ? "<td class=\"num\">" : "<td>") << HtmlEscape(cell) << "</td>";
    }
    out << "</tr>\n";
  }
  out << "</tbody>\n</table>\n";
}

void RenderSection(std::ostream& out, const HtmlSection& section) {
  out << "<section>\n<h2>" << HtmlEscape(section.heading) << "</h2>\n";
  if (!section.note.empty()) out << "<p>" << HtmlEscape(section.note) << "</p>\n";
  if (!section.table.header.empty()) RenderTable(out, section.table);
  if (!section.checks.empty()) {
    out << "<ul class=\"checks\">\n";
    for (const HtmlCheck& check : section.checks) {
      out << "<li>" << (check.passed ? "<span class=\"pass\">PASS</span> " : "<span class=\"fail\">FAIL</span> ")
          << HtmlEscape(check.text) << "</li>\n";
    }
    out << "</ul>\n";
  }
  if (!section.details.header.empty()) {
    out << "<details>\n<summary>" << HtmlEscape(section.details_summary) << "</summary>\n";
    RenderTable(out, section.details);
    out << "</details>\n";
  }
  if (!section.svg.empty()) out << "<div class=\"plot\">\n" << section.svg << "\n</div>\n";
  if (!section.preformatted.empty()) out << "<pre>" << HtmlEscape(section.preformatted) << "</pre>\n";
  out << "</section>\n";
}

// The length of the UTF-8 sequence starting at text[i], or 0 when it is not one.
std::size_t Utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const std::size_t length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xe ? 3
                                             : (lead >> 3) == 0x1e ? 4 : 0;
  if (length == 0 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  }
  return length;
}

}  // namespace

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const std::size_t length = Utf8Length(text, i);
    if (length == 0) {
      out += "\xef\xbf\xbd";  // U+FFFD
      ++i;
      continue;
    }
    if (length > 1) {
      out.append(text.substr(i, length));
    } else if (c == '&') {
      out += "&amp;";
    } else if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '"') {
      out += "&quot;";
    } else if (c == '\'') {
      out += "&#39;";
    } else if ((static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') || c == '\x7f') {
      out += "\xef\xbf\xbd";
    } else {
      out += c;
    }
    i += length;
  }
  return out;
}

std::string RenderHtml(const HtmlReport& report) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"generator\" content=\"shapebench\">\n<title>" << HtmlEscape(report.title)
      << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<h1>" << HtmlEscape(report.title)
      << "</h1>\n";
  if (!report.subtitle.empty()) out << "<p class=\"subtitle\">" << HtmlEscape(report.subtitle) << "</p>\n";
  for (const HtmlSection& section : report.sections) RenderSection(out, section);
  out << "</body>\n</html>\n";
  return out.str();
}

void WriteHtmlReport(const std::string& path, const HtmlReport& report) {
  const std::string page = RenderHtml(report);
  WriteFileAtomically(path, [&](std::ostream& out) { out << page; });
}

HtmlTable MetricsHtmlTable(const Metrics& metrics) {
  HtmlTable table;
  table.header = {"metric", "value", "unit", "lower/higher is better", "meaning"};
  auto add = [&](const MetricInfo& info) {
    const auto [number, unit] = EngineeringValue(metrics.*info.field, info.unit);
    table.rows.push_back({std::string(info.name), number, unit, std::string(BetterName(info.better)),
                          std::string(info.description)});
  };
  for (const MetricInfo& info : MetricTable()) add(info);
  // A nonlinear plant's own metrics where defined, as the text table has them.
  for (const MetricInfo& info : NonlinearMetricTable()) {
    if (!std::isnan(metrics.*info.field)) add(info);
  }
  return table;
}

std::vector<HtmlCheck> HtmlChecks(const std::vector<CheckResult>& results) {
  std::vector<HtmlCheck> checks;
  for (const CheckResult& result : results) {
    std::string line = FormatCheckLine("", result);
    // "PASS  metric ...": the verdict is shown as its own badge.
    const std::size_t space = line.find(' ');
    line = space == std::string::npos ? line : line.substr(space + 1);
    while (!line.empty() && line.front() == ' ') line.erase(0, 1);
    checks.push_back({result.passed, line});
  }
  return checks;
}

}  // namespace shapebench::bench
