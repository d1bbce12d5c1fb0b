// Reliability in process (docs/reliability.md): CSV round trips of hostile fields, RunOrdered cancelled midway,
// deferred signals, the run-length bound, the trace stride, gnuplot quoting.
#include <signal.h>

#include <atomic>
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "common/ordered_pool.h"
#include "common/csv.h"
#include "bench/output/gnuplot.h"
#include "common/interrupt.h"
#include "bench/output/report.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;

// Tests that every hostile field (commas, quotes, CR, LF, CR LF, only quotes, spaces,
// empty, a NUL) survives CsvRecord then CsvReader exactly, and that a record cut inside a
// quoted field is torn, not returned.
TEST(Csv, HostileFieldsRoundTrip) {
  const std::vector<std::string> fields = {
      "plain", "a,b", "say \"hi\"", "\"", "\"\"", "line1\nline2", "cr\rlf\r\n", " lead", "trail ", "",
      std::string("nul\0inside", 10), ",\n\"", "error: f.yaml:1:2: k: expected a number, got \"6,000\""};
  const std::string record = CsvRecord(fields) + CsvRecord({"next"});
  std::istringstream in(record);
  CsvReader reader(in);
  std::vector<std::string> read;
  ASSERT_TRUE(reader.Next(&read));
  EXPECT_EQ(read, fields);
  ASSERT_TRUE(reader.Next(&read));
  EXPECT_EQ(read, std::vector<std::string>{"next"});
  EXPECT_FALSE(reader.Next(&read));
  EXPECT_FALSE(reader.torn());
  EXPECT_EQ(CsvField("a\"b"), "\"a\"\"b\"");
  EXPECT_EQ(CsvField("a\rb"), "\"a\rb\"");

  const std::string first = CsvRecord({"1", "ok"});
  std::istringstream cut(first + CsvRecord({"2", "x,\"y\"\nz"}).substr(0, 9));
  CsvReader torn(cut);
  ASSERT_TRUE(torn.Next(&read));
  EXPECT_FALSE(torn.Next(&read));
  EXPECT_TRUE(torn.torn());
  EXPECT_EQ(torn.offset(), first.size());
}

// Tests that RunOrdered, cancelled midway, stops taking items, hands over every result
// that is complete and in order (a prefix 0..m-1, nothing after a gap), and returns m.
TEST(Interrupt, RunOrderedCancelledKeepsACompletePrefix) {
  for (const int jobs : {1, 2, 4}) {
    std::atomic<bool> cancel{false};
    std::vector<std::uint64_t> consumed;
    const std::uint64_t done = RunOrdered<std::uint64_t>(
        1000, jobs,
        [&](std::uint64_t k) {
          if (k == 30) cancel = true;  // the signal arrives while point 30 runs
          return k * k;
        },
        [&](std::uint64_t k, std::uint64_t&& value) {
          EXPECT_EQ(value, k * k);
          consumed.push_back(k);
        },
        8, [&] { return cancel.load(); });
    ASSERT_EQ(done, consumed.size()) << jobs;
    EXPECT_GE(done, 31u) << jobs;  // 30 and everything before it were started
    EXPECT_LT(done, 1000u) << jobs;
    for (std::uint64_t k = 0; k < consumed.size(); ++k) EXPECT_EQ(consumed[k], k);
  }
}

// Tests that inside a deferred section a SIGTERM is recorded (the process goes on) and
// ThrowIfInterrupted then throws InterruptedError with exit code 143.
TEST(Interrupt, DeferredSignalIsRecordedThenThrown) {
  InstallInterruptHandlers();
  {
    const DeferInterrupts defer;
    ASSERT_EQ(raise(SIGTERM), 0);
    EXPECT_EQ(PendingInterrupt(), SIGTERM);
    try {
      ThrowIfInterrupted("state");
      ADD_FAILURE() << "no InterruptedError";
    } catch (const InterruptedError& error) {
      EXPECT_EQ(error.exit_code(), 143);
      EXPECT_STREQ(error.what(), "interrupted by SIGTERM: state");
    }
  }
  ClearPendingInterrupt();
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  EXPECT_NO_THROW(ThrowIfInterrupted("state"));
}

// Tests the trace stride: 1 when the samples fit, else at most max_rows rows kept
// (samples 0, stride, 2 stride, ...) that reach to within one stride of the last sample.
TEST(GuardRails, TraceStride) {
  EXPECT_EQ(TraceStride(100, 100), 1u);
  EXPECT_EQ(TraceStride(101, 100), 2u);
  for (const std::size_t samples : {101u, 199u, 200u, 1000u, 12345u}) {
    for (const long max_rows : {2L, 3L, 100L}) {
      const std::size_t stride = TraceStride(samples, max_rows);
      const std::size_t rows = (samples - 1) / stride + 1;
      EXPECT_LE(rows, static_cast<std::size_t>(max_rows)) << samples << " " << max_rows;
      EXPECT_LT(samples - 1 - (rows - 1) * stride, stride) << samples << " " << max_rows;
    }
  }
}

// Tests the run-length lower bound on a single move: 213 mm at 30 m/min (0.426 s at the
// feed), 0.3 s acc/dec (a = 1.667 m/s^2: from rest to rest at 2a at least
// 2 sqrt(0.213 / 3.333) = 0.506 s), method 1 at 25 Hz (0.02 s) and the residual window
// of the 25 Hz mode (0.12 s): 0.646 s, below the run's 0.746 s of motion plus its window.
TEST(GuardRails, MinimumRunSecondsIsALowerBound) {
  const Scenario scenario = LoadScenario(DataPath("sweeps/sdof_method1.yaml"), {});
  std::string breakdown;
  const double seconds = MinimumRunSeconds(scenario, &breakdown);
  EXPECT_NEAR(seconds, 2.0 * std::sqrt(0.213 / (2.0 * 0.5 / 0.3)) + 0.02 + 0.12, 1e-9) << breakdown;
  EXPECT_LT(seconds, 0.746 + 0.12);
  EXPECT_NE(breakdown.find("residual window 0.12 s"), std::string::npos) << breakdown;
}

// Tests that a grid above the point limit loads with force (and not without).
TEST(GuardRails, HugeGridNeedsForce) {
  ScratchDir dir;
  const std::string big = dir.Write("big.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                                                    "\ngrid:\n  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 3000}\n"
                                                    "  controller.accel_time_s: {from: 0.1, to: 0.4, steps: 1000}\n");
  EXPECT_THROW(LoadSweep(big, {}), ConfigError);
  SweepLoadOptions options;
  options.force = true;
  EXPECT_EQ(LoadSweep(big, {}, options).points, 3'000'000u);
}

// Tests gnuplot quoting: single quotes doubled, control characters (newline, CR, NUL,
// tab) become spaces, backslashes and backquotes left as they are (literal inside '').
TEST(Gnuplot, QuotedStrings) {
  EXPECT_EQ(GnuplotQuoted("it's"), "'it''s'");
  EXPECT_EQ(GnuplotQuoted(std::string("a\nb\rc\0d\te", 9)), "'a b c d e'");
  EXPECT_EQ(GnuplotQuoted("\\ `x` $(y) @z \"q\""), "'\\ `x` $(y) @z \"q\"'");
}

}  // namespace
}  // namespace shapebench::bench
