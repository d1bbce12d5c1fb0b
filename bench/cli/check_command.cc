// `shapebench check FILE.yaml...`: scenarios (or sweeps) run and their checks evaluated;
// lines or JSON, --junit REPORT.xml, --report FILE.html. Exit 1 when a check fails.
#include <chrono>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/config_error.h"
#include "bench/output/output_path.h"
#include "bench/output/report.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/checks.h"
#include "bench/run/located_run.h"
#include "bench/sweep/band_check.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "common/interrupt.h"
#include "model/integrator.h"

namespace shapebench::bench::cli {
namespace {

struct CheckArgs {
  std::vector<std::string> files;
  std::vector<std::string> sets;
  std::string junit;
  std::string report;  // --report FILE.html
  bool json = false;  // the results as one JSON object instead of the lines
  int jobs = 0;  // sweep files: worker threads (0: every hardware thread)
  bool force = false;  // sweep files: load a grid above SweepLoadOptions::max_points
};

// The files of a check, every one loaded before anything runs: bad input fails fast and
// writes nothing. A file with base: and grid: is a sweep: its checks apply to every point.
struct CheckFiles {
  std::vector<Scenario> scenarios;
  std::vector<std::optional<Sweep>> sweeps;
};

CheckFiles LoadCheckFiles(const CheckArgs& args, const std::vector<Override>& overrides) {
  CheckFiles files;
  SweepLoadOptions load;
  load.force = args.force;  // as `sweep --force`: the grid's refusal tells the user to pass it
  for (const std::string& file : args.files) {
    Doing("loading " + file);
    const bool sweep = IsSweepFile(file);
    files.sweeps.push_back(sweep ? std::optional<Sweep>(LoadSweep(file, overrides, load)) : std::nullopt);
    const std::optional<Sweep>& loaded = files.sweeps.back();
    if (sweep && !loaded->note.empty() && !IsDistributedWorker()) std::cerr << loaded->note << "\n";
    files.scenarios.push_back(sweep ? Scenario{} : LoadScenario(file, overrides));
    if (sweep ? loaded->checks.empty() && loaded->gates.empty() : files.scenarios.back().checks.empty()) {
      throw ConfigError(file, 0, 0, "checks",
                        "no checks to evaluate; add e.g. checks: {peak_ratio: {max: 1.01}}");
    }
    if (!sweep) ValidateBandChecks(files.scenarios.back(), overrides);
  }
  return files;
}

// The exit code of a check, raised to the most severe seen: bad input > solver failure >
// failed check.
class CheckExit {
 public:
  void Raise(int code) {
    const int rank[] = {0, 1, 3, 2};
    if (rank[code] > rank[code_]) code_ = code;
  }
  int code() const { return code_; }

