#include "bench/compare/compare_sweep.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/csv.h"
#include "common/interrupt.h"
#include "common/shown_text.h"
#include "bench/sweep/point_loop.h"
#include "common/exit_codes.h"

namespace shapebench::bench {
namespace {


std::string AxisName(const SweepAxis& axis) {
  std::string name;
  for (const SweepValues& values : axis.keys) name += (name.empty() ? "" : " + ") + values.key;
  return name;
}

// The first value where two axes' keys differ, or "".
std::string ValueDifference(const SweepValues& a, const SweepValues& b) {
  if (a.size() != b.size()) {
    return "'" + a.key + "' has " + std::to_string(a.size()) + " values in the baseline, " +
           std::to_string(b.size()) + " in the candidate";
  }
  for (std::uint64_t i = 0; i < a.size(); ++i) {
    if (a.Text(i) != b.Text(i)) {
      return "'" + a.key + "' value " + std::to_string(i) + " is " + a.Text(i) + " in the baseline, " +
             b.Text(i) + " in the candidate";
    }
  }
  return "";
}

Sweep LoadSweepSide(CompareSide* side) {
  try {
    Sweep sweep = LoadSweep(side->file, side->overrides);
    side->name = sweep.name;
    return sweep;
  } catch (const ConfigError& error) {
    throw side->Relabeled(error);
  }
}

// The candidate's and the baseline's outcome of one point.
struct PointPair {
  PointOutcome baseline;
  PointOutcome candidate;
};

// Folds the points into the summaries, in point order, and writes points.csv's rows.
class Tally {
 public:
  Tally(SweepComparison* comparison, const Sweep& sweep, std::ostream* csv, std::ostream& err)
      : comparison_(comparison), sweep_(sweep), csv_(csv), err_(err) {
    if (csv_ == nullptr) return;
    std::vector<std::string> header = {"point"};
    for (const std::string& key : sweep.Keys()) header.push_back(key);
    for (const char* column :
         {"metric", "baseline", "candidate", "change", "relative_change", "favours", "error"}) {
      header.emplace_back(column);
    }
    *csv_ << CsvRecord(header);
  }

  void Add(std::uint64_t index, PointPair&& pair) {
    const SweepPoint point = MakePoint(sweep_, index, {});
    const std::string label = point.Label();
    std::vector<std::string> fields = {std::to_string(index)};
    fields.insert(fields.end(), point.texts.begin(), point.texts.end());
    if (!pair.baseline.ok() || !pair.candidate.ok()) {
      Failed(label, pair, fields);
      return;
    }
    const std::vector<MetricChange> changes = CompareMetrics(pair.baseline.metrics, pair.candidate.metrics);
    for (std::size_t m = 0; m < changes.size(); ++m) {
      const MetricChange& change = changes[m];
      SweepMetricSummary& summary = comparison_->metrics[m];
      Count(change.better, &summary);
      if (!std::isnan(change.worsening) &&
          (!summary.has_worst || change.worsening > summary.worst.change.worsening)) {
        summary.has_worst = true;
        summary.worst = {index, label, change};
      }
      if (csv_ != nullptr) Row(fields, change);
    }
    for (SweepGateSummary& gate : comparison_->gates) {
      const MetricChange& change = changes[static_cast<std::size_t>(gate.gate.info - MetricTable().data())];
      if (!GatePasses(gate.gate, change)) ++gate.failed;
      if (std::isnan(change.worsening)) {
        ++gate.not_comparable;
      } else if (!gate.has_worst || change.worsening > gate.worst.change.worsening) {
        gate.has_worst = true;
        gate.worst = {index, label, change};
      }
    }
  }

 private:
  static void Count(Verdict verdict, SweepMetricSummary* summary) {
    switch (verdict) {
      case Verdict::kCandidate: ++summary->candidate_better; break;
      case Verdict::kBaseline: ++summary->baseline_better; break;
      case Verdict::kSame: ++summary->same; break;
      case Verdict::kNotComparable: ++summary->not_comparable; break;
    }
  }

  void Row(std::vector<std::string> fields, const MetricChange& change) {
    fields.emplace_back(change.info->name);
    for (const double value : {change.baseline, change.candidate, change.change, change.relative_change}) {
      fields.push_back(ExactDouble(value));
    }
    fields.emplace_back(VerdictName(change.better));
    fields.emplace_back();
    *csv_ << CsvRecord(fields);
  }

