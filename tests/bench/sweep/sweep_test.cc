// Sweep files (bench/sweep/sweep.h): grid expansion, point overrides, errors located at
// FILE:LINE:COL, the CSV helpers and the ordered worker pool (bench/sweep/sweep_runner.h).
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "common/ordered_pool.h"
#include "common/csv.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "tests/support/bench_test_support.h"
#include "bench/sweep/sweep_layout.h"
#include "tests/support/sweep_file.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;

using testing::SweepFile;

std::vector<std::string> Texts(const Sweep& sweep, std::uint64_t point) {
  return MakePoint(sweep, point, {}).texts;
}

// Tests that a linear range has `steps` values from `from` to `to` inclusive, each written
// in its short decimal form and equal to from + i (to - from) / (steps - 1).
TEST(SweepGrid, LinearRange) {
  const Sweep sweep =
      SweepFile("grid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 201}\n").Load();
  ASSERT_EQ(sweep.points, 201u);
  EXPECT_EQ(Texts(sweep, 0), std::vector<std::string>{"15"});
  EXPECT_EQ(Texts(sweep, 1), std::vector<std::string>{"15.1"});
  EXPECT_EQ(Texts(sweep, 3), std::vector<std::string>{"15.3"});
  EXPECT_EQ(Texts(sweep, 200), std::vector<std::string>{"35"});
  for (std::uint64_t i = 0; i < sweep.points; ++i) {
    const double value = std::strtod(Texts(sweep, i)[0].c_str(), nullptr);
    EXPECT_NEAR(value, 15.0 + 0.1 * static_cast<double>(i), 1e-12) << i;
    EXPECT_LE(Texts(sweep, i)[0].size(), 4u) << Texts(sweep, i)[0];  // "15.1", never 15.100000000000001
  }
}

// Tests that `spacing: log` spaces the values evenly in log (a decade per step here) and
// keeps the ends exactly as written; steps 1 gives `from` alone.
TEST(SweepGrid, LogRangeAndSingleStep) {
  const Sweep sweep = SweepFile(
                          "grid:\n"
                          "  controller.feed_mm_min: {from: 10, to: 10000, steps: 4, spacing: log}\n"
                          "  controller.accel_time_s: {from: 0.25, to: 0.25, steps: 1}\n")
                          .Load();
  ASSERT_EQ(sweep.points, 4u);
  EXPECT_TRUE(sweep.axes[0].keys[0].log());
  const std::vector<std::string> expected = {"10", "100", "1000", "10000"};
  for (std::uint64_t i = 0; i < 4; ++i) {
    EXPECT_EQ(Texts(sweep, i), (std::vector<std::string>{expected[i], "0.25"})) << i;
  }
}

// Tests that list values are used as written: plain scalars as their text, quoted ones
// quoted in the override, mappings in flow style.
TEST(SweepGrid, ListValuesAsWritten) {
  const Sweep sweep = SweepFile(
                          "grid:\n"
                          "  controller.pattern: [{method: 3, k1: 0.6}, {method: none}]\n"
                          "  controller.feed_mm_min: [6000, 1.20e4, \"3000\"]\n")
                          .Load();
  ASSERT_EQ(sweep.points, 6u);
  const SweepPoint first = MakePoint(sweep, 0, {});
  EXPECT_EQ(first.texts, (std::vector<std::string>{"{method: 3, k1: 0.6}", "6000"}));
  EXPECT_EQ(first.overrides[0].value_yaml, "{method: 3, k1: 0.6}");
  EXPECT_EQ(MakePoint(sweep, 1, {}).texts[1], "1.20e4");
  const SweepPoint quoted = MakePoint(sweep, 2, {});
  EXPECT_EQ(quoted.texts[1], "3000");
  EXPECT_EQ(quoted.overrides[1].value_yaml, "\"3000\"");
}

