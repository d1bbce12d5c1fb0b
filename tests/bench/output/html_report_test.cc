// --report FILE.html (bench/output/html_report.h) through the CLI and its pieces.
#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "bench/output/html_report.h"
#include "common/format.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;


std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// Tests that markup, quotes and ampersands become entities and a stray byte no raw byte.
TEST(HtmlReport, EscapesMarkupQuotesAndBadBytes) {
  EXPECT_EQ(HtmlEscape("<script>alert('x&y')</script>"),
            "&lt;script&gt;alert(&#39;x&amp;y&#39;)&lt;/script&gt;");
  EXPECT_EQ(HtmlEscape("a=\"b\""), "a=&quot;b&quot;");
  EXPECT_EQ(HtmlEscape("µm"), "µm");  // UTF-8 kept
  EXPECT_EQ(HtmlEscape(std::string("x\xff\x01y")), "x\xef\xbf\xbd\xef\xbf\xbdy");
}

// Tests that lengths read in um below a millimetre and mm above, times in ms below a
// second, as in the `run` table (one formatter, common/format.h); zero keeps the SI unit.
TEST(HtmlReport, ShowsEngineeringUnits) {
  EXPECT_EQ(EngineeringValue(8.3388e-6, "m"), (std::pair<std::string, std::string>{"8.3388", "um"}));
  EXPECT_EQ(EngineeringValue(0.0, "m"), (std::pair<std::string, std::string>{"0", "m"}));
  EXPECT_EQ(EngineeringValue(0.2, "m"), (std::pair<std::string, std::string>{"200", "mm"}));
  EXPECT_EQ(EngineeringValue(0.72, "s"), (std::pair<std::string, std::string>{"720", "ms"}));
  EXPECT_EQ(EngineeringValue(1.5, "s"), (std::pair<std::string, std::string>{"1.5", "s"}));
  EXPECT_EQ(EngineeringValue(1.0425, "1").second, "");
  EXPECT_EQ(EngineeringValue(NAN, "m").first, "n/a");
  EXPECT_EQ(EngineeringValue(1.0, "bool").first, "yes");
}

