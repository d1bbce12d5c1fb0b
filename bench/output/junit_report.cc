// WriteJUnit and XmlEscape (bench/output/report.h): the JUnit XML that CI systems read.
#include <cmath>
#include <ostream>
#include <string>

#include "common/atomic_file.h"
#include "common/csv.h"
#include "bench/output/report.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

// Length of the well-formed UTF-8 sequence at text[i], or 0; *allowed says whether XML 1.0
// allows its code point (Char ::= #x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD] |
// [#x10000-#x10FFFF]): not overlong forms, surrogates, U+FFFE, U+FFFF, above U+10FFFF.
std::size_t Utf8Length(const std::string& text, std::size_t i, bool* allowed) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  char32_t code = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2, code = lead & 0x1F;
  else if (lead >= 0xE0 && lead <= 0xEF) length = 3, code = lead & 0x0F;
  else if (lead >= 0xF0 && lead <= 0xF4) length = 4, code = lead & 0x07;
  else return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  static constexpr char32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};  // shortest form
  *allowed = code >= kLeast[length] && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF) &&
             code != 0xFFFE && code != 0xFFFF;
  return length;
}

// U+FFFD REPLACEMENT CHARACTER: what XML cannot carry is shown as replaced, not dropped.
constexpr char kReplacement[] = "\xEF\xBF\xBD";

// A stable name (CI tracks a testcase by it): "METRIC @ POINT"; a band check
// "METRIC over KEY in [FROM, TO]", its worst value and place in the message and properties.
std::string TestcaseName(const CheckResult& result) {
  if (result.banded()) {
    return result.metric + " over " + result.band_key + " in [" + FormatValue(result.band_from, 15) +
           ", " + FormatValue(result.band_to, 15) + "]";
  }
  return result.point.empty() ? CheckedQuantity(result) : CheckedQuantity(result) + " @ " + result.point;
}

// The failure's message: the value and the bound it crossed, "residual_ratio = 0.0613 >
// max 0.05" (a band check: its worst value and where, then the bound).
std::string FailureMessage(const CheckResult& result) {
  if (result.banded()) return BandText(result) + ": " + result.message;
  const std::string subject =
      CheckedQuantity(result) + (result.point.empty() ? "" : " @ " + result.point) + " = " + result.value_text;
  if (result.message.rfind("above ", 0) == 0) return subject + " > " + result.message.substr(6);
  if (result.message.rfind("below ", 0) == 0) return subject + " < " + result.message.substr(6);
  return subject + ": " + result.message;
}

}  // namespace

namespace {

// A band check's worst value and where, as properties (for tools) and the sentence (for
// people): "worst residual_ratio 0.061 at machine.modes[0].frequency_hz = 24.37 in [24, 26]".
void WriteBandDetails(std::ostream& out, const CheckResult& result) {
  // The shortest text that reads back as the same double: 18.15, not 18.149999999999999.
  const auto number = [](double value) { return std::isfinite(value) ? ShortestDouble(value) : FormatValue(value, 17); };
  out << "      <properties>\n"
      << "        <property name=\"band_key\" value=\"" << XmlEscape(result.band_key) << "\"/>\n"
      << "        <property name=\"worst_value\" value=\"" << number(result.value) << "\"/>\n"
      << "        <property name=\"worst_at\" value=\"" << number(result.worst_at) << "\"/>\n"
      << "        <property name=\"runs\" value=\"" << result.band_runs << "\"/>\n"
      << "      </properties>\n"
      << "      <system-out>" << XmlEscape(BandText(result)) << "</system-out>\n";
}

}  // namespace