// Tests the order of the points: axes in the order written, the last varying fastest, a
// zip group one axis at its place with its keys moving together; the command line's
// --set options follow the point's overrides.
TEST(SweepGrid, OrderLastKeyFastestZipOneAxis) {
  const Sweep sweep = SweepFile(
                          "grid:\n"
                          "  controller.pattern.method: [1, 3]\n"
                          "  zip:\n"
                          "    controller.feed_mm_min: [6000, 12000]\n"
                          "    controller.accel_time_s: {from: 0.1, to: 0.2, steps: 2}\n"
                          "  machine.modes[0].frequency_hz: [20, 25, 30]\n")
                          .Load();
  ASSERT_EQ(sweep.points, 12u);
  EXPECT_EQ(sweep.Keys(), (std::vector<std::string>{"controller.pattern.method", "controller.feed_mm_min",
                                                     "controller.accel_time_s",
                                                     "machine.modes[0].frequency_hz"}));
  EXPECT_EQ(Texts(sweep, 0), (std::vector<std::string>{"1", "6000", "0.1", "20"}));
  EXPECT_EQ(Texts(sweep, 1), (std::vector<std::string>{"1", "6000", "0.1", "25"}));
  EXPECT_EQ(Texts(sweep, 3), (std::vector<std::string>{"1", "12000", "0.2", "20"}));
  EXPECT_EQ(Texts(sweep, 11), (std::vector<std::string>{"3", "12000", "0.2", "30"}));
  EXPECT_EQ(sweep.AxisIndices(10), (std::vector<std::uint64_t>{1, 1, 1}));
  const SweepPoint point = MakePoint(sweep, 5, {Override{"move.distance_mm", "150"}});
  ASSERT_EQ(point.overrides.size(), 5u);
  EXPECT_EQ(point.overrides[2].key_path, "controller.accel_time_s");
  EXPECT_EQ(point.overrides[4].key_path, "move.distance_mm");
  EXPECT_EQ(point.Label(),
            "controller.pattern.method=1, controller.feed_mm_min=12000, "
            "controller.accel_time_s=0.2, machine.modes[0].frequency_hz=30");
}

// Tests that metrics default to every metric in Metrics::Named() order, and that a
// metrics: list is kept in the order written.
TEST(SweepGrid, MetricsKept) {
  const Sweep all = SweepFile("grid:\n  controller.feed_mm_min: [6000]\n").Load();
  std::vector<std::string> names;
  for (const auto& named : Metrics{}.Named()) names.push_back(named.first);
  EXPECT_EQ(all.metrics, names);
  const Sweep some =
      SweepFile("grid:\n  controller.feed_mm_min: [6000]\nmetrics: [residual_ratio, peak_ratio]\n").Load();
  EXPECT_EQ(some.metrics, (std::vector<std::string>{"residual_ratio", "peak_ratio"}));
  EXPECT_EQ(ResultColumns(some), (std::vector<std::string>{"point", "controller.feed_mm_min",
                                                            "residual_ratio", "peak_ratio", "status",
                                                            "error"}));
}

struct ErrorCase {
  std::string name;
  std::string body;  // after the base: line (line 1)
  int line;
  int column;
  std::string key_path;
  std::string message;  // a part of it
};

// Tests that the robust bands' threshold is a ratio metric's max check, else the sweep's
// band_threshold:, else its 5% level; that a checked ratio metric not plotted gets a band
// along the first line plot's keys, and a metric that is no ratio none.
TEST(SweepBands, ThresholdFromCheckThenBandThresholdThenFivePercent) {
  const std::string grid =
      "grid:\n  controller.pattern.method: [none, 1]\n  machine.modes[0].frequency_hz: [20, 25, 30]\n"
      "plots:\n  - {metric: residual_ratio, x: \"machine.modes[0].frequency_hz\", series: controller.pattern.method}\n"
      "  - {metric: peak_ratio, x: \"machine.modes[0].frequency_hz\", series: controller.pattern.method}\n"
      "  - {metric: motion_time_s, x: \"machine.modes[0].frequency_hz\"}\n";
  const SweepFile plain(grid);
  const std::vector<BandSpec> five = SweepLayout::Of(plain.Load()).bands;
  ASSERT_EQ(five.size(), 2u);
  EXPECT_EQ(five[0].metric, "residual_ratio");
  EXPECT_EQ(five[0].series, "controller.pattern.method");
  EXPECT_DOUBLE_EQ(five[0].threshold, 0.05);
  EXPECT_DOUBLE_EQ(five[1].threshold, 1.05);
  const SweepFile mixed(grid + "band_threshold: 0.02\nchecks: {peak_ratio: {max: 1.2}, cruise_residual_ratio: {max: 0.1}}\n");
  const std::vector<BandSpec> bands = SweepLayout::Of(mixed.Load()).bands;
  ASSERT_EQ(bands.size(), 3u);
  EXPECT_DOUBLE_EQ(bands[0].threshold, 0.02);  // band_threshold: no check on residual_ratio
  EXPECT_DOUBLE_EQ(bands[1].threshold, 1.2);   // the check's max
  EXPECT_EQ(bands[2].metric, "cruise_residual_ratio");
  EXPECT_EQ(bands[2].x, "machine.modes[0].frequency_hz");
  EXPECT_DOUBLE_EQ(bands[2].threshold, 0.1);
}

