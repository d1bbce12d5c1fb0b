// Legends that survive real labels (issue 37 must-show 1): each plot kind drawn with long
// mapping values (a whole controller.pattern per series, long --candidate-set labels)
// names its series by what differs in the legend, lists the full names once in a caption
// (both read back from gnuplot's SVG text), and leaves nothing on stderr: gnuplot warns
// there ("difficulty fitting plot titles into key") and draws an empty key when a title is
// wider than the page.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/output/html_report.h"
#include "bench/output/plot_labels.h"
#include "bench/output/report.h"
#include "bench/scenario/scenario.h"
#include "bench/sweep/sweep_plot.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ScratchDir;

// Three whole pattern mappings that differ in their method, one also in a long key.
const std::vector<std::string> kPatterns = {
    "{method: zv, mode: both, frequency_hz: 25, design_damping_ratio: 0.02, realization: stepped}",
    "{method: zvd, mode: both, frequency_hz: 25, design_damping_ratio: 0.02, realization: stepped}",
    "{method: ei, mode: both, frequency_hz: 25, design_damping_ratio: 0.02, realization: stepped, "
    "vibration_tolerance: 0.0312500000000001}"};
const std::vector<double> kFrequencies = {20, 22.5, 25, 27.5, 30};

// A sweep of controller.pattern (3 mappings) x machine.modes[0].frequency_hz (5 values).
SweepLayout LongKeyLayout() {
  SweepLayout layout;
  layout.name = "long_keys";
  layout.keys = {"controller.pattern", "machine.modes[0].frequency_hz"};
  layout.key_axis = {0, 1};
  layout.key_log = {false, false};
  layout.axis_sizes = {3, 5};
  layout.metrics = {"residual_ratio"};
  layout.bands = {{"residual_ratio", "machine.modes[0].frequency_hz", "controller.pattern", 0.05}};
  return layout;
}

std::string LongKeyResults(const ScratchDir& dir) {
  std::string csv = "point,controller.pattern,machine.modes[0].frequency_hz,residual_ratio,status,error\n";
  for (std::size_t s = 0; s < kPatterns.size(); ++s) {
    for (std::size_t i = 0; i < kFrequencies.size(); ++i) {
      const double value = 0.01 * (1.0 + static_cast<double>(s)) * (1.0 + std::abs(kFrequencies[i] - 25.0));
      csv += std::to_string(s * 5 + i) + ",\"" + kPatterns[s] + "\"," + ShortestDouble(kFrequencies[i]) + "," +
             ShortestDouble(value) + ",ok,\n";
    }
  }
  return dir.Write("results.csv", csv);
}

// Whether the SVG holds `text` as a whole text element's content.
bool HasText(const std::string& svg, const std::string& text) {
  return svg.find(">" + text + "</") != std::string::npos;
}

// Tests that the sweep's line plot, CDF and heat map of a swept whole pattern mapping name
// each series (a heat map's tic) by the key that differs, "method: zvd", cut with a "[n]"
// tag when still long, each full mapping in the caption; and that gnuplot says nothing on
// stderr (the legend fits: before, it was empty and gnuplot warned).
TEST(PlotLegend, SweepPlotsNameSeriesByWhatDiffers) {
  const ScratchDir dir;
  const std::string csv = LongKeyResults(dir);
  SweepLayout layout = LongKeyLayout();
  SweepPlot line;
  line.metric = "residual_ratio";
  line.x = "machine.modes[0].frequency_hz";
  line.series = "controller.pattern";
  SweepPlot cdf = line;
  cdf.cdf = true;
  cdf.limits = {0.05};
  SweepPlot heat;
  heat.metric = "residual_ratio";
  heat.heatmap_x = "machine.modes[0].frequency_hz";
  heat.heatmap_y = "controller.pattern";
  for (const SweepPlot& plot : {line, cdf, heat}) {
    SCOPED_TRACE(plot.heatmap() ? "heat map" : plot.cdf ? "cdf" : "line plot");
    ::testing::internal::CaptureStderr();
    const std::string svg = SweepPlotSvg(layout, plot, csv);
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_TRUE(HasText(svg, "method: zv")) << svg;
    EXPECT_TRUE(HasText(svg, "method: zvd"));
    EXPECT_FALSE(HasText(svg, "controller.pattern = " + kPatterns[0])) << "a whole mapping in the legend";
    for (const std::string& pattern : kPatterns) {
      const bool found = svg.find(pattern + "</") != std::string::npos;
      EXPECT_TRUE(found) << "the caption lacks " << pattern;
    }
    // The third differs in two keys: cut in the legend, tagged, whole in the caption.
    EXPECT_NE(svg.find(">[3] method: ei, vibrati"), std::string::npos);
  }
}