std::string XmlEscape(const std::string& text) {
  std::string escaped;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    switch (c) {
      case '&': escaped += "&amp;"; continue;
      case '<': escaped += "&lt;"; continue;
      case '>': escaped += "&gt;"; continue;
      case '"': escaped += "&quot;"; continue;
      case '\'': escaped += "&apos;"; continue;
      case '\t': escaped += "&#9;"; continue;
      case '\n': escaped += "&#10;"; continue;
      case '\r': escaped += "&#13;"; continue;
      default: break;
    }
    if (c < 0x20) {
      escaped += kReplacement;  // not representable in XML 1.0
    } else if (c < 0x80) {
      escaped += static_cast<char>(c);
    } else if (bool allowed = false; const std::size_t length = Utf8Length(text, i, &allowed)) {
      escaped += allowed ? text.substr(i, length) : std::string(kReplacement);  // one per character
      i += length - 1;
    } else {
      escaped += kReplacement;  // not UTF-8, or a code point XML 1.0 does not allow
    }
  }
  return escaped;
}

void WriteJUnit(const std::string& path, const std::vector<ScenarioCheckReport>& reports) {
  int tests = 0;
  int failures = 0;
  int errors = 0;
  double time_s = 0.0;
  for (const auto& report : reports) {
    tests += report.error.empty() ? static_cast<int>(report.results.size()) : 1;
    errors += report.error.empty() ? 0 : 1;
    tests += static_cast<int>(report.point_errors.size());
    errors += static_cast<int>(report.point_errors.size());
    for (const auto& result : report.results) failures += result.passed ? 0 : 1;
    time_s += report.run_time_s;
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out << "<testsuites name=\"shapebench check\" tests=\"" << tests << "\" failures=\""
        << failures << "\" errors=\"" << errors << "\" time=\"" << FormatFixed(time_s, 3) << "\">\n";
    for (const auto& report : reports) {
      int suite_failures = 0;
      for (const auto& result : report.results) suite_failures += result.passed ? 0 : 1;
      const int suite_tests = (report.error.empty() ? static_cast<int>(report.results.size()) : 1) +
                              static_cast<int>(report.point_errors.size());
      const int suite_errors =
          (report.error.empty() ? 0 : 1) + static_cast<int>(report.point_errors.size());
      const std::string classname = XmlEscape("shapebench." + report.name);
      out << "  <testsuite name=\"" << XmlEscape(report.file) << "\" tests=\"" << suite_tests
          << "\" failures=\"" << suite_failures << "\" errors=\"" << suite_errors
          << "\" time=\"" << FormatFixed(report.run_time_s, 3)
          << "\">\n";
      if (!report.error.empty()) {
        out << "    <testcase classname=\"" << classname << "\" name=\"run\" time=\""
            << FormatFixed(report.run_time_s, 3) << "\">\n"
            << "      <error type=\"RunError\" message=\"" << XmlEscape(report.error) << "\">"
            << XmlEscape(report.error) << "</error>\n"
            << "    </testcase>\n";
      }
      // A sweep's point whose run failed: "run @ key=value".
      for (const auto& [point, message] : report.point_errors) {
        out << "    <testcase classname=\"" << classname << "\" name=\""
            << XmlEscape("run @ " + point) << "\" time=\"0.000\">\n"
            << "      <error type=\"RunError\" message=\"" << XmlEscape(message) << "\">"
            << XmlEscape(message) << "</error>\n"
            << "    </testcase>\n";
      }
      for (const auto& result : report.results) {
        out << "    <testcase classname=\"" << classname << "\" name=\""
            << XmlEscape(TestcaseName(result)) << "\" time=\""
            << FormatFixed(std::isfinite(result.run_time_s) ? result.run_time_s : 0.0, 3) << "\"";
        if (result.passed && !result.banded()) {
          out << "/>\n";
          continue;
        }
        out << ">\n";
        if (result.banded()) WriteBandDetails(out, result);
        if (!result.passed) {
          const std::string message = FailureMessage(result);
          out << "      <failure type=\"CheckFailed\" message=\"" << XmlEscape(message) << "\">"
              << XmlEscape(FormatCheckLine(report.file, result)) << "</failure>\n";
        }
        out << "    </testcase>\n";
      }
      out << "  </testsuite>\n";
    }
    out << "</testsuites>\n";
  });
}

}  // namespace shapebench::bench
