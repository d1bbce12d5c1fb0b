// shapebench command line (SPEC section 2): run, check, modes, pattern.
// Exit codes: 0 ok; 1 a check failed; 2 bad input, usage or unwritable output;
// 3 the solver failed. Errors go to stderr as "error: ...".
#include <chrono>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/atomic_file.h"
#include "bench/checks.h"
#include "bench/cosim.h"
#include "bench/modes_report.h"
#include "bench/pattern_report.h"
#include "bench/report.h"
#include "bench/scenario_loader.h"
#include "common/validation_error.h"
#include "model/integrator.h"
#include "model/machine.h"

namespace {

using namespace shapebench;
using namespace shapebench::bench;

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

std::string SolverMessage(const model::SolverError& error) {
  return "solver failed: " + error.flag_name() + ": " + error.what();
}

// Maps the exceptions of loading, running and writing onto exit codes.
int Guarded(const std::function<int()>& command) {
  try {
    return command();
  } catch (const ConfigError& error) {
    std::cerr << "error: " << error.what() << "\n";
    return kExitBadInput;
  } catch (const model::SolverError& error) {
    std::cerr << "error: " << SolverMessage(error) << "\n";
    return kExitSolverFailed;
  } catch (const std::exception& error) {  // ValidationError without a file, I/O errors
    std::cerr << "error: " << error.what() << "\n";
    return kExitBadInput;
  }
}

// RunScenario's ValidationErrors are about the scenario: locate them in its sources.
RunResult RunLocated(const Scenario& scenario, const std::vector<Override>& overrides) {
  try {
    return RunScenario(scenario);
  } catch (const ValidationError& error) {
    throw LocateValidationError(scenario.source_file, overrides, error);
  }
}

struct RunArgs {
  std::string scenario;
  std::vector<std::string> sets;
  bool json = false;
  std::string out_dir;
};

int RunCommand(const RunArgs& args) {
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  const Scenario scenario = LoadScenario(args.scenario, overrides);
  const RunResult result = RunLocated(scenario, overrides);
  for (const std::string& warning : result.command.warnings) {
    std::cerr << "warning: " << scenario.source_file << ": " << warning << "\n";
  }
  if (!args.out_dir.empty()) {
    // Created only now: bad input and solver failures leave no directory behind.
    std::filesystem::create_directories(args.out_dir);
    const std::filesystem::path dir(args.out_dir);
    WriteFileAtomically((dir / "metrics.json").string(), [&](std::ostream& out) {
      out << MetricsJson(result.metrics).dump(2) << "\n";
    });
    WriteTraceCsv((dir / "trace.csv").string(), result.trace);
    WriteDeflectionPlot((dir / "deflection.png").string(), result, scenario);
    WritePathPlot((dir / "path.png").string(), result, scenario);
  }
  if (args.json) {
    std::cout << MetricsJson(result.metrics).dump(2) << std::endl;
  } else {
    std::cout << "scenario " << scenario.name << " (" << scenario.source_file << ")\n";
    PrintMetricsTable(std::cout, result.metrics);
    std::cout.flush();
  }
  return kExitOk;
}

struct CheckArgs {
  std::vector<std::string> files;
  std::vector<std::string> sets;
  std::string junit;
};

int CheckCommand(const CheckArgs& args) {
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  // Every file is loaded before anything runs: bad input fails fast and writes nothing.
  std::vector<Scenario> scenarios;
  for (const std::string& file : args.files) {
    scenarios.push_back(LoadScenario(file, overrides));
    if (scenarios.back().checks.empty()) {
      throw ConfigError(file, 0, 0, "checks",
                        "no checks to evaluate; add e.g. checks: {peak_ratio: {max: 1.01}}");
    }
  }
  int exit_code = kExitOk;
  auto raise = [&](int code) {
    // Severity: bad input > solver failure > failed check.
    const int rank[] = {0, 1, 3, 2};
    if (rank[code] > rank[exit_code]) exit_code = code;
  };
  std::vector<ScenarioCheckReport> reports;
  for (const Scenario& scenario : scenarios) {
    ScenarioCheckReport report;
    report.file = scenario.source_file;
    report.name = scenario.name;
    const auto start = std::chrono::steady_clock::now();
    try {
      const RunResult result = RunLocated(scenario, overrides);
      report.results = EvaluateChecks(scenario.checks, result.metrics);
    } catch (const ConfigError& error) {
      report.error = error.what();
      std::cerr << "error: " << error.what() << "\n";
      raise(kExitBadInput);
    } catch (const model::SolverError& error) {
      report.error = SolverMessage(error);
      std::cerr << "error: " << report.error << " (" << report.file << ")\n";
      raise(kExitSolverFailed);
    }
    report.run_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const CheckResult& result : report.results) {
      std::cout << FormatCheckLine(report.file, result) << "\n";
      if (!result.passed) raise(kExitCheckFailed);
    }
    std::cout.flush();
    reports.push_back(report);
  }
  if (!args.junit.empty()) WriteJUnit(args.junit, reports);
  return exit_code;
}