// Tests that `run --report` of a scenario named <script> shows the name as text: no tag
// of it anywhere (title, headings, the plot's SVG), and the page is one file that fetches
// nothing, whose only scripts are the interactive trace's two (the inlined library, then
// its graph).
TEST(HtmlReport, RunReportEscapesAHostileName) {
  ScratchDir dir;
  const std::string page = dir.File("report.html");
  const CliResult r = RunCli({"run", "configs/demo.yaml", "--set", "name=<script>alert(1)</script><b", "--report",
                              page},
                             kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = ReadText(page);
  EXPECT_EQ(Count(html, "<script"), 2u);
  EXPECT_EQ(Count(html, "<script>"), 2u);
  EXPECT_NE(html.find("<script>/*! @license https://github.com/danvk/dygraphs"), std::string::npos);
  EXPECT_EQ(Count(html, "<b<"), 0u);
  EXPECT_GE(Count(html, "&lt;script&gt;alert(1)&lt;/script&gt;&lt;b"), 2u);  // <title> and <h1>
  EXPECT_EQ(Count(html, "<svg"), 1u);
  EXPECT_NE(html.find("<td>peak_ratio</td>"), std::string::npos);
  EXPECT_NE(html.find("Effective scenario"), std::string::npos);
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org"));  // only SVG's namespaces
  EXPECT_EQ(html.find(" src="), std::string::npos);  // no element to load (the library's JS sets data: icons)
  EXPECT_EQ(html.find("sourceMappingURL"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
}

// Tests that `check --report` shows each check's verdict: PASS when it holds, FAIL with
// its bound when an override tightens it, and the exit code is check's as without it.
TEST(HtmlReport, CheckReportShowsPassAndFail) {
  ScratchDir dir;
  const CliResult pass = RunCli({"check", "configs/scenarios/method1.yaml", "--report", dir.File("pass.html")},
                                kSourceDir);
  ASSERT_EQ(pass.exit_code, 0) << pass.err;
  const std::string passed = ReadText(dir.File("pass.html"));
  EXPECT_NE(passed.find("<span class=\"pass\">PASS</span> peak_ratio"), std::string::npos);
  EXPECT_EQ(passed.find("class=\"fail\""), std::string::npos);

  const CliResult fail = RunCli({"check", "configs/scenarios/method1.yaml", "--set", "checks.peak_ratio.max=0.5",
                                 "--report", dir.File("fail.html")},
                                kSourceDir);
  EXPECT_EQ(fail.exit_code, 1) << fail.err;
  const std::string failed = ReadText(dir.File("fail.html"));
  EXPECT_TRUE(std::regex_search(failed, std::regex("<span class=\"fail\">FAIL</span> peak_ratio = [0-9.]+ \\(max 0\\.5\\)")));
  EXPECT_NE(failed.find("<p class=\"subtitle\">FAIL: "), std::string::npos);
}

// Tests that `sweep --report` draws the sweep's own plots (its `plots:`: residual_ratio
// and peak_ratio by method, as its PNGs), lists the robust bands (bands.csv's rows) and
// has every point's row in the results table.
TEST(HtmlReport, SweepReportHasPlotAndTable) {
  ScratchDir dir;
  const CliResult r = RunCli({"sweep", "configs/sweeps/natural_period.yaml", "--jobs", "2", "--out",
                              dir.File("out"), "--report", dir.File("sweep.html")},
                             kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = ReadText(dir.File("sweep.html"));
  EXPECT_EQ(Count(html, "<svg"), 2u);
  EXPECT_NE(html.find("<h2>residual_ratio-vs-frequency_hz-by-method.png</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>peak_ratio-vs-frequency_hz-by-method.png</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Robust bands</h2>"), std::string::npos);
  EXPECT_NE(html.find("<th>contains_design</th>"), std::string::npos);
  EXPECT_NE(html.find("<th>residual_ratio</th>"), std::string::npos);
  EXPECT_NE(html.find("<th>motion_time_s [ms]</th>"), std::string::npos);
  const std::string bands = ReadText(dir.File("out/bands.csv"));
  const auto band_rows = static_cast<std::size_t>(std::count(bands.begin(), bands.end(), '\n'));  // with its header
  EXPECT_EQ(Count(html, "<tr>"), band_rows + 1u + 603u);  // the bands, the header and 3 x 201 points
}

// Tests that `check` of a sweep whose every point fails summarises: on the terminal the
// check's summary line and the robust bands first, then the first 20 failing point-checks
// with their count stated (not 603 FAIL lines); in the report one line per check and the
// failing points in a closed <details> table with a row each.
TEST(HtmlReport, CheckOfASweepIsSummarised) {
  ScratchDir dir;
  const CliResult r = RunCli({"check", "configs/sweeps/natural_period.yaml", "--set", "controller.feed_mm_min=20000",
                              "--report", dir.File("check.html")},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.out.rfind("FAIL configs/sweeps/natural_period.yaml motion_time_s: 0 of 603 points pass", 0), 0u) << r.out;
  const std::size_t bands = r.out.find("\nrobust band residual_ratio <= 0.05 along machine.modes[0].frequency_hz:\n");
  const std::size_t failing =
      r.out.find("\nfailing points: the first 20 of 603 failing point-checks (--junit and --json list every one):\n");
  ASSERT_NE(bands, std::string::npos) << r.out;
  ASSERT_NE(failing, std::string::npos) << r.out;
  EXPECT_LT(bands, failing);
  EXPECT_EQ(Count(r.out.substr(failing), "\nFAIL "), 20u);
  const std::string html = ReadText(dir.File("check.html"));
  EXPECT_EQ(Count(html, "class=\"fail\">FAIL</span>"), 1u);
  EXPECT_NE(html.find("<details>\n<summary>603 failing point-checks (click to list them)</summary>"), std::string::npos);
  EXPECT_EQ(Count(html, "<tr>"), 1u + 603u);  // the details table's header and a row per failing point
}

// Tests that `compare --report` shows both sides' metrics and the overlaid plot.
TEST(HtmlReport, CompareReportHasBothSides) {
  ScratchDir dir;
  const CliResult r = RunCli({"compare", "configs/demo.yaml", "--candidate-set", "controller.pattern.method=none",
                              "--gate", "peak_ratio=0.05", "--report", dir.File("compare.html")},
                             kSourceDir);
  EXPECT_EQ(r.exit_code, 1) << r.err;  // the unshaped candidate fails the gate
  const std::string html = ReadText(dir.File("compare.html"));
  EXPECT_NE(html.find("<th>baseline</th><th>candidate</th>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"fail\">FAIL</span> gate peak_ratio=0.05"), std::string::npos);
  EXPECT_EQ(Count(html, "<svg"), 1u);
  EXPECT_NE(html.find("Candidate scenario: configs/demo.yaml --set controller.pattern.method=none"),
            std::string::npos);
}

// Tests that an unwritable --report fails with exit 2 before anything runs, leaving nothing.
TEST(HtmlReport, UnwritablePathFailsFirst) {
  ScratchDir dir;
  const CliResult missing =
      RunCli({"run", "configs/demo.yaml", "--report", dir.File("no/such/dir/r.html")}, kSourceDir);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("error: --report " + dir.File("no/such/dir/r.html") + ": cannot write there: "),
            std::string::npos)
      << missing.err;
  EXPECT_EQ(missing.out, "");  // no metrics table: nothing ran
  const CliResult directory = RunCli({"check", "configs/scenarios/method1.yaml", "--report", dir.path().string()},
                                     kSourceDir);
  EXPECT_EQ(directory.exit_code, 2);
  EXPECT_EQ(directory.out, "");
  const CliResult sweep = RunCli({"compare", "configs/sweeps/natural_period.yaml", "--candidate-set", "a=1",
                                  "--report", dir.File("c.html")},
                                 kSourceDir);
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_NE(sweep.err.find("two scenarios only"), std::string::npos) << sweep.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("c.html")));
}

}  // namespace
}  // namespace shapebench::bench
