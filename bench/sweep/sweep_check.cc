// CheckSweep (bench/sweep/sweep_runner.h): `check` on a sweep file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "common/ordered_pool.h"
#include "common/shown_text.h"
#include "bench/sim/checks.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/sweep_runner.h"

namespace shapebench::bench {
namespace {

constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

struct CheckTally {
  std::uint64_t passed = 0;
  std::uint64_t failed = 0;
  double worst_violation = -std::numeric_limits<double>::infinity();
  std::string worst_value;
  std::string worst_point;
  std::string bound;
};

// Each point's outcome with the wall time of its run (a JUnit testcase's time).
using TimedOutcome = std::pair<PointOutcome, double>;

TimedOutcome TimedRun(const Sweep& sweep, const std::vector<Override>& sets, std::uint64_t point) {
  const auto point_start = std::chrono::steady_clock::now();
  PointOutcome outcome = RunPoint(sweep, sets, point);
  return TimedOutcome(std::move(outcome), std::chrono::duration<double>(
                                              std::chrono::steady_clock::now() - point_start)
                                              .count());
}

// An outcome between MPI ranks (same binary on every rank: the bytes of the doubles):
// status, index, time, Metrics, then the error text.
static_assert(std::is_trivially_copyable_v<Metrics>);
constexpr std::size_t kOutcomeHead = 1 + sizeof(std::uint64_t) + sizeof(double) + sizeof(Metrics);

std::string EncodeOutcome(const TimedOutcome& timed) {
  std::string bytes(kOutcomeHead, '\0');
  bytes[0] = static_cast<char>(timed.first.status);
  std::memcpy(&bytes[1], &timed.first.index, sizeof(std::uint64_t));
  std::memcpy(&bytes[1 + sizeof(std::uint64_t)], &timed.second, sizeof(double));
  std::memcpy(&bytes[1 + sizeof(std::uint64_t) + sizeof(double)], &timed.first.metrics, sizeof(Metrics));
  return bytes + timed.first.error;
}

TimedOutcome DecodeOutcome(const std::string& bytes) {
  TimedOutcome timed;
  if (bytes.size() < kOutcomeHead) throw std::runtime_error("MPI: a point's outcome arrived cut short");
  timed.first.status = static_cast<PointOutcome::Status>(bytes[0]);
  std::memcpy(&timed.first.index, &bytes[1], sizeof(std::uint64_t));
  std::memcpy(&timed.second, &bytes[1 + sizeof(std::uint64_t)], sizeof(double));
  std::memcpy(&timed.first.metrics, &bytes[1 + sizeof(std::uint64_t) + sizeof(double)], sizeof(Metrics));
  timed.first.error = bytes.substr(kOutcomeHead);
  return timed;
}

}  // namespace

void ServeCheckSweep(const Sweep& sweep, const std::vector<Override>& sets, int jobs) {
  CurrentDistributor()->Serve(
      jobs, [&](std::uint64_t point) { return EncodeOutcome(TimedRun(sweep, sets, point)); });
}

int CheckSweep(const Sweep& sweep, const std::vector<Override>& sets, int jobs,
               std::ostream& out, std::ostream& err, ScenarioCheckReport* report) {
  const auto start = std::chrono::steady_clock::now();
  int exit_code = 0;
  auto raise = [&](int code) {
    const int rank[] = {0, 1, 3, 2};  // bad input > solver failure > failed check
    if (rank[code] > rank[exit_code]) exit_code = code;
  };
  report->file = sweep.file;
  report->name = sweep.name;
  std::vector<CheckTally> tallies(sweep.checks.size());
  std::uint64_t failed_points = 0;
  RunDistributed<TimedOutcome>(
      0, sweep.points, jobs, [&](std::uint64_t point) { return TimedRun(sweep, sets, point); },
      [&](std::uint64_t point, TimedOutcome&& timed) {
        const PointOutcome& outcome = timed.first;
        const std::string label = MakePoint(sweep, point, {}).Label();
        if (!outcome.ok()) {
          ++failed_points;
          err << "error: " << outcome.error << " (" << sweep.file << " @ " << label << ")\n";
          report->point_errors.emplace_back(label, outcome.error);
          raise(outcome.status == PointOutcome::Status::kSolverFailed ? kExitSolverFailed
                                                                     : kExitBadInput);
          return;
        }
        std::vector<CheckResult> results = EvaluateChecks(sweep.checks, outcome.metrics);
        for (std::size_t c = 0; c < results.size(); ++c) {
          CheckResult& result = results[c];
          result.point = label;
          result.run_time_s = timed.second;
          CheckTally& tally = tallies[c];
          tally.bound = result.bound;
          ++(result.passed ? tally.passed : tally.failed);
          const double violation = Violation(sweep.checks[c], result.value);
          if (violation > tally.worst_violation || tally.worst_point.empty()) {
            tally.worst_violation = violation;
            tally.worst_value = result.value_text;
            tally.worst_point = label;
          }
          if (!result.passed) {
            out << TerminalSafe(FormatCheckLine(sweep.file, result), true) << "\n";
            raise(kExitCheckFailed);
          }
          report->results.push_back(std::move(result));
        }
      },
      EncodeOutcome, DecodeOutcome);
  for (std::size_t c = 0; c < sweep.checks.size(); ++c) {
    const CheckTally& tally = tallies[c];
    const std::uint64_t run = tally.passed + tally.failed;
    out << (tally.failed == 0 && failed_points == 0 ? "PASS " : "FAIL ") << sweep.file << " "
        << sweep.checks[c].metric << ": " << tally.passed << " of " << sweep.points
        << " points pass";
    if (!tally.bound.empty()) out << " (" << tally.bound << ")";
    if (failed_points > 0) out << ", " << failed_points << " failed to run";
    if (run > 0) out << "; worst " << tally.worst_value << " @ " << tally.worst_point;
    out << "\n";
  }
  out.flush();
  report->run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return exit_code;
}

}  // namespace shapebench::bench
