// What the plots show and how they are named: run titles, plots left out when they would
// show nothing, sweep plot file names and log axes. The gnuplot scripts are read through
// a `gnuplot` on PATH that keeps a copy of its input and hands it to the real one.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/output/gnuplot.h"
#include "bench/output/report.h"
#include "bench/sweep/sweep_plot.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::DataPath;
using testing::ReadText;
using testing::RunCli;
using testing::ScratchDir;
using testing::ShellQuoted;


// A directory with a `gnuplot` that appends its script to SCRIPTS and runs the real
// gnuplot on it; returns the RunCli wrapper that puts it first on PATH.
std::string ScriptCopyingGnuplot(const ScratchDir& dir) {
  std::string real = "/usr/bin/gnuplot";
  const std::string paths = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  for (std::size_t from = 0; from <= paths.size();) {
    const std::size_t to = std::min(paths.find(':', from), paths.size());
    const std::string candidate = paths.substr(from, to - from) + "/gnuplot";
    if (to > from && access(candidate.c_str(), X_OK) == 0) {
      real = candidate;
      break;
    }
    from = to + 1;
  }
  const std::string bin = dir.Write("bin/gnuplot", "#!/bin/sh\ntee -a " + ShellQuoted(dir.File("scripts.gp")) +
                                                       " | " + ShellQuoted(real) + "\n");
  std::filesystem::permissions(bin, std::filesystem::perms::owner_all);
  return "PATH=" + ShellQuoted(dir.File("bin")) + ":\"$PATH\" ";
}

// Tests that a plot's file name takes each key's shortest dotted suffix that no other key
// of the sweep ends with: frequency_hz alone when unique, modes[0].frequency_hz (as
// modes_0_) when the pattern's frequency_hz is also swept.
TEST(PlotOutputs, FileNamesUseShortestUniqueKeySuffix) {
  SweepPlot plot;
  plot.metric = "residual_ratio";
  plot.x = "machine.modes[0].frequency_hz";
  plot.series = "controller.pattern.method";
  const std::vector<std::string> unique = {"machine.modes[0].frequency_hz", "controller.pattern.method"};
  EXPECT_EQ(SweepPlotFileName(plot, unique), "residual_ratio-vs-frequency_hz-by-method.png");
  const std::vector<std::string> clash = {"machine.modes[0].frequency_hz", "controller.pattern.method",
                                          "controller.pattern.frequency_hz"};
  EXPECT_EQ(SweepPlotFileName(plot, clash), "residual_ratio-vs-modes_0_.frequency_hz-by-method.png");
  EXPECT_EQ(ShortKey("controller.pattern.frequency_hz", clash), "pattern.frequency_hz");
  // A key that is itself a suffix of another keeps its whole name.
  EXPECT_EQ(ShortKey("b.c", {"a.b.c", "b.c"}), "b.c");
  EXPECT_EQ(ShortKey("a.b.c", {"a.b.c", "b.c"}), "a.b.c");
  SweepPlot heat;
  heat.metric = "peak_ratio";
  heat.heatmap_x = "machine.modes[0].frequency_hz";
  heat.heatmap_y = "controller.accel_time_s";
  EXPECT_EQ(SweepPlotFileName(heat, {"machine.modes[0].frequency_hz", "controller.accel_time_s"}),
            "peak_ratio-over-frequency_hz-and-accel_time_s.png");
}

// Tests that a run's plot title names the scenario, its pattern method and every --set
// option, a long value shortened with "...".
TEST(PlotOutputs, RunTitleCarriesMethodAndOverrides) {
  const std::vector<Override> overrides = ParseOverrides(
      {"controller.pattern.method=none", "controller.pattern.frequency_hz=25." + std::string(60, '0')});
  const Scenario scenario = LoadScenario(DataPath("shaped_method1.yaml"), overrides);
  const std::string title = RunPlotTitle(scenario, overrides);
  EXPECT_EQ(title.rfind(scenario.name + ", method none, --set controller.pattern.method=none "
                        "controller.pattern.frequency_hz=25.000", 0),
            0u)
      << title;
  EXPECT_NE(title.find("..."), std::string::npos) << title;
  EXPECT_EQ(title.find(std::string(30, '0')), std::string::npos) << title;
  const Scenario plain = LoadScenario(DataPath("shaped_method1.yaml"), {});
  EXPECT_EQ(RunPlotTitle(plain, {}), plain.name + ", method 1");
}