// Tests that every error in a sweep file is a ConfigError at its FILE:LINE:COL with the
// key path and a message that says what is allowed.
TEST(SweepFileErrors, LocatedAtFileLineColumn) {
  const std::vector<ErrorCase> cases = {
      {"unknown top-level key", "grid: {controller.feed_mm_min: [1]}\nbogus: 1\n", 3, 1, "bogus",
       "unknown key 'bogus'; allowed: name, base, grid, metrics, plots, checks"},
      {"steps below 1", "grid:\n  controller.feed_mm_min: {from: 1, to: 2, steps: 0}\n", 3, 51,
       "grid.controller.feed_mm_min.steps", "must be at least 1"},
      {"from not a number", "grid:\n  controller.feed_mm_min: {from: abc, to: 2, steps: 3}\n", 3, 34,
       "grid.controller.feed_mm_min.from", "expected a number, got 'abc'"},
      {"to missing", "grid:\n  controller.feed_mm_min: {from: 1, steps: 3}\n", 3, 27,
       "grid.controller.feed_mm_min", "a range needs from, to and steps; 'to' is missing"},
      {"zip lists of unequal length",
       "grid:\n  zip:\n    controller.feed_mm_min: [6000, 12000]\n"
       "    controller.accel_time_s: [0.1, 0.2, 0.3]\n",
       5, 30, "grid.zip.controller.accel_time_s", "'controller.feed_mm_min' has 2, this one 3"},
      {"unknown metric", "grid:\n  controller.feed_mm_min: [6000]\nmetrics: [peak_ratio, peak_ratioo]\n",
       4, 23, "metrics[1]", "unknown metric 'peak_ratioo'; allowed: static_displacement_m"},
      {"plot key not in the grid",
       "grid:\n  controller.feed_mm_min: [6000]\nplots:\n  - {metric: peak_ratio, x: controller.accel_time_s}\n",
       5, 29, "plots[0].x", "'controller.accel_time_s' is not a key of the grid; grid keys: "},
      {"plot metric not kept",
       "grid:\n  controller.feed_mm_min: [6000]\nmetrics: [peak_ratio]\nplots:\n"
       "  - {metric: residual_ratio, x: controller.feed_mm_min}\n",
       6, 14, "plots[0].metric", "is not kept; add it to metrics:"},
      {"series on the x axis' zip",
       "grid:\n  zip:\n    controller.feed_mm_min: [1, 2]\n    controller.accel_time_s: [0.1, 0.2]\n"
       "plots:\n  - {metric: peak_ratio, x: controller.feed_mm_min, series: controller.accel_time_s}\n",
       7, 61, "plots[0].series", "moves with 'controller.feed_mm_min'"},
      {"not a key path", "grid:\n  controller..feed: [1]\n", 3, 3, "grid.controller..feed", "not a key path"},
      {"band_threshold not above 0", "grid:\n  controller.feed_mm_min: [6000]\nband_threshold: -1\n", 4, 17,
       "band_threshold", "expected a number > 0 (the level of the robust bands"},
      {"a scalar instead of values", "grid:\n  controller.feed_mm_min: 6000\n", 3, 27,
       "grid.controller.feed_mm_min", "expected a list of values [a, b, ...] or a range"},
      {"empty grid", "grid: {}\n", 2, 7, "grid", "expected at least one key"},
      {"key swept twice", "grid:\n  zip:\n    controller.feed_mm_min: [1]\n  controller.feed_mm_min: [2]\n",
       5, 27, "grid.controller.feed_mm_min", "swept twice"},
      {"a key inside a swept key", "grid:\n  controller.pattern: [{method: 1}]\n  controller.pattern.method: [1]\n",
       4, 30, "grid.controller.pattern.method", "overlaps 'controller.pattern'"},
      {"log spacing from 0", "grid:\n  controller.feed_mm_min: {from: 0, to: 2, steps: 3, spacing: log}\n", 3,
       34, "grid.controller.feed_mm_min.from", "log spacing needs from > 0"},
      {"index out of range in the base", "grid:\n  machine.modes[3].frequency_hz: [20, 30]\n", 3, 35,
       "machine.modes[3].frequency_hz", "index 3 is out of range: 'machine.modes' has 1 element"},
      {"not a scenario key", "grid:\n  controller.feed_rate: [6000]\n", 3, 26, "controller.feed_rate",
       "unknown key 'feed_rate'; allowed: period_s, feed_mm_min"},
      {"grid too large", "grid:\n  controller.feed_mm_min: {from: 1, to: 2, steps: 2000}\n"
                         "  controller.accel_time_s: {from: 0.1, to: 0.2, steps: 1001}\n",
       3, 3, "grid", "the grid has 2,002,000 points, more than the 2,000,000 a sweep runs without --force"},
  };
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.name);
    const SweepFile file(c.body);
    try {
      file.Load();
      ADD_FAILURE() << "no error";
    } catch (const ConfigError& error) {
      EXPECT_EQ(error.file(), file.path());
      EXPECT_EQ(error.line(), c.line) << error.what();
      EXPECT_EQ(error.column(), c.column) << error.what();
      EXPECT_EQ(error.key_path(), c.key_path) << error.what();
      EXPECT_NE(error.message().find(c.message), std::string::npos) << error.what();
      EXPECT_EQ(std::string(error.what()).rfind(file.path() + ":" + std::to_string(c.line) + ":" +
                                                    std::to_string(c.column) + ": " + c.key_path + ": ",
                                                0),
                0u)
          << error.what();
    }
  }
}

