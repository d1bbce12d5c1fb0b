// Hostile text and limits found by attacking the CLI: names and values that could break
// the JUnit XML, flood an error message, drive the terminal, or overflow a file name; and
// messages that must name the right limit and tell a value from its bound.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/output/report.h"
#include "tests/support/bench_test_support.h"
#include "common/atomic_file.h"
#include "common/format.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;


bool XmlIsWellFormed(const std::string& path) {
  return std::system(("xmllint --noout " + testing::ShellQuoted(path) + " 2>/dev/null").c_str()) == 0;
}

// Tests that text XML 1.0 cannot carry (U+FFFE, U+FFFF, surrogates, code points above
// U+10FFFF, overlong forms, truncated sequences, control bytes) is replaced by U+FFFD, and
// that a document of such names is well-formed for xmllint.
TEST(HostileText, XmlEscapeKeepsTheDocumentWellFormed) {
  const std::string replacement = "\xEF\xBF\xBD";
  EXPECT_EQ(XmlEscape("t\xEF\xBF\xBF"), "t" + replacement);          // U+FFFF
  EXPECT_EQ(XmlEscape("t\xEF\xBF\xBE"), "t" + replacement);          // U+FFFE
  EXPECT_EQ(XmlEscape("\xEF\xBF\xBD"), replacement);                 // U+FFFD itself is fine
  EXPECT_EQ(XmlEscape("\xF0\x9F\x98\x80"), "\xF0\x9F\x98\x80");      // U+1F600 kept
  EXPECT_EQ(XmlEscape("\xED\x9F\xBF"), "\xED\x9F\xBF");              // U+D7FF kept
  EXPECT_EQ(XmlEscape("\xEE\x80\x80"), "\xEE\x80\x80");              // U+E000 kept
  EXPECT_EQ(XmlEscape("\xED\xA0\x80").find("\xED"), std::string::npos);  // U+D800
  const std::vector<std::string> hostile = {
      "t\xEF\xBF\xBF", "t\xEF\xBF\xBE", "\xED\xA0\x80x", "\xED\xBF\xBF", "\xF4\x90\x80\x80",
      "\xE0\x80\xAF", "\xF0\x80\x80\xAF", "\xC0\xAF", "\xE2\x82", "\x1b[2J\x7f", "\xEF\xBF"};
  ScratchDir dir;
  for (const std::string& name : hostile) {
    const std::string path = dir.Write("doc.xml", "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<a n=\"" +
                                                      XmlEscape(name) + "\">" + XmlEscape(name) + "</a>\n");
    EXPECT_TRUE(XmlIsWellFormed(path)) << ReadText(path);
  }
}

// Tests that `check --junit` of a scenario named "t\uFFFF" writes well-formed XML.
TEST(HostileText, JUnitOfANonCharacterNameIsWellFormed) {
  ScratchDir dir;
  const std::string junit = dir.File("report.xml");
  const CliResult result = RunCli({"check", DataPath("shaped_method1.yaml"), "--set", "name=\"t\\uFFFF\"",
                                   "--junit", junit},
                                  kSourceDir);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(XmlIsWellFormed(junit)) << ReadText(junit);
}

// Tests that a 10000-character value or key (an explicit "? KEY" passes yaml-cpp's
// 1024-character limit on plain keys) is quoted in an error message only by its
// first 200 characters, an ellipsis and its full length.
TEST(HostileText, LongValuesAreCutInErrorMessages) {
  EXPECT_EQ(ClippedForMessage("short"), "short");
  EXPECT_EQ(ClippedForMessage(std::string(10000, 'x')),
            std::string(200, 'x') + "... (10000 characters in all)");
  // A cut does not split a UTF-8 character.
  EXPECT_EQ(ClippedForMessage(std::string(199, 'x') + "\xC2\xB5" + "yyy"), std::string(199, 'x') +
                                                                               "... (204 characters in all)");
  const std::string long_value(10000, 'v');
  const CliResult value = RunCli({"run", DataPath("shaped_method1.yaml"), "--set", "controller.period_s=" + long_value},
                                 kSourceDir);
  EXPECT_EQ(value.exit_code, 2) << value.err.substr(0, 500);
  EXPECT_LT(value.err.size(), 1000u) << value.err.substr(0, 500);
  EXPECT_NE(value.err.find("(10000 characters in all)"), std::string::npos) << value.err.substr(0, 500);

  ScratchDir dir;
  const std::string key(10000, 'k');
  const std::string scenario = dir.Write("long_key.yaml", ReadText(DataPath("shaped_method1.yaml")) + "? " + key + "\n: 1\n");
  const CliResult unknown = RunCli({"run", scenario}, kSourceDir);
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err.substr(0, 500);
  EXPECT_LT(unknown.err.size(), 2000u) << unknown.err.substr(0, 500);
  EXPECT_NE(unknown.err.find("unknown key 'kkk"), std::string::npos) << unknown.err.substr(0, 500);
}