 private:
  int code_ = kExitOk;
};

// One scenario run and its checks evaluated, each check's line printed unless --json.
ScenarioCheckReport CheckScenario(const Scenario& scenario, const std::vector<Override>& overrides,
                                  bool json, CheckExit* exit) {
  ScenarioCheckReport report;
  report.file = scenario.source_file;
  report.name = scenario.name;
  const auto start = std::chrono::steady_clock::now();
  Doing("running scenario '" + scenario.name + "' (" + scenario.source_file + ")", RunMemory(scenario));
  try {
    // Checks read the metrics only: no trace (its memory grew with the run).
    const RunResult result = RunScenarioLocated(scenario, overrides, RunOptions{false});
    PrintRunWarnings(scenario.source_file, result);
    report.results = EvaluateScenarioChecks(scenario, overrides, result.metrics);
    // A failed stroke_alarm check says where the alarm fired (issue 32 item 15).
    for (CheckResult& check : report.results) {
      if (check.metric == "stroke_alarm" && !check.passed && !check.banded() && result.command.stroke_alarm) {
        check.message += " (the alarm fired " + result.command.stroke_alarm_site.Text() + ")";
      }
    }
  } catch (const ConfigError& error) {
    report.error = error.what();
    std::cerr << "error: " << Safe(error.what()) << "\n";
    exit->Raise(kExitBadInput);
  } catch (const model::SolverError& error) {
    report.error = SolverFailureText(error);
    std::cerr << "error: " << Safe(report.error) << " (" << Safe(report.file) << ")\n";
    exit->Raise(kExitSolverFailed);
  }
  report.run_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Its checks share the run (and a band check's runs): each testcase is given its time.
  for (CheckResult& result : report.results) result.run_time_s = report.run_time_s;
  for (const CheckResult& result : report.results) {
    if (!json) std::cout << Safe(FormatCheckLine(report.file, result)) << "\n";
    if (!result.passed) exit->Raise(kExitCheckFailed);
  }
  std::cout.flush();
  return report;
}

int CheckCommand(const CheckArgs& args) {
  if (!args.report.empty()) RequireWritableOutputFile("--report", args.report);  // before anything runs
  if (!args.junit.empty()) RequireWritableOutputFile("--junit", args.junit);  // before the runs
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  const CheckFiles files = LoadCheckFiles(args, overrides);
  AgreeAcrossRanks([&] {  // every MPI rank serves these sweeps, or none runs (exit 2)
    RunIdentity identity;
    identity.Add("command", "check");
    std::string sweeps;
    std::string hashes;
    for (const auto& sweep : files.sweeps) {
      if (!sweep) continue;
      sweeps += (sweeps.empty() ? "" : ", ") + sweep->file;
      hashes += (hashes.empty() ? "" : ", ") + SweepHash(*sweep, overrides);
    }
    identity.Add("sweep files", sweeps);
    identity.Add("--set options", SetsText(overrides));
    identity.Add("sweep hashes", hashes);
    return identity;
  });
  if (IsDistributedWorker()) {  // an MPI rank other than 0 (bench/sweep/sweep_mpi.h)
    for (const auto& sweep : files.sweeps) {
      if (sweep) ServeCheckSweep(*sweep, overrides, JobsOrDefault(args.jobs));
    }
    return kExitOk;
  }
  CheckExit exit;
  std::vector<ScenarioCheckReport> reports;
  for (std::size_t i = 0; i < files.scenarios.size(); ++i) {
    if (!files.sweeps[i]) {
      reports.push_back(CheckScenario(files.scenarios[i], overrides, args.json, &exit));
      continue;
    }
    const Sweep& sweep = *files.sweeps[i];
    Doing("checking sweep '" + sweep.name + "' (" + sweep.file + ")", SweepMemory(JobsOrDefault(args.jobs)));
    std::ostringstream not_shown;  // --json: the JSON replaces the lines
    ScenarioCheckReport report;
    exit.Raise(CheckSweep(sweep, overrides, JobsOrDefault(args.jobs),
                          args.json ? static_cast<std::ostream&>(not_shown) : std::cout, std::cerr, &report));
    reports.push_back(report);
  }
  if (args.json) std::cout << CheckReportsJson(reports).dump(2) << std::endl;
  if (!args.junit.empty()) {
    Doing("writing " + args.junit);
    const DeferInterrupts defer;
    WriteJUnit(args.junit, reports);
    ThrowIfInterrupted(args.junit + " is complete");
  }
  if (!args.report.empty()) WriteReport(args.report, [&] { return CheckHtmlReport(reports); });
  return exit.code();
}

}  // namespace

Command AddCheckCommand(CLI::App* app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* check = app->add_subcommand("check", "run scenarios and evaluate their checks");
  check->add_option("files", args->files, "scenario or sweep files with checks:")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(check, &args->sets);
  check->add_option("--junit", args->junit, "write JUnit XML")->type_name("REPORT.xml");
  check->add_option("--report", args->report, kReportHelp)->type_name("FILE.html");
  check->add_flag("--json", args->json, "print the results as one JSON object (band checks: worst value and where)");
  check->add_option("--jobs", args->jobs, "sweep files: worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096))
      ->type_name("N");
  check->add_flag("--force", args->force, kForceHelp);
  return {check, [args] { return CheckCommand(*args); }, /*on_every_rank=*/true};
}

}  // namespace shapebench::bench::cli