// Tests that the line plot draws each series' robust band as a strip and names it in the
// legend with its threshold, and that bands.csv and bands.json are written beside the PNGs.
TEST(PlotLegend, LinePlotDrawsRobustBands) {
  const ScratchDir dir;
  const std::string csv = LongKeyResults(dir);
  SweepLayout layout = LongKeyLayout();
  SweepPlot line;
  line.metric = "residual_ratio";
  line.x = "machine.modes[0].frequency_hz";
  line.series = "controller.pattern";
  layout.plots = {line};
  ::testing::internal::CaptureStderr();
  const std::string svg = SweepPlotSvg(layout, line, csv);
  const std::vector<std::string> written = WriteSweepPlots(dir.File(""), layout, csv);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(HasText(svg, "robust bands &lt;= 0.05 (strips)")) << svg;  // as SVG escapes it
  ASSERT_EQ(written.size(), 3u);
  const nlohmann::json json = nlohmann::json::parse(testing::ReadText(written[2]));
  ASSERT_EQ(json.at("bands").size(), 3u);
  EXPECT_EQ(json["bands"][0]["value"], kPatterns[0]);
  EXPECT_EQ(json["bands"][0]["threshold"], 0.05);
  EXPECT_TRUE(json["bands"][0]["design"].is_null());
  EXPECT_EQ(json["bands"][0]["intervals"][0]["from"], 22.5);
  EXPECT_EQ(json["bands"][0]["intervals"][0]["to"], 27.5);
  EXPECT_EQ(json["bands"][0]["intervals"][0]["contains_design"], false);
  EXPECT_EQ(testing::ReadText(written[1]),
            "metric,x,series,value,threshold,design,rank,from,to,contains_design\n"
            "residual_ratio,machine.modes[0].frequency_hz,controller.pattern,\"" + kPatterns[0] +
                "\",0.05,,1,22.5,27.5,0\n"
                "residual_ratio,machine.modes[0].frequency_hz,controller.pattern,\"" + kPatterns[1] +
                "\",0.05,,1,25,25,0\n"
                "residual_ratio,machine.modes[0].frequency_hz,controller.pattern,\"" + kPatterns[2] +
                "\",0.05,,1,25,25,0\n");
}

// Tests that compare's deflection overlay with a long --candidate-set label keeps the
// label's start in the legend, tagged, the whole label in the caption, and no warning.
TEST(PlotLegend, OverlayCutsLongRunLabels) {
  RunResult run;
  for (int i = 0; i <= 100; ++i) {
    run.trace.time_s.push_back(0.01 * i);
    run.trace.deflection_m.push_back(1e-6 * std::sin(0.3 * i));
    run.trace.command_accel_m_s2.push_back(0.0);
  }
  run.metrics.static_displacement_m = 1e-6;
  const Scenario scenario;
  const std::string long_label =
      "candidate: configs/scenarios/sdof_method1.yaml --set controller.pattern={method: ei, mode: both, "
      "frequency_hz: 25, design_damping_ratio: 0.02, vibration_tolerance: 0.03}";
  const std::vector<OverlaidRun> runs = {{&run, &scenario, "baseline", "baseline: configs/demo.yaml"},
                                         {&run, &scenario, "candidate", long_label}};
  ::testing::internal::CaptureStderr();
  const std::string svg = DeflectionOverlaySvg(runs, "deflection");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(HasText(svg, "baseline: configs/demo.yaml"));
  EXPECT_NE(svg.find(">[1] candidate: configs/scenarios/"), std::string::npos) << svg;
  EXPECT_TRUE(HasText(svg, "[1] " + long_label));
}

// Tests that a series value that is no mapping keeps its text and a title no longer than
// the key allows stays whole, while mappings are told apart by their differing entries
// (all of them when none differs) and a cut title never splits a UTF-8 character.
TEST(PlotLegend, DifferingPartsAndCuts) {
  EXPECT_EQ(DifferingParts({"zv", "zvd"}), (std::vector<std::string>{"zv", "zvd"}));
  EXPECT_EQ(DifferingParts({"{method: zv, frequency_hz: 25}", "{method: zvd, frequency_hz: 25}"}),
            (std::vector<std::string>{"method: zv", "method: zvd"}));
  EXPECT_EQ(DifferingParts({"{method: zv}", "{method: zv}"}), (std::vector<std::string>{"method: zv", "method: zv"}));
  EXPECT_EQ(DifferingParts({"{method: zv}", "{method: zv, k1: 0.6}"}),
            (std::vector<std::string>{"", "k1: 0.6"}));
  const FittedLegend legend = FitLegend({"short", std::string(40, 'x') + "é"}, {"short", "full"});
  EXPECT_EQ(legend.titles[0], "short");
  EXPECT_EQ(legend.titles[1], "[1] " + std::string(kMaxLegendChars - 5, 'x') + "…");
  EXPECT_EQ(legend.caption, (std::vector<std::string>{"[1] full"}));
  const FittedLegend utf8 = FitLegend({std::string(30, 'y') + "ééééééééééé"}, {"f"});
  EXPECT_EQ(utf8.titles[0], "[1] " + std::string(30, 'y') + "é…");
}

}  // namespace
}  // namespace shapebench::bench
