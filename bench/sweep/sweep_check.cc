// CheckSweep (bench/sweep/sweep_runner.h): `check` on a sweep file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <tuple>
#include <utility>

#include "common/csv.h"
#include "common/ordered_pool.h"
#include "common/shown_text.h"
#include "bench/scenario/checks.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/point_loop.h"
#include "bench/sweep/robust_band.h"
#include "bench/sweep/sweep_runner.h"
#include "common/sample_math.h"
#include "common/exit_codes.h"

namespace shapebench::bench {
namespace {

// How many failing point-checks `check` of a sweep prints under its summary.
constexpr std::uint64_t kShownFailures = 20;


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
// The samples of each combination of the other grid keys' values (a group), for the
// sweep's quantile and yield gates.
class GateTally {
 public:
  explicit GateTally(const Sweep& sweep) : sweep_(sweep) {
    std::uint64_t groups = 1;
    for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
      if (a != sweep.sample_axis) groups *= sweep.axes[a].size();
    }
    if (sweep.gates.empty()) groups = 0;
    passing_.assign(groups, 0);
    values_.assign(groups, std::vector<std::vector<double>>(sweep.gates.size()));
  }

  // A point's outcome; `passed` whether it passed every min/max check.
  void Add(std::uint64_t point, const PointOutcome& outcome, bool passed) {
    if (passing_.empty()) return;
    const std::uint64_t group = Group(point);
    if (outcome.ok() && passed) ++passing_[group];
    for (std::size_t g = 0; g < sweep_.gates.size(); ++g) {
      const SampleGate& gate = sweep_.gates[g];
      if (gate.kind != SampleGate::Kind::kQuantile) continue;
      const MetricInfo* info = FindMetric(gate.metric);
      double value = outcome.ok() && info != nullptr ? outcome.metrics.*info->field : NAN;
      // A sample that failed to run or has no value counts as the worst (the side of the bound).
      if (std::isnan(value)) value = gate.max ? INFINITY : -INFINITY;
      values_[group][g].push_back(value);
    }
  }

  // One result per gate and group, in that order.
  std::vector<CheckResult> Results() const {
    std::vector<CheckResult> results;
    for (std::size_t g = 0; g < sweep_.gates.size(); ++g) {
      for (std::uint64_t group = 0; group < passing_.size(); ++group) results.push_back(Result(g, group));
    }
    return results;
  }

 private:
  std::uint64_t Group(std::uint64_t point) const {
    const std::vector<std::uint64_t> digits = sweep_.AxisIndices(point);
    std::uint64_t group = 0;
    for (std::size_t a = 0; a < sweep_.axes.size(); ++a) {
      if (a != sweep_.sample_axis) group = group * sweep_.axes[a].size() + digits[a];
    }
    return group;
  }

  std::string Label(std::uint64_t group) const {
    std::string label;
    for (std::size_t a = sweep_.axes.size(); a-- > 0;) {
      if (a == sweep_.sample_axis) continue;
      const std::uint64_t digit = group % sweep_.axes[a].size();
      group /= sweep_.axes[a].size();
      std::string part;
      for (const SweepValues& values : sweep_.axes[a].keys) {
        part += (part.empty() ? "" : ", ") + values.key + "=" + values.Text(digit);
      }
      label = part + (label.empty() ? "" : ", ") + label;
    }
    return label;
  }

  CheckResult Result(std::size_t g, std::uint64_t group) const {
    const SampleGate& gate = sweep_.gates[g];
    const std::uint64_t n = sweep_.sampling->samples;
    CheckResult result;
    std::string detail;
    if (gate.kind == SampleGate::Kind::kYield) {
      const double yield = static_cast<double>(passing_[group]) / static_cast<double>(n);
      result = EvaluateCheck(Check{gate.metric, gate.min, gate.max}, yield);
      std::tie(result.interval_low, result.interval_high) = WilsonInterval(passing_[group], n);
      result.statistic = "yield";
      result.passing = passing_[group];
      detail = std::to_string(passing_[group]) + " of " + std::to_string(n) + " samples pass every check; " +
               "95% Wilson interval " + FormatValue(result.interval_low) + " to " + FormatValue(result.interval_high);
    } else {
      std::vector<double> sorted = values_[group][g];
      std::sort(sorted.begin(), sorted.end());
      const std::uint64_t rank = QuantileRank(n, gate.quantile);
      const QuantileRanks ranks = QuantileInterval(n, gate.quantile);
      // A sample without a value sorts as the worst (+-inf, no metric is infinite): the
      // quantile or an interval end landing on one is n/a, never "inf" (issue 32 item 16).
      const auto value = [&sorted](std::uint64_t r) { return std::isinf(sorted[r - 1]) ? NAN : sorted[r - 1]; };
      result = EvaluateCheck(Check{gate.metric, gate.min, gate.max}, value(rank));
      if (std::isnan(result.value)) {
        const auto missing = std::count_if(sorted.begin(), sorted.end(), [](double x) { return std::isinf(x); });
        result.message = "n/a: the quantile falls on one of the " + std::to_string(missing) + " of " +
                         std::to_string(n) + " samples without a value (failed or n/a), counted as the worst";
      }
      result.interval_low = ranks.lower == 0 ? -INFINITY : value(ranks.lower);
      result.interval_high = ranks.upper > n ? INFINITY : value(ranks.upper);
      result.statistic = "quantile " + ShortestDouble(gate.quantile);
      char coverage[32];
      std::snprintf(coverage, sizeof coverage, "%.3f", ranks.coverage);
      detail = "sample " + std::to_string(rank) + " of " + std::to_string(n) + " sorted; 95% order-statistic " +
               "interval " + (ranks.lower == 0 ? "-inf" : FormatValue(result.interval_low)) + " to " +
               (ranks.upper > n ? "+inf" : FormatValue(result.interval_high)) + " (samples " +
               std::to_string(ranks.lower) + " and " + std::to_string(ranks.upper) + ", coverage " + coverage + ")";
    }
    result.samples = n;
    result.point = Label(group);
    result.value_text += " (" + detail + ")";
    return result;
  }