// Tests that a run refused for its length names limits.max_ticks when max_ticks is the
// limit that binds, both when the lower bound at load and when the planned window exceed it.
TEST(HostileText, RunLengthRefusalNamesTheBindingLimit) {
  const std::string scenario = DataPath("shaped_method1.yaml");
  const CliResult both = RunCli({"run", scenario, "--set", "limits={max_simulated_s: 0.2, max_ticks: 10}"}, kSourceDir);
  EXPECT_EQ(both.exit_code, 2) << both.err;
  EXPECT_NE(both.err.find(": limits.max_ticks: scenario 'shaped_method1' would take"), std::string::npos) << both.err;

  const CliResult window = RunCli({"run", scenario, "--set", "limits.max_ticks=1150"}, kSourceDir);
  EXPECT_EQ(window.exit_code, 2) << window.err;
  EXPECT_NE(window.err.find("limits.max_ticks: the command and its residual window take"), std::string::npos)
      << window.err;
  EXPECT_EQ(window.err.find("limits.max_simulated_s"), std::string::npos) << window.err;
}

// Tests that numbers in messages keep six significant digits when those read back
// exactly, and enough more to tell a value from a bound otherwise (1.000001 is not 1).
TEST(HostileText, FormatNumberTellsAValueFromItsBound) {
  EXPECT_EQ(FormatNumber(1.0), "1");
  EXPECT_EQ(FormatNumber(0.05), "0.05");
  EXPECT_EQ(FormatNumber(1e-7), "1e-07");
  EXPECT_EQ(FormatNumber(123456.0), "123456");
  EXPECT_EQ(FormatNumber(1.000001), "1.000001");
  EXPECT_EQ(FormatNumber(0.999999999999), "0.999999999999");
  EXPECT_EQ(FormatNumber(10.001100000000001), "10.0011");  // computed: 17 digits, kept to six
  const CliResult damping = RunCli({"run", DataPath("shaped_method1.yaml"), "--set",
                                    "machine.modes[0].damping_ratio=1.000001"},
                                   kSourceDir);
  EXPECT_EQ(damping.exit_code, 2) << damping.err;
  EXPECT_NE(damping.err.find("got 1.000001"), std::string::npos) << damping.err;
}

// Tests that control characters of a scenario's name (ESC [ 2 J clears a terminal) are
// printed as visible escapes in the `run` table header and in error messages.
TEST(HostileText, ControlCharactersArePrintedVisibly) {
  EXPECT_EQ(TerminalSafe("a\x1b[2J\tb\x7f"), "a\\x1b[2J\tb\\x7f");
  EXPECT_EQ(TerminalSafe("a\nb"), "a\\x0ab");
  EXPECT_EQ(TerminalSafe("a\nb", /*keep_newlines=*/true), "a\nb");
  EXPECT_EQ(TerminalSafe("\xC2\x9B" "31m \xC2\xB5"), "\\u009b31m \xC2\xB5");  // C1 CSI; U+00B5 kept
  const std::string scenario = DataPath("shaped_method1.yaml");
  const CliResult run = RunCli({"run", scenario, "--set", "name=\"t\\e[2J\\x07\""}, kSourceDir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("scenario t\\x1b[2J\\x07 ("), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find('\x1b'), std::string::npos);
  const CliResult refused =
      RunCli({"run", scenario, "--set", "name=\"t\\e[2J\"", "--set", "limits.max_simulated_s=0.2"}, kSourceDir);
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("scenario 't\\x1b[2J' would"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find('\x1b'), std::string::npos);
}

// Tests that a file whose name is 250 characters long (its temporary name would pass
// NAME_MAX, 255, with a suffix) is written atomically, leaving no temporary file.
TEST(HostileText, LongFileNamesAreWrittenAtomically) {
  ScratchDir dir;
  const std::string path = dir.File(std::string(246, 'j') + ".xml");
  WriteFileAtomically(path, [](std::ostream& out) { out << "<a/>\n"; });
  EXPECT_EQ(ReadText(path), "<a/>\n");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) files += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
  const CliResult check =
      RunCli({"check", DataPath("shaped_method1.yaml"), "--junit", dir.File(std::string(246, 'k') + ".xml")},
             kSourceDir);
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_TRUE(XmlIsWellFormed(dir.File(std::string(246, 'k') + ".xml")));
}

}  // namespace
}  // namespace shapebench::bench