// Tests that --force lets a grid above the limit load, and that a --set on a swept key
// is refused at --set:N:1.
TEST(SweepFileErrors, ForceAndSetOnSweptKey) {
  const SweepFile big("grid:\n  controller.feed_mm_min: {from: 1000, to: 2000, steps: 2000}\n"
                      "  controller.accel_time_s: {from: 0.1, to: 0.2, steps: 1001}\n");
  SweepLoadOptions force;
  force.force = true;
  EXPECT_EQ(big.Load({}, force).points, 2'002'000u);

  const SweepFile file("grid:\n  controller.feed_mm_min: [6000]\n");
  try {
    file.Load({Override{"move.distance_mm", "150"}, Override{"controller.feed_mm_min", "5"}});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("--set:2:1: controller.feed_mm_min: ", 0), 0u) << error.what();
  }
}

// Tests that a point's invalid value (method 4 with t1 > T/6) is that point's error,
// located at the value in the sweep file, while the other points run.
TEST(SweepPoints, InvalidValueIsThePointsLocatedError) {
  const SweepFile file("grid:\n  controller.pattern.t1_s: [0.004, 0.009]\n");
  const std::vector<Override> sets = {Override{"controller.pattern.method", "4"}};
  const Sweep sweep = file.Load(sets);
  const PointOutcome good = RunPoint(sweep, sets, 0);
  ASSERT_TRUE(good.ok()) << good.error;
  EXPECT_LT(good.metrics.residual_ratio, 1e-3);
  const PointOutcome bad = RunPoint(sweep, sets, 1);
  EXPECT_EQ(bad.status, PointOutcome::Status::kBadInput);
  EXPECT_EQ(bad.error.rfind(file.path() + ":3:36: controller.pattern.t1_s: must be in [0, T/6]", 0), 0u)
      << bad.error;
  EXPECT_TRUE(std::isnan(bad.metrics.peak_ratio));
}