  const Sweep& sweep_;
  std::vector<std::uint64_t> passing_;
  std::vector<std::vector<std::vector<double>>> values_;  // [group][gate] the samples' values
};

// Per check: how many points pass, the bound, the worst value and its point.
void PrintCheckSummary(std::ostream& out, const Sweep& sweep, const std::vector<CheckTally>& tallies,
                       std::uint64_t failed_points, bool yield_gated) {
  for (std::size_t c = 0; c < sweep.checks.size(); ++c) {
    const CheckTally& tally = tallies[c];
    const std::uint64_t run = tally.passed + tally.failed;
    const char* verdict = yield_gated ? "     " : tally.failed == 0 && failed_points == 0 ? "PASS " : "FAIL ";
    out << verdict << sweep.file << " "
        << sweep.checks[c].metric << ": " << tally.passed << " of " << sweep.points
        << " points pass";
    if (!tally.bound.empty()) out << " (" << tally.bound << ")";
    if (failed_points > 0) out << ", " << failed_points << " failed to run";
    if (run > 0) out << "; worst " << tally.worst_value << " @ " << tally.worst_point;
    out << "\n";
  }
}

// The robust bands, then the first failing point-checks (`failing` in all).
void PrintBandsAndFailures(std::ostream& out, const std::vector<SeriesBands>& bands, std::uint64_t failing,
                           const std::vector<std::string>& failing_lines) {
  for (const std::string& line : BandsSummary(bands)) out << TerminalSafe(line, true) << "\n";
  if (failing > 0) {
    out << "failing points: " << (failing > kShownFailures ? "the first " + std::to_string(kShownFailures) + " of " : "")
        << failing << " failing point-checks" << (failing > kShownFailures ? " (--junit and --json list every one)" : "")
        << ":\n";
    for (const std::string& line : failing_lines) out << line << "\n";
  }
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
  GateTally gates(sweep);
  // Under a yield gate the min/max checks define a passing sample; the yield is the verdict.
  const bool yield_gated = std::any_of(sweep.gates.begin(), sweep.gates.end(), [](const SampleGate& gate) {
    return gate.kind == SampleGate::Kind::kYield;
  });
  BandTally bands(sweep);
  // The failing point-checks are printed after the summary, the first kShownFailures of
  // them (a sweep can fail hundreds; --junit and --json list every one).
  std::vector<std::string> failing_lines;
  std::uint64_t failing = 0;
  const PointCodec<TimedOutcome> codec{EncodeOutcome, DecodeOutcome};
  ForEachSweepPoint<TimedOutcome>(
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
          gates.Add(point, outcome, false);
          return;
        }
        bands.Add(point, outcome.metrics);
        std::vector<CheckResult> results = EvaluateChecks(sweep.checks, outcome.metrics);
        gates.Add(point, outcome, std::all_of(results.begin(), results.end(),
                                              [](const CheckResult& result) { return result.passed; }));
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
          if (yield_gated) continue;  // the yield's input, not a verdict of its own
          if (!result.passed) {
            if (failing++ < kShownFailures) failing_lines.push_back(TerminalSafe(FormatCheckLine(sweep.file, result), true));
            raise(kExitCheckFailed);
          }
          report->results.push_back(std::move(result));
        }
      },
      {}, &codec);
  PrintCheckSummary(out, sweep, tallies, failed_points, yield_gated);
  PrintBandsAndFailures(out, bands.Bands(), failing, failing_lines);
  for (CheckResult& result : gates.Results()) {
    out << TerminalSafe(FormatCheckLine(sweep.file, result), true) << "\n";
    if (!result.passed) raise(kExitCheckFailed);
    report->results.push_back(std::move(result));
  }
  out.flush();
  report->run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return exit_code;
}

}  // namespace shapebench::bench
