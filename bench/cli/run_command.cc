// `shapebench run SCENARIO.yaml`: one scenario simulated; its metrics as a table or JSON,
// --out DIR with metrics.json, trace.csv and plots, --report FILE.html.
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/output/command_plot.h"
#include "bench/output/mat_file.h"
#include "bench/output/output_path.h"
#include "bench/output/report.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/checks.h"
#include "bench/run/located_run.h"
#include "bench/sweep/band_check.h"
#include "common/atomic_file.h"
#include "common/interrupt.h"

namespace shapebench::bench::cli {
namespace {

struct RunArgs {
  std::string scenario;
  std::vector<std::string> sets;
  bool json = false;
  std::string out_dir;
  std::string report;  // --report FILE.html
};

// deflection.png and path.png, each left out with a note on stderr when it would show
// nothing (a flat zero line, a line along one axis). Appends the names written.
void WriteRunPlots(const std::filesystem::path& dir, const Scenario& scenario, const RunResult& result,
                   const std::string& title, std::vector<std::string>* written) {
  if (DeflectionIsZero(result)) {
    std::cerr << "note: " << Safe(scenario.source_file) << ": no deflection.png: the deflection is "
              << "identically 0 (a rigid machine, no states)\n";
  } else {
    WriteDeflectionPlot((dir / "deflection.png").string(), result, scenario, title);
    written->push_back("deflection.png");
  }
  if (PathIsSingleAxisLine(result)) {
    std::cerr << "note: " << Safe(scenario.source_file) << ": no path.png: the programmed path is a "
              << "straight move along one axis (its XY plot would be a line)\n";
  } else {
    WritePathPlot((dir / "path.png").string(), result, scenario, title);
    written->push_back("path.png");
  }
}

// The files of `run --out DIR`. Created only now: bad input and solver failures leave no
// directory behind. A new directory is filled under a temporary name and renamed when
// complete, so a failure (gnuplot, full disk) leaves none behind either. A signal while
// writing lets the files finish (each is complete or absent), then stops. Returns the
// names of the files written.
std::vector<std::string> WriteRunOutputs(const std::string& out_dir, const Scenario& scenario,
                                         const RunResult& result, const std::vector<Override>& overrides) {
  const DeferInterrupts defer;
  StagedDirectory staged(out_dir);
  const std::filesystem::path dir(staged.path());
  std::vector<std::string> written;
  try {
    WriteFileAtomically((dir / "metrics.json").string(), [&](std::ostream& out) {
      out << RunJson(result).dump(2) << "\n";
    });
    const std::size_t stride =
        WriteTraceCsv((dir / "trace.csv").string(), result.trace, scenario.limits.max_trace_rows);
    if (stride > 1) {
      std::cerr << "note: " << scenario.source_file << ": the trace has " << result.trace.time_s.size()
                << " samples, more than limits.max_trace_rows (" << scenario.limits.max_trace_rows
                << "): trace.csv and the plots keep 1 in " << stride
                << "; the metrics use every sample\n";
    }
    WriteTraceMat((dir / "trace.mat").string(), result.trace, scenario.limits.max_trace_rows);
    written = {"metrics.json", "trace.csv", "trace.mat"};
    WriteRunPlots(dir, scenario, result, RunPlotTitle(scenario, overrides), &written);
    WriteCommandPlot((dir / "command.png").string(), result, scenario, RunPlotTitle(scenario, overrides));
    written.push_back("command.png");
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  ThrowIfInterrupted("the output in " + out_dir + " is complete");
  return written;
}

int RunCommand(const RunArgs& args) {
  if (!args.report.empty()) RequireWritableOutputFile("--report", args.report);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the run
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  Doing("loading " + args.scenario);
  const Scenario scenario = LoadScenario(args.scenario, overrides);
  Doing("running scenario '" + scenario.name + "' (" + scenario.source_file + ")", RunMemory(scenario));
  // The trace only for what shows it (--out's trace.csv and plots, --report): without,
  // the run's memory is its command and samples (bench/scenario/run_memory.h).
  RunOptions options;
  options.record_trace = !args.out_dir.empty() || !args.report.empty();
  options.attribute_sources = true;  // the table and JSON name the lines, traced or not
  const RunResult result = RunScenarioLocated(scenario, overrides, options);
  Doing("writing the outputs of scenario '" + scenario.name + "'");
  PrintRunWarnings(scenario.source_file, result);
  std::vector<std::string> written;
  if (!args.out_dir.empty()) written = WriteRunOutputs(args.out_dir, scenario, result, overrides);
  if (!args.report.empty()) {
    WriteReport(args.report, [&] {
      Doing("evaluating the checks of scenario '" + scenario.name + "' for the report", RunMemory(scenario));
      const std::vector<CheckResult> checks = EvaluateScenarioChecks(scenario, overrides, result.metrics);
      return RunHtmlReport(scenario, result, checks, EffectiveScenarioYaml(args.scenario, overrides));
    });
  }
  if (args.json) {
    std::cout << RunJson(result).dump(2) << std::endl;
  } else {
    std::cout << "scenario " << Safe(scenario.name) << " (" << Safe(scenario.source_file) << ")\n";
    PrintRunTable(std::cout, result);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

}  // namespace

Command AddRunCommand(CLI::App* app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = app->add_subcommand("run", "simulate one scenario");
  run->add_option("scenario", args->scenario, "scenario file")->required()->type_name("SCENARIO.yaml");
  AddSetOption(run, &args->sets);
  run->add_flag("--json", args->json, "print the metrics as one JSON object");
  run->add_option("--out", args->out_dir, "write metrics.json, trace.csv, trace.mat and the plots into DIR (created)")
      ->type_name("DIR");
  run->add_option("--report", args->report, kReportHelp)->type_name("FILE.html");
  return {run, [args] { return RunCommand(*args); }};
}

}  // namespace shapebench::bench::cli