// Tests that the hash that ties shards and resumed runs together changes with the grid,
// the --set options and the kept metrics, and with nothing else.
TEST(SweepPoints, HashFollowsWhatResultsDependOn) {
  const SweepFile a("grid:\n  controller.feed_mm_min: [6000, 12000]\n");
  const SweepFile same("grid:\n  controller.feed_mm_min: [6000, 12000]\nplots: []\n");
  const SweepFile other_grid("grid:\n  controller.feed_mm_min: [6000, 12001]\n");
  const SweepFile other_metrics("grid:\n  controller.feed_mm_min: [6000, 12000]\nmetrics: [peak_ratio]\n");
  const std::string hash = SweepHash(a.Load(), {});
  EXPECT_EQ(hash.size(), 16u);
  EXPECT_EQ(SweepHash(same.Load(), {}), hash);
  EXPECT_NE(SweepHash(other_grid.Load(), {}), hash);
  EXPECT_NE(SweepHash(other_metrics.Load(), {}), hash);
  EXPECT_NE(SweepHash(a.Load(), {Override{"move.distance_mm", "150"}}), hash);
}

// Tests that the shipped sweeps load (the natural-period one has 3 x 201 points).
TEST(SweepPoints, ShippedSweepsLoad) {
  const std::string dir = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/sweeps";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    EXPECT_TRUE(IsSweepFile(entry.path().string()));
    EXPECT_NO_THROW(LoadSweep(entry.path().string(), {}));
    ++files;
  }
  EXPECT_GE(files, 1);
  EXPECT_EQ(LoadSweep(dir + "/natural_period.yaml", {}).points, 603u);
  EXPECT_FALSE(IsSweepFile(DataPath("sweeps/sdof_method1.yaml")));
}

// Tests RFC 4180 quoting: fields with commas, quotes or newlines are quoted, quotes
// doubled, and the reader gives back exactly the fields written.
TEST(SweepCsv, QuotingRoundTrip) {
  EXPECT_EQ(CsvField("plain"), "plain");
  EXPECT_EQ(CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
  const std::vector<std::string> fields = {"1", "", "x.yaml:3:5: k: got \"6,000\", expected [0, 1]",
                                           "line\r\nbreak", "end"};
  const std::string record = CsvRecord(fields);
  std::istringstream in(record + record);
  CsvReader reader(in);
  std::vector<std::string> read;
  ASSERT_TRUE(reader.Next(&read));
  EXPECT_EQ(read, fields);
  EXPECT_EQ(reader.offset(), record.size());
  ASSERT_TRUE(reader.Next(&read));
  EXPECT_EQ(read, fields);
  EXPECT_FALSE(reader.Next(&read));
  EXPECT_FALSE(reader.torn());
}

// Tests that a record cut short (inside a quoted field, or without its final newline)
// is reported torn and not returned, and offset() stays at the last complete record.
TEST(SweepCsv, TornRecordIsNotTrusted) {
  const std::string whole = CsvRecord({"0", "ok", ""});
  for (const std::string& tail : {std::string("1,error,\"a, b\nc"), std::string("1,ok,")}) {
    std::istringstream in(whole + tail);
    CsvReader reader(in);
    std::vector<std::string> read;
    ASSERT_TRUE(reader.Next(&read));
    EXPECT_FALSE(reader.Next(&read));
    EXPECT_TRUE(reader.torn());
    EXPECT_EQ(reader.offset(), whole.size());
  }
}

// Tests that the worker pool hands results over in order whatever the threads' timing,
// never runs more than `window` items ahead, and rethrows a worker's exception.
TEST(SweepRunOrdered, InOrderBoundedAndRethrows) {
  std::atomic<std::uint64_t> consumed{0};
  std::atomic<std::uint64_t> max_ahead{0};
  std::vector<std::uint64_t> seen;
  RunOrdered<std::uint64_t>(
      500, 4,
      [&](std::uint64_t k) {
        const std::uint64_t ahead = k - std::min(k, consumed.load());
        std::uint64_t previous = max_ahead.load();
        while (ahead > previous && !max_ahead.compare_exchange_weak(previous, ahead)) {
        }
        if (k % 7 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
        return k * k;
      },
      [&](std::uint64_t k, std::uint64_t&& value) {
        EXPECT_EQ(value, k * k);
        seen.push_back(k);
        consumed = k + 1;
      },
      16);
  ASSERT_EQ(seen.size(), 500u);
  for (std::uint64_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], k);
  EXPECT_LT(max_ahead.load(), 16u);

  EXPECT_THROW(RunOrdered<int>(
                   100, 3,
                   [](std::uint64_t k) {
                     if (k == 42) throw std::runtime_error("boom");
                     return 0;
                   },
                   [](std::uint64_t, int&&) {}),
               std::runtime_error);
}

}  // namespace
}  // namespace shapebench::bench