struct ModesArgs {
  std::string file;
  std::vector<std::string> sets;
  bool json = false;
};

int ModesCommand(const ModesArgs& args) {
  // Every modelled axis; the static deflection SPEC names is the driven axis'.
  const model::MultiAxisMachineConfig machine =
      LoadMachineAxes(args.file, ParseOverrides(args.sets));
  const std::vector<model::AxisModes> axes = model::AnalyzeMachineModes(machine);
  if (args.json) {
    std::cout << ModesJson(axes, machine.driven_axis).dump(2) << std::endl;
  } else {
    PrintModesTable(std::cout, axes, machine.driven_axis);
  }
  return kExitOk;
}

struct PatternArgs {
  std::string file;
  std::vector<std::string> sets;
};

int PatternCommand(const PatternArgs& args) {
  LoadOptions options;
  options.plan_move = false;  // the pattern is shown whatever the move
  const Scenario scenario = LoadScenario(args.file, ParseOverrides(args.sets), options);
  PrintPatternReport(std::cout, scenario.controller);
  return kExitOk;
}

void AddSetOption(CLI::App* command, std::vector<std::string>* sets) {
  command
      ->add_option("--set", *sets,
                   "override one key, VALUE parsed as YAML (repeatable): --set a.b[0].c=VALUE")
      ->allow_extra_args(false)
      ->type_name("KEY=VALUE");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"shapebench: CNC vibration co-simulation testbench"};
  app.require_subcommand(1);

  RunArgs run_args;
  CLI::App* run = app.add_subcommand("run", "simulate one scenario");
  run->add_option("scenario", run_args.scenario, "scenario file")->required()->type_name("SCENARIO.yaml");
  AddSetOption(run, &run_args.sets);
  run->add_flag("--json", run_args.json, "print the metrics as one JSON object");
  run->add_option("--out", run_args.out_dir,
                  "write metrics.json, trace.csv and deflection.png into DIR (created)")
      ->type_name("DIR");

  CheckArgs check_args;
  CLI::App* check = app.add_subcommand("check", "run scenarios and evaluate their checks");
  check->add_option("files", check_args.files, "scenario files with checks:")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(check, &check_args.sets);
  check->add_option("--junit", check_args.junit, "write JUnit XML")->type_name("REPORT.xml");

  ModesArgs modes_args;
  CLI::App* modes = app.add_subcommand("modes", "modal analysis of the machine model");
  modes->add_option("file", modes_args.file, "machine or scenario file")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(modes, &modes_args.sets);
  modes->add_flag("--json", modes_args.json, "print one JSON object");

  PatternArgs pattern_args;
  CLI::App* pattern = app.add_subcommand(
      "pattern", "the shaping pattern as steps, impulses and profile table, with its residual");
  pattern->add_option("file", pattern_args.file, "scenario file")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(pattern, &pattern_args.sets);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help
    std::cerr << "error: " << error.what() << "\n";
    const auto parsed = app.get_subcommands();
    std::cerr << (parsed.empty() ? app.help() : parsed.back()->help());
    return kExitBadInput;
  }

  if (run->parsed()) return Guarded([&] { return RunCommand(run_args); });
  if (check->parsed()) return Guarded([&] { return CheckCommand(check_args); });
  if (modes->parsed()) return Guarded([&] { return ModesCommand(modes_args); });
  if (pattern->parsed()) return Guarded([&] { return PatternCommand(pattern_args); });
  return kExitBadInput;
}