  void Failed(const std::string& label, const PointPair& pair, std::vector<std::string> fields) {
    ++comparison_->failed_points;
    std::string errors;
    for (const auto& [side, outcome] : {std::pair{&comparison_->baseline, &pair.baseline},
                                        std::pair{&comparison_->candidate, &pair.candidate}}) {
      if (outcome->ok()) continue;
      const bool baseline = side == &comparison_->baseline;
      const std::string message = side->Relabeled(outcome->error);
      err_ << "error: " << TerminalSafe(message, true) << " (" << (baseline ? "baseline " : "candidate ")
           << TerminalSafe(side->file) << " @ " << TerminalSafe(label) << ")\n";
      errors += (errors.empty() ? "" : "; ") + std::string(baseline ? "baseline: " : "candidate: ") + message;
      const int code =
          outcome->status == PointOutcome::Status::kSolverFailed ? kExitSolverFailed : kExitBadInput;
      if (comparison_->point_exit_code != kExitBadInput) comparison_->point_exit_code = code;
    }
    if (csv_ == nullptr) return;
    fields.insert(fields.end(), {"", "", "", "", "", "error", errors});
    *csv_ << CsvRecord(fields);
  }

  SweepComparison* comparison_;
  const Sweep& sweep_;
  std::ostream* csv_;
  std::ostream& err_;
};

}  // namespace

void CheckSameGrid(const Sweep& baseline, const Sweep& candidate) {
  const auto differ = [&](const std::string& what) {
    throw std::runtime_error("compare: the sweeps' grids differ (" + what + "): " + baseline.file + " vs " +
                             candidate.file + "; point by point needs the same grid");
  };
  if (baseline.axes.size() != candidate.axes.size()) {
    differ(std::to_string(baseline.axes.size()) + (baseline.axes.size() == 1 ? " axis" : " axes") +
           " in the baseline, " +
           std::to_string(candidate.axes.size()) + " in the candidate");
  }
  for (std::size_t a = 0; a < baseline.axes.size(); ++a) {
    const SweepAxis& base = baseline.axes[a];
    const SweepAxis& cand = candidate.axes[a];
    if (AxisName(base) != AxisName(cand)) {
      differ("axis " + std::to_string(a + 1) + " is " + AxisName(base) + " in the baseline, " +
             AxisName(cand) + " in the candidate");
    }
    for (std::size_t k = 0; k < base.keys.size(); ++k) {
      const std::string difference = ValueDifference(base.keys[k], cand.keys[k]);
      if (!difference.empty()) differ(difference);
    }
  }
}

bool SweepComparison::passed() const {
  for (const SweepGateSummary& gate : gates) {
    if (!gate.passed()) return false;
  }
  return true;
}

ComparedSweeps LoadComparedSweeps(const CompareRequest& request) {
  ComparedSweeps sweeps;
  sweeps.baseline = BaselineSide(request);
  sweeps.candidate = CandidateSide(request);
  sweeps.baseline_sweep = LoadSweepSide(&sweeps.baseline);
  sweeps.candidate_sweep = LoadSweepSide(&sweeps.candidate);
  CheckSameGrid(sweeps.baseline_sweep, sweeps.candidate_sweep);
  return sweeps;
}

SweepComparison CompareSweeps(const ComparedSweeps& sweeps, const std::vector<Gate>& gates, int jobs,
                              std::ostream* points_csv, std::ostream& err) {
  SweepComparison comparison;
  comparison.baseline = sweeps.baseline;
  comparison.candidate = sweeps.candidate;
  comparison.points = sweeps.baseline_sweep.points;
  for (const MetricInfo& info : MetricTable()) {
    SweepMetricSummary summary;
    summary.info = &info;
    comparison.metrics.push_back(summary);
  }
  for (const Gate& gate : gates) {
    SweepGateSummary summary;
    summary.gate = gate;
    comparison.gates.push_back(summary);
  }
  Tally tally(&comparison, sweeps.baseline_sweep, points_csv, err);
  ForEachSweepPoint<PointPair>(
      0, comparison.points, jobs,
      [&](std::uint64_t point) {
        return PointPair{RunPoint(sweeps.baseline_sweep, sweeps.baseline.overrides, point),
                         RunPoint(sweeps.candidate_sweep, sweeps.candidate.overrides, point)};
      },
      [&](std::uint64_t point, PointPair&& pair) { tally.Add(point, std::move(pair)); },
      [] { return PendingInterrupt() != 0; });
  ThrowIfInterrupted("nothing written");
  return comparison;
}

}  // namespace shapebench::bench
