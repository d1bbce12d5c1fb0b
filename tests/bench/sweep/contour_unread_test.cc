// A sweep's point computes only what its row reads: without max_contour_error_m among its
// columns, the closed form skips the contour error's samples (ContourUnreadScope,
// bench/run/closed_form_sampler.h) and every other metric stays the same bit for bit.
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/closed_form_sampler.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/metrics.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench::contour_unread_test {
namespace {

using testing::DataPath;
using testing::ReadText;
using testing::ScratchDir;

// results.csv's lines split at commas (numbers and plain words: no quoting).
std::vector<std::vector<std::string>> CsvCells(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    std::string cell;
    while (std::getline(fields, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// Tests that under ContourUnreadScope the closed form reports max_contour_error_m n/a and
// every other metric as a run without the scope, bit for bit, over the sweeps' natural
// periods (every 0.5 Hz and a few between), undamped and damped (the unread path steps the
// ticks near the line's ends in its own loop and refuses them by a cheaper test: the same
// ticks must jump); and that the scope ends with its block.
TEST(ContourUnread, OtherMetricsBitForBitContourNa) {
  std::vector<double> frequencies = {19.3, 31.7};
  for (int i = 0; i <= 40; ++i) frequencies.push_back(15.0 + 0.5 * i);
  int overshooting = 0;  // runs whose tool leaves the line (0 where the pattern leaves none)
  for (const double hz : frequencies) {
    for (const double zeta : {0.0, 0.02, 0.3}) {
      const Scenario scenario = testing::SdofScenario(hz, zeta);
      const RunResult all = RunScenario(scenario, RunOptions{false});
      RunResult unread;
      {
        const ContourUnreadScope scope(true);
        unread = RunScenario(scenario, RunOptions{false});
      }
      ASSERT_TRUE(unread.single_mode) << hz;
      if (all.metrics.max_contour_error_m > 0.0) ++overshooting;
      EXPECT_TRUE(std::isnan(unread.metrics.max_contour_error_m)) << hz << " Hz, zeta " << zeta;
      for (const MetricInfo& info : MetricTable()) {
        if (info.field == &Metrics::max_contour_error_m) continue;
        const double a = all.metrics.*info.field;
        const double b = unread.metrics.*info.field;
        EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << info.name << " at " << hz << " Hz, zeta " << zeta;
      }
      EXPECT_EQ(RunScenario(scenario, RunOptions{false}).metrics.max_contour_error_m, all.metrics.max_contour_error_m);
    }
  }
  EXPECT_GE(overshooting, 120);  // of 129: the contour error was read and nonzero
}

// Tests that a sweep listing max_contour_error_m writes it in every row, and that the same
// sweep without it writes the other columns byte for byte the same.
TEST(ContourUnread, SweepRowsWithAndWithoutTheContourColumn) {
  ScratchDir dir;
  const std::string grid = "base: " + DataPath("sweeps/sdof_method1.yaml") +
                           "\ngrid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 21}\n"
                           "  machine.modes[0].damping_ratio: [0, 0.02]\nplots: []\n";
  const auto results = [&](const std::string& name, const std::string& metrics) {
    const Sweep sweep = LoadSweep(dir.Write(name + ".yaml", grid + "metrics: [" + metrics + "]\n"), {});
    SweepRunOptions options;
    options.out_dir = dir.File(name);
    options.jobs = 1;
    EXPECT_EQ(RunSweep(sweep, {}, options).ok, sweep.points) << name;
    return CsvCells(ReadText(dir.File(name) + "/results.csv"));
  };
  const auto with = results("with", "peak_ratio, max_contour_error_m, residual_ratio");
  const auto without = results("without", "peak_ratio, residual_ratio");
  ASSERT_EQ(with.size(), 43u);  // the header and 42 points
  ASSERT_EQ(without.size(), with.size());
  // Columns: point, the two keys, the metrics, status, error.
  ASSERT_EQ(with[0][4], "max_contour_error_m");
  int positive = 0;  // 0 where the pattern leaves no overshoot at the line's ends
  for (std::size_t r = 1; r < with.size(); ++r) {
    ASSERT_GE(with[r].size(), 7u) << r;
    ASSERT_GE(without[r].size(), 6u) << r;
    ASSERT_FALSE(with[r][4].empty()) << "row " << r;
    if (std::stod(with[r][4]) > 0.0) ++positive;
    EXPECT_EQ(with[r][3], without[r][3]) << "peak_ratio, row " << r;
    EXPECT_EQ(with[r][5], without[r][4]) << "residual_ratio, row " << r;
  }
  EXPECT_GE(positive, 36);
}

}  // namespace
}  // namespace shapebench::bench::contour_unread_test
