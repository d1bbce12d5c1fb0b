// `shapebench compare BASELINE.yaml [CANDIDATE.yaml]`: two scenarios or two sweeps side by
// side (bench/compare/, docs/compare.md). Exit 1 when a gate fails; a sweep's point that
// fails to run makes it 2 or 3, as `check` ranks them.
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/compare/compare.h"
#include "bench/compare/compare_html.h"
#include "bench/compare/compare_report.h"
#include "bench/compare/compare_runs.h"
#include "bench/compare/compare_sweep.h"
#include "bench/output/output_path.h"
#include "bench/sweep/sweep.h"

namespace shapebench::bench::cli {
namespace {

struct CompareArgs {
  std::string baseline;
  std::string candidate;
  std::vector<std::string> sets;
  std::vector<std::string> baseline_sets;
  std::vector<std::string> candidate_sets;
  std::vector<std::string> gates;
  bool json = false;
  std::string out_dir;
  std::string report;  // --report FILE.html (two scenarios)
  int jobs = 0;
};

int CompareSweepsCommand(const CompareArgs& args, const CompareRequest& request, const std::vector<Gate>& gates) {
  const ComparedSweeps sweeps = LoadComparedSweeps(request);
  const int jobs = JobsOrDefault(args.jobs);
  const SweepComparison comparison = args.out_dir.empty()
                                         ? CompareSweeps(sweeps, gates, jobs, nullptr, std::cerr)
                                         : CompareSweepsWritingTo(args.out_dir, sweeps, gates, jobs, std::cerr);
  if (args.json) {
    std::cout << ComparisonJson(comparison).dump(2) << std::endl;
  } else {
    PrintComparison(std::cout, comparison);
    std::cout.flush();
  }
  if (!args.out_dir.empty()) {  // the files of CompareSweepsWritingTo
    PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, {"points.csv", "compare.txt", "compare.json"});
  }
  if (comparison.point_exit_code != 0) return comparison.point_exit_code;
  return comparison.passed() ? kExitOk : kExitCheckFailed;
}

int CompareScenariosCommand(const CompareArgs& args, const CompareRequest& request, const std::vector<Gate>& gates) {
  const ScenarioComparison comparison = CompareScenarios(request, gates);
  for (const auto& [side, run] : {std::pair{&comparison.baseline, &comparison.baseline_run},
                                  std::pair{&comparison.candidate, &comparison.candidate_run}}) {
    for (const std::string& warning : run->command.warnings) {
      std::cerr << "warning: " << Safe(side->file) << ": " << Safe(warning) << "\n";
    }
  }
  if (!args.out_dir.empty()) WriteComparisonOutputs(args.out_dir, comparison);
  if (!args.report.empty()) WriteReport(args.report, [&] { return CompareHtmlReport(comparison); });
  if (args.json) {
    std::cout << ComparisonJson(comparison).dump(2) << std::endl;
  } else {
    PrintComparison(std::cout, comparison);
    std::cout.flush();
  }
  if (!args.out_dir.empty()) {  // the files of WriteComparisonOutputs
    PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, {"compare.txt", "compare.json", "deflection.png"});
  }
  return comparison.passed() ? kExitOk : kExitCheckFailed;
}

int CompareCommand(const CompareArgs& args) {
  const std::vector<Gate> gates = ParseGates(args.gates);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  const CompareRequest request{args.baseline, args.candidate, args.sets, args.baseline_sets, args.candidate_sets};
  const bool sweep = IsSweepFile(args.baseline);
  if (!args.report.empty()) {
    if (sweep) throw std::runtime_error("compare --report: two scenarios only (a sweep's: sweep --report)");
    RequireWritableOutputFile("--report", args.report);  // before anything runs
  }
  if (!args.candidate.empty() && IsSweepFile(args.candidate) != sweep) {
    throw std::runtime_error("compare: " + (sweep ? args.baseline : args.candidate) +
                             " is a sweep file (base:, grid:), " + (sweep ? args.candidate : args.baseline) +
                             " is not: give two scenarios or two sweeps");
  }
  return sweep ? CompareSweepsCommand(args, request, gates) : CompareScenariosCommand(args, request, gates);
}

}  // namespace

Command AddCompareCommand(CLI::App* app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* compare = app->add_subcommand(
      "compare",
      "two scenarios (or two sweeps, point by point) side by side, every metric; --gate fails "
      "(exit 1) when the candidate is worse");
  compare->add_option("baseline", args->baseline, "the baseline: a scenario or sweep file")
      ->required()
      ->type_name("BASELINE.yaml");
  compare->add_option("candidate", args->candidate,
                      "the candidate: a file of the same kind (default: BASELINE with --candidate-set)")
      ->type_name("CANDIDATE.yaml");
  AddSetOption(compare, &args->sets, "--set", "override one key on both sides (repeatable): --set a.b=VALUE");
  AddSetOption(compare, &args->baseline_sets, "--baseline-set",
               "override one key on the baseline only, after --set (repeatable)");
  AddSetOption(compare, &args->candidate_sets, "--candidate-set",
               "override one key on the candidate only, after --set (repeatable)");
  compare
      ->add_option("--gate", args->gates,
                   "exit 1 when the candidate is worse than the baseline by more than REL, relative "
                   "to max(|baseline|, the unit's floor) (repeatable): --gate residual_ratio=0.05")
      ->allow_extra_args(false)
      ->type_name("METRIC=REL");
  compare->add_flag("--json", args->json, "print the comparison as one JSON object");
  compare
      ->add_option("--out", args->out_dir,
                   "write compare.txt, compare.json and deflection.png (sweeps: points.csv) into DIR")
      ->type_name("DIR");
  compare->add_option("--report", args->report, kReportHelp)->type_name("FILE.html");
  compare->add_option("--jobs", args->jobs, "sweeps: worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096))
      ->type_name("N");
  compare->footer(
      "Floors of max(|baseline|, floor): m 1e-9, s 1e-6, ratios 1e-6, count and bool 1. Lower is\n"
      "better compares magnitudes. A gate on a metric n/a on either side fails. Two sweeps need\n"
      "the same grid; a gate fails when any point fails it. Exit: 0 pass, 1 a gate failed,\n"
      "2 bad input, 3 the solver failed. docs/compare.md");
  return {compare, [args] { return CompareCommand(*args); }};
}

}  // namespace shapebench::bench::cli