// Tests that `run --out` of a straight one-axis move writes no path.png and says so, and
// that the deflection plot's script carries the title with the method and the --set
// option and marks the peak, the residual and the motion's end.
TEST(PlotOutputs, SingleAxisMoveHasNoPathPlot) {
  ScratchDir dir;
  const std::string path = ScriptCopyingGnuplot(dir);
  const CliResult r = RunCli({"run", DataPath("shaped_method1.yaml"), "--set", "controller.pattern.method=none",
                              "--out", dir.File("out")},
                             kSourceDir, path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/path.png")));
  EXPECT_NE(r.err.find("no path.png: the programmed path is a straight move along one axis"), std::string::npos)
      << r.err;
  EXPECT_EQ(PngDefect(dir.File("out/deflection.png")), "");
  const std::string script = ReadText(dir.File("scripts.gp"));
  EXPECT_NE(script.find("set title 'shaped_method1, method none, --set controller.pattern.method=none'"),
            std::string::npos)
      << script.substr(0, 400);
  EXPECT_NE(script.find("set label 'peak "), std::string::npos);
  EXPECT_NE(script.find("set label 'residual "), std::string::npos);
  EXPECT_NE(script.find("set label 'motion end "), std::string::npos);

  const CliResult xy = RunCli({"run", DataPath("shaped_method1_xy.yaml"), "--out", dir.File("xy")}, kSourceDir);
  ASSERT_EQ(xy.exit_code, 0) << xy.err;
  EXPECT_EQ(PngDefect(dir.File("xy/path.png")), "");
  EXPECT_EQ(xy.err.find("no path.png"), std::string::npos) << xy.err;
}

// Tests that the stabilisation diagram of `identify --out` labels its right axis with the
// FRF's unit and log scale and ticks it as 1e-08 (not 0.00000001, which pushed the label
// off the page), and that gnuplot says nothing on stderr.
TEST(PlotOutputs, StabilisationRightAxisHasItsUnit) {
  ScratchDir dir;
  const std::string path = ScriptCopyingGnuplot(dir);
  const CliResult r = RunCli({"identify", "configs/measurements/column_y_accelerance.uff", "--out", dir.File("out")},
                             kSourceDir, path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(PngDefect(dir.File("out/stabilisation.png")), "");
  const std::string script = ReadText(dir.File("scripts.gp"));
  EXPECT_TRUE(std::regex_search(script, std::regex("set y2label '\\|H\\| \\[[^\\]]+\\], log scale'")))
      << script.substr(0, 800);
  EXPECT_NE(script.find("set format y2 '%g'"), std::string::npos);
  EXPECT_EQ(r.err.find("arning"), std::string::npos) << r.err;
}

// Tests that `run --out` on a rigid machine (no states, deflection identically 0) writes
// no deflection.png and says so instead.
TEST(PlotOutputs, RigidMachineHasNoDeflectionPlot) {
  ScratchDir dir;
  std::string yaml = ReadText(DataPath("shaped_method1_xy.yaml"));
  const std::size_t from = yaml.find("machine:");
  const std::size_t to = yaml.find("drive:");
  yaml.replace(from, to - from, "machine: {axes: {}, driven_axis: y}\n");
  const std::string scenario = dir.Write("rigid.yaml", yaml);
  const CliResult r = RunCli({"run", scenario, "--out", dir.File("out")}, kSourceDir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/deflection.png")));
  EXPECT_NE(r.err.find("no deflection.png: the deflection is identically 0"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/metrics.json")));
  EXPECT_EQ(PngDefect(dir.File("out/path.png")), "");  // the L-shaped path still has its plot
}

// Tests that a sweep plot's `log: true` puts the metric's axis (a heat map's colour
// scale) in log, `log: false` keeps it linear although the ratio spans many decades, and
// that a `log:` that is no boolean is refused naming the key.
TEST(PlotOutputs, SweepLogAxesAsAsked) {
  ScratchDir dir;
  const std::string path = ScriptCopyingGnuplot(dir);
  dir.Write("base.yaml", ReadText(DataPath("shaped_method1.yaml")));
  const std::string head =
      "base: base.yaml\ngrid:\n  machine.modes[0].frequency_hz: {from: 20, to: 30, steps: 11}\n"
      "  controller.accel_time_s: [0.05, 0.1]\nmetrics: [residual_ratio, motion_time_s]\nplots:\n";
  const std::string logged = dir.Write(
      "log.yaml", head +
                      "  - {metric: motion_time_s, x: \"machine.modes[0].frequency_hz\", log: true}\n"
                      "  - {metric: residual_ratio, heatmap: [\"machine.modes[0].frequency_hz\", controller.accel_time_s], "
                      "log: true}\n");
  const CliResult a = RunCli({"sweep", logged, "--out", dir.File("a")}, dir.path().string(), path);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(PngDefect(dir.File("a/motion_time_s-vs-frequency_hz.png")), "");
  EXPECT_EQ(PngDefect(dir.File("a/residual_ratio-over-frequency_hz-and-accel_time_s.png")), "");
  const std::string scripts = ReadText(dir.File("scripts.gp"));
  EXPECT_NE(scripts.find("set logscale y\n"), std::string::npos);
  EXPECT_NE(scripts.find("set logscale cb\n"), std::string::npos);

  std::filesystem::remove(dir.File("scripts.gp"));
  const std::string linear = dir.Write(
      "linear.yaml", head + "  - {metric: residual_ratio, x: \"machine.modes[0].frequency_hz\", log: false}\n");
  const CliResult b = RunCli({"sweep", linear, "--out", dir.File("b")}, dir.path().string(), path);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string linear_script = ReadText(dir.File("scripts.gp"));
  EXPECT_NE(linear_script.find("set ylabel"), std::string::npos);
  EXPECT_EQ(linear_script.find("logscale"), std::string::npos);

  const std::string bad = dir.Write(
      "bad.yaml", head + "  - {metric: residual_ratio, x: \"machine.modes[0].frequency_hz\", log: maybe}\n");
  const CliResult c = RunCli({"sweep", bad, "--out", dir.File("c")}, dir.path().string());
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_NE(c.err.find("log"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("expected one of true|false"), std::string::npos) << c.err;
}

// Tests that a ratio metric whose values span more than two decades gets a log axis by
// default, and one that spans less, or a metric that is no ratio, does not.
TEST(PlotOutputs, RatioSpanningDecadesDefaultsToLog) {
  SweepPlot plot;
  plot.metric = "residual_ratio";
  EXPECT_TRUE(LogMetricAxis(plot, {1e-4, 0.5, 2.0}));
  EXPECT_FALSE(LogMetricAxis(plot, {0.02, 0.5, 1.5}));
  EXPECT_FALSE(LogMetricAxis(plot, {0.0, 0.5, 1.5}));  // zeros are no decades
  plot.log = false;
  EXPECT_FALSE(LogMetricAxis(plot, {1e-4, 0.5, 2.0}));
  plot.log = true;
  EXPECT_TRUE(LogMetricAxis(plot, {0.5, 1.0}));
  SweepPlot time;
  time.metric = "motion_time_s";
  EXPECT_FALSE(LogMetricAxis(time, {1e-4, 0.5, 2.0}));
}

}  // namespace
}  // namespace shapebench::bench
