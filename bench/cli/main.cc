// shapebench command line: run, check, modes, pattern, sensitivity,
// sweep, merge, compare, identify, recommend.
// Exit codes: 0 ok; 1 a check or a compare gate failed; 2 bad input, usage, unwritable
// output (stdout included) or out of memory; 3 the solver failed. Errors go to stderr as
// "error: ...".
#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <typeinfo>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "common/atomic_file.h"
#include "common/fd_stream.h"
#include "bench/compare/compare.h"
#include "bench/compare/compare_html.h"
#include "bench/compare/compare_report.h"
#include "bench/compare/compare_runs.h"
#include "bench/compare/compare_sweep.h"
#include "bench/sim/checks.h"
#include "bench/sweep/band_check.h"
#include "bench/sim/cosim.h"
#include "common/interrupt.h"
#include "common/shown_text.h"
#include "bench/output/html_report.h"
#include "bench/output/identify_report.h"
#include "bench/output/modes_report.h"
#include "bench/output/pattern_report.h"
#include "bench/output/recommend_report.h"
#include "bench/output/output_path.h"
#include "bench/output/report.h"
#include "bench/sim/located_run.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_html.h"
#include "bench/sweep/sweep_files.h"
#include "bench/sweep/sweep_runner.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/slurm_array.h"
#include "bench/sweep/sweep_mpi.h"
#include "bench/sensitivity/sensitivity.h"
#include "common/validation_error.h"
#include "model/integrator.h"
#include "model/machine.h"
#include "bench/cli/shapebench_version.h"  // generated in the build tree: cmake/git_version.cmake

namespace {

using namespace shapebench;
using namespace shapebench::bench;

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

// Text from the input as printed: its control characters visible, not obeyed by the terminal.
std::string Safe(const std::string& text) { return TerminalSafe(text, /*keep_newlines=*/true); }

std::string SolverMessage(const model::SolverError& error) { return SolverFailureText(error); }

// What the command is doing and what bounds its memory, for the message of a
// std::bad_alloc (which names neither). Set by each command as it goes.
struct Activity {
  std::string doing = "starting";
  std::string memory;  // "" when no limit applies
};
Activity activity;

void Doing(std::string doing, std::string memory = "") {
  activity.doing = std::move(doing);
  activity.memory = std::move(memory);
}

// A run's bound: the estimate stayed under limits.max_memory_mb (bench/sim/run_memory.h),
// so the machine, or a limit on the process (ulimit -v), gave less than the scenario allows.
std::string RunMemory(const Scenario& scenario) {
  return "limits.max_memory_mb is " + std::to_string(scenario.limits.max_memory_mb) +
         " MB a run, more than this process could get: lower it (such a run is then refused "
         "before it starts), shorten the run or free memory";
}

std::string SweepMemory(int jobs) {
  return (jobs == 1 ? std::string("1 run at a time (--jobs 1)")
                    : std::to_string(jobs) + " runs at once (--jobs)") +
         ", each up to its limits.max_memory_mb: lower --jobs or limits.max_memory_mb";
}

// Out of memory is exit 2 like the memory guard's refusal (limits.max_memory_mb): the
// input asks for more than the machine gives, as an unwritable output is the machine's too.
int OutOfMemory() {
  std::cerr << "error: out of memory while " << Safe(activity.doing);
  if (!activity.memory.empty()) std::cerr << "; " << Safe(activity.memory);
  std::cerr << "\n";
  return kExitBadInput;
}

// Maps the exceptions of loading, running and writing onto exit codes.
int Guarded(const std::function<int()>& command) {
  try {
    return command();
  } catch (const std::bad_alloc&) {
    return OutOfMemory();
  } catch (const InterruptedError& error) {  // SIGINT, SIGTERM: 130, 143
    std::cerr << "error: " << Safe(error.what()) << "\n";
    return error.exit_code();
  } catch (const std::exception& error) {
    if (PendingInterrupt() != 0) {
      // E.g. gnuplot killed by the terminal's SIGINT: report the interruption.
      std::cerr << "error: interrupted by " << SignalName(PendingInterrupt()) << " (" << Safe(error.what())
                << ")\n";
      return 128 + PendingInterrupt();
    }
    if (const auto* config = dynamic_cast<const ConfigError*>(&error)) {
      std::cerr << "error: " << Safe(config->what()) << "\n";
      return kExitBadInput;
    }
    if (const auto* solver = dynamic_cast<const model::SolverError*>(&error)) {
      std::cerr << "error: " << Safe(SolverMessage(*solver)) << "\n";
      return kExitSolverFailed;
    }
    std::cerr << "error: " << Safe(error.what()) << "\n";  // ValidationError without a file, I/O
    return kExitBadInput;
  }
}

// Every command with --out lists the files it wrote, one "wrote PATH" line each (PATH as
// DIR/FILE with DIR as given), after its report: on stdout, or on stderr with --json, so
// that stdout stays one JSON document (docs/concepts.md#what-a-run-writes).
void PrintWrote(std::ostream& out, const std::string& dir, const std::vector<std::string>& files) {
  for (const std::string& file : files) {
    out << "wrote " << Safe((std::filesystem::path(dir) / file).string()) << "\n";
  }
  out.flush();
}

void PrintWrote(std::ostream& out, const std::vector<std::string>& paths) {
  for (const std::string& path : paths) out << "wrote " << Safe(path) << "\n";
  out.flush();
}

// RunScenario's ValidationErrors are about the scenario: located in its sources.
RunResult RunLocated(const Scenario& scenario, const std::vector<Override>& overrides) {
  return RunScenarioLocated(scenario, overrides);
}

// --report FILE.html (bench/output/html_report.h), written complete or not at all.
void WriteReport(const std::string& path, const std::function<HtmlReport()>& build) {
  Doing("writing the report " + path);
  const HtmlReport report = build();  // gnuplot runs here: before the deferral, so ^C stops it
  const DeferInterrupts defer;
  WriteHtmlReport(path, report);
  ThrowIfInterrupted(path + " is complete");
}

// The files of `run --out DIR`. Created only now: bad input and solver failures leave no
// directory behind. A new directory is filled under a temporary name and renamed when
// complete, so a failure (gnuplot, full disk) leaves none behind either. A signal while
// writing lets the files finish (each is complete or absent), then stops.
// deflection.png and path.png are left out when they would show nothing (a flat zero
// line, a line along one axis); a note on stderr says so. Returns the names of the files
// written.
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
    const std::string title = RunPlotTitle(scenario, overrides);
    written = {"metrics.json", "trace.csv"};
    if (DeflectionIsZero(result)) {
      std::cerr << "note: " << Safe(scenario.source_file) << ": no deflection.png: the deflection is "
                << "identically 0 (a rigid machine, no states)\n";
    } else {
      WriteDeflectionPlot((dir / "deflection.png").string(), result, scenario, title);
      written.push_back("deflection.png");
    }
    if (PathIsSingleAxisLine(result)) {
      std::cerr << "note: " << Safe(scenario.source_file) << ": no path.png: the programmed path is a "
                << "straight move along one axis (its XY plot would be a line)\n";
    } else {
      WritePathPlot((dir / "path.png").string(), result, scenario, title);
      written.push_back("path.png");
    }
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  ThrowIfInterrupted("the output in " + out_dir + " is complete");
  return written;
}

// The controller's warnings (a short-block clamp, a stroke alarm that dropped the rest of
// the program) and the run's (a cross-check that disagreed) on stderr.
void PrintRunWarnings(const std::string& file, const RunResult& result) {
  for (const std::string& warning : result.command.warnings) {
    std::cerr << "warning: " << Safe(file) << ": " << Safe(warning) << "\n";
  }
  for (const std::string& warning : result.warnings) {
    std::cerr << "warning: " << Safe(file) << ": " << Safe(warning) << "\n";
  }
}

struct RunArgs {
  std::string scenario;
  std::vector<std::string> sets;
  bool json = false;
  std::string out_dir;
  std::string report;  // --report FILE.html
};

int RunCommand(const RunArgs& args) {
  if (!args.report.empty()) ValidateReportPath(args.report);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the run
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  Doing("loading " + args.scenario);
  const Scenario scenario = LoadScenario(args.scenario, overrides);
  Doing("running scenario '" + scenario.name + "' (" + scenario.source_file + ")", RunMemory(scenario));
  const RunResult result = RunLocated(scenario, overrides);
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
    PrintMetricsTable(std::cout, result.metrics);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

struct CheckArgs {
  std::vector<std::string> files;
  std::vector<std::string> sets;
  std::string junit;
  std::string report;  // --report FILE.html
  bool json = false;  // the results as one JSON object instead of the lines
  int jobs = 0;  // sweep files: worker threads (0: every hardware thread)
  bool force = false;  // sweep files: load a grid above SweepLoadOptions::max_points
};

int JobsOrDefault(int jobs) {
  return jobs > 0 ? jobs : DefaultJobs();  // MPI ranks on one host share its cores
}

int CheckCommand(const CheckArgs& args) {
  if (!args.report.empty()) ValidateReportPath(args.report);  // before anything runs
  if (!args.junit.empty()) RequireWritableOutputFile("--junit", args.junit);  // before the runs
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  // Every file is loaded before anything runs: bad input fails fast and writes nothing.
  // A file with base: and grid: is a sweep: its checks apply to every point.
  std::vector<Scenario> scenarios;
  std::vector<std::optional<Sweep>> sweeps;
  SweepLoadOptions load;
  load.force = args.force;  // as `sweep --force`: the grid's refusal tells the user to pass it
  for (const std::string& file : args.files) {
    Doing("loading " + file);
    const bool sweep = IsSweepFile(file);
    sweeps.push_back(sweep ? std::optional<Sweep>(LoadSweep(file, overrides, load)) : std::nullopt);
    if (sweep && !sweeps.back()->note.empty() && !IsDistributedWorker()) std::cerr << sweeps.back()->note << "\n";
    scenarios.push_back(sweep ? Scenario{} : LoadScenario(file, overrides));
    if (sweep ? sweeps.back()->checks.empty() && sweeps.back()->gates.empty() : scenarios.back().checks.empty()) {
      throw ConfigError(file, 0, 0, "checks",
                        "no checks to evaluate; add e.g. checks: {peak_ratio: {max: 1.01}}");
    }
    if (!sweep) ValidateBandChecks(scenarios.back(), overrides);
  }
  if (IsDistributedWorker()) {  // an MPI rank other than 0 (bench/sweep/sweep_mpi.h)
    for (const auto& sweep : sweeps) {
      if (sweep) ServeCheckSweep(*sweep, overrides, JobsOrDefault(args.jobs));
    }
    return kExitOk;
  }
  int exit_code = kExitOk;
  auto raise = [&](int code) {
    // Severity: bad input > solver failure > failed check.
    const int rank[] = {0, 1, 3, 2};
    if (rank[code] > rank[exit_code]) exit_code = code;
  };
  std::vector<ScenarioCheckReport> reports;
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const Scenario& scenario = scenarios[i];
    ScenarioCheckReport report;
    if (sweeps[i]) {
      Doing("checking sweep '" + sweeps[i]->name + "' (" + sweeps[i]->file + ")",
            SweepMemory(JobsOrDefault(args.jobs)));
      std::ostringstream not_shown;  // --json: the JSON replaces the lines
      raise(CheckSweep(*sweeps[i], overrides, JobsOrDefault(args.jobs),
                       args.json ? static_cast<std::ostream&>(not_shown) : std::cout, std::cerr,
                       &report));
      reports.push_back(report);
      continue;
    }
    report.file = scenario.source_file;
    report.name = scenario.name;
    const auto start = std::chrono::steady_clock::now();
    Doing("running scenario '" + scenario.name + "' (" + scenario.source_file + ")", RunMemory(scenario));
    try {
      const RunResult result = RunLocated(scenario, overrides);
      PrintRunWarnings(scenario.source_file, result);
      report.results = EvaluateScenarioChecks(scenario, overrides, result.metrics);
    } catch (const ConfigError& error) {
      report.error = error.what();
      std::cerr << "error: " << Safe(error.what()) << "\n";
      raise(kExitBadInput);
    } catch (const model::SolverError& error) {
      report.error = SolverMessage(error);
      std::cerr << "error: " << Safe(report.error) << " (" << Safe(report.file) << ")\n";
      raise(kExitSolverFailed);
    }
    report.run_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Its checks share the run (and a band check's runs): each testcase is given its time.
    for (CheckResult& result : report.results) result.run_time_s = report.run_time_s;
    for (const CheckResult& result : report.results) {
      if (!args.json) std::cout << Safe(FormatCheckLine(report.file, result)) << "\n";
      if (!result.passed) raise(kExitCheckFailed);
    }
    std::cout.flush();
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
  return exit_code;
}

struct ModesArgs {
  std::string file;
  std::vector<std::string> sets;
  bool json = false;
};

int ModesCommand(const ModesArgs& args) {
  // Every modelled axis; the static deflection reported is the driven axis'.
  Doing("analysing the modes of " + args.file);
  const model::MultiAxisMachineConfig machine =
      LoadMachineAxes(args.file, ParseOverrides(args.sets));
  const std::vector<model::AxisModes> axes = model::AnalyzeMachineModes(machine);
  if (args.json) {
    nlohmann::ordered_json json = ModesJson(axes, machine.driven_axis);
    AddModesCouplingJson(machine, &json);  // a coupled machine's compliance and mode vectors
    std::cout << json.dump(2) << std::endl;
  } else {
    PrintModesTable(std::cout, axes, machine.driven_axis);
    PrintModesCoupling(std::cout, machine);
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
  Doing("showing the pattern of " + args.file);
  const Scenario scenario = LoadScenario(args.file, ParseOverrides(args.sets), options);
  PrintPatternReport(std::cout, scenario);  // with the time penalty of its move or program
  return kExitOk;
}

struct SensitivityArgs {
  std::string file;
  std::vector<std::string> sets;
  std::string out_dir;
};

// Residual vibration vs plant frequency / design frequency per shaper (bench/sensitivity/sensitivity.h).
int SensitivityCommand(const SensitivityArgs& args) {
  Doing("computing the sensitivity curves of " + args.file);
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  const SensitivitySpec spec = LoadSensitivity(args.file, ParseOverrides(args.sets));
  const SensitivityResult result = ComputeSensitivity(spec);
  if (!args.out_dir.empty()) {
    const DeferInterrupts defer;
    std::error_code ec;
    std::filesystem::create_directories(args.out_dir, ec);
    if (ec || !std::filesystem::is_directory(args.out_dir)) {
      throw std::runtime_error("cannot create " + args.out_dir + ": " +
                               (ec ? ec.message() : "not a directory"));
    }
    const std::filesystem::path dir(args.out_dir);
    WriteSensitivityCsv((dir / "sensitivity.csv").string(), result);
    WriteSensitivityPlot((dir / "sensitivity.png").string(), result,
                         "shaper sensitivity: " + std::filesystem::path(args.file).stem().string());
    ThrowIfInterrupted("the output in " + args.out_dir + " is complete");
  }
  PrintSensitivityTable(std::cout, result);
  if (!args.out_dir.empty()) PrintWrote(std::cout, args.out_dir, {"sensitivity.csv", "sensitivity.png"});
  std::cout.flush();
  return kExitOk;
}

struct SweepArgs {
  std::string file;
  std::vector<std::string> sets;
  int jobs = 0;
  std::string out_dir;
  std::string shard;
  std::string report;  // --report FILE.html
  bool force = false;
  bool no_sync = false;
};

// --shard I/N: I in 0..N-1 (the points p with p % N == I).
void ParseShard(const std::string& text, SweepRunOptions* options) {
  const std::size_t slash = text.find('/');
  const auto digits = [](const std::string& part) {
    return !part.empty() && part.size() <= 9 &&
           part.find_first_not_of("0123456789") == std::string::npos;
  };
  const std::string index = slash == std::string::npos ? "" : text.substr(0, slash);
  const std::string count = slash == std::string::npos ? "" : text.substr(slash + 1);
  if (!digits(index) || !digits(count) || std::stoul(count) < 1 ||
      std::stoul(index) >= std::stoul(count)) {
    throw std::runtime_error("--shard: expected I/N with N >= 1 and I in 0..N-1 (e.g. 0/4), got '" +
                             text + "'");
  }
  options->shard_index = std::stoul(index);
  options->shard_count = std::stoul(count);
}

// A grid of runs (bench/sweep/sweep.h, bench/sweep/sweep_runner.h): results.csv, plots.
int SweepCommand(const SweepArgs& args) {
  if (!args.report.empty()) ValidateReportPath(args.report);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the points
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  SweepRunOptions options;
  if (!args.shard.empty()) ParseShard(args.shard, &options);
  // In a Slurm job array without --shard: this task's shard, in DIR/shard-I-of-N.
  const std::optional<ArrayShard> array = args.shard.empty() ? SlurmArrayShard() : std::nullopt;
  if (array) {
    options.shard_index = array->index;
    options.shard_count = array->count;
  }
  SweepLoadOptions load;
  load.force = args.force;
  Doing("loading " + args.file);
  const Sweep sweep = LoadSweep(args.file, overrides, load);
  if (!sweep.note.empty() && !IsDistributedWorker()) std::cerr << sweep.note << "\n";
  options.out_dir = args.out_dir.empty()
                        ? (std::filesystem::path("sweep_out") / sweep.name).string()
                        : args.out_dir;
  if (array) options.out_dir = ArrayShardDir(options.out_dir, *array);
  options.jobs = JobsOrDefault(args.jobs);
  if (args.no_sync) options.durability = Durability::kUnsynced;
  if (IsDistributedWorker()) {  // an MPI rank other than 0 (bench/sweep/sweep_mpi.h)
    ServeSweep(sweep, overrides, options);
    return kExitOk;
  }
  options.progress = isatty(STDERR_FILENO) != 0;
  Doing("running sweep '" + sweep.name + "' (" + sweep.file + ") into " + options.out_dir,
        SweepMemory(options.jobs) + "; the complete rows are kept, the same command resumes");
  const SweepRunSummary summary = RunSweep(sweep, overrides, options);
  std::cout << "sweep " << Safe(sweep.name) << ": " << summary.points << " points";
  if (options.shard_count > 1) {
    std::cout << " (shard " << options.shard_index << "/" << options.shard_count << " of "
              << sweep.points << ")";
  }
  std::cout << ", " << summary.ok << " ok, " << summary.errors << " error";
  if (summary.resumed > 0) std::cout << " (" << summary.resumed << " done before)";
  std::cout << " -> " << summary.results << "\n";
  PrintWrote(std::cout, {(std::filesystem::path(summary.results).parent_path() / kSweepManifestFile).string(),
                        summary.results});
  PrintWrote(std::cout, summary.plots);
  std::cout.flush();
  if (!args.report.empty()) {
    WriteReport(args.report, [&] { return SweepHtmlReport(ReadSweepHtmlData(sweep, overrides, summary.results)); });
  }
  return kExitOk;
}

struct MergeArgs {
  std::vector<std::string> dirs;
  std::string out_dir;
};

// Joins shard outputs into the unsharded results.csv (bench/sweep/sweep_runner.h).
int MergeCommand(const MergeArgs& args) {
  std::vector<std::string> shards = args.dirs;
  std::string out_dir = args.out_dir;
  if (out_dir.empty()) {
    if (shards.size() < 2) {
      throw std::runtime_error("merge: expected OUT_DIR SHARD_DIR... (or --out OUT_DIR SHARD_DIR...)");
    }
    out_dir = shards.front();
    shards.erase(shards.begin());
  }
  const DeferInterrupts defer;
  Doing("merging shards into " + out_dir);
  const MergeSummary summary = MergeShards(out_dir, shards);
  ThrowIfInterrupted("the merged output in " + out_dir + " is complete");
  std::cout << "merged " << summary.shards << " shards: " << summary.points << " points -> "
            << summary.results << "\n";
  PrintWrote(std::cout, {(std::filesystem::path(summary.results).parent_path() / kSweepManifestFile).string(),
                        summary.results});
  PrintWrote(std::cout, summary.plots);
  return kExitOk;
}

// stdout goes through a buffer that keeps write(2)'s errno: `run --json > FULL_DISK` fails
// naming the cause instead of exiting 0 with nothing written (stdio keeps no errno for a
// failed flush). Line-buffered on a terminal, as stdio is.
class CheckedStdout {
 public:
  CheckedStdout()
      : buffer_(STDOUT_FILENO, isatty(STDOUT_FILENO) != 0), stdio_(std::cout.rdbuf(&buffer_)) {}
  ~CheckedStdout() {
    std::cout.flush();
    std::cout.rdbuf(stdio_);
  }
  CheckedStdout(const CheckedStdout&) = delete;
  CheckedStdout& operator=(const CheckedStdout&) = delete;

  // `code`, or 2 when stdout could not be written (a solver failure or an interruption kept).
  int Checked(int code) {
    std::cout.flush();
    if (buffer_.error() == 0) return code;
    std::cerr << "error: cannot write standard output: " << std::strerror(buffer_.error()) << "\n";
    return code == kExitOk || code == kExitCheckFailed ? kExitBadInput : code;
  }

 private:
  FdStreamBuf buffer_;
  std::streambuf* stdio_;
};

// --report of run, check, sweep and compare.
constexpr const char* kReportHelp =
    "write a self-contained HTML report (metrics, plots, checks, effective scenario) to FILE";

// --force of `sweep` and `check` (SweepLoadOptions::max_points).
constexpr const char* kForceHelp = "run a grid of more than 2,000,000 points";

void AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                  const std::string& name = "--set",
                  const std::string& help =
                      "override one key, VALUE parsed as YAML (repeatable): --set a.b[0].c=VALUE") {
  command->add_option(name, *sets, help)->allow_extra_args(false)->type_name("KEY=VALUE");
}

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

// Two scenarios or two sweeps side by side (bench/compare/, docs/compare.md): exit 1 when
// a gate fails; a sweep's point that fails to run makes it 2 or 3, as `check` ranks them.
int CompareCommand(const CompareArgs& args) {
  const std::vector<Gate> gates = ParseGates(args.gates);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  const CompareRequest request{args.baseline, args.candidate, args.sets, args.baseline_sets,
                               args.candidate_sets};
  const bool sweep = IsSweepFile(args.baseline);
  if (!args.report.empty()) {
    if (sweep) throw std::runtime_error("compare --report: two scenarios only (a sweep's: sweep --report)");
    ValidateReportPath(args.report);  // before anything runs
  }
  if (!args.candidate.empty() && IsSweepFile(args.candidate) != sweep) {
    throw std::runtime_error("compare: " + (sweep ? args.baseline : args.candidate) +
                             " is a sweep file (base:, grid:), " + (sweep ? args.candidate : args.baseline) +
                             " is not: give two scenarios or two sweeps");
  }
  if (sweep) {
    const ComparedSweeps sweeps = LoadComparedSweeps(request);
    const int jobs = JobsOrDefault(args.jobs);
    const SweepComparison comparison =
        args.out_dir.empty() ? CompareSweeps(sweeps, gates, jobs, nullptr, std::cerr)
                             : CompareSweepsWritingTo(args.out_dir, sweeps, gates, jobs, std::cerr);
    if (args.json) {
      std::cout << ComparisonJson(comparison).dump(2) << std::endl;
    } else {
      PrintComparison(std::cout, comparison);
      std::cout.flush();
    }
    if (!args.out_dir.empty()) {  // the files of CompareSweepsWritingTo
      PrintWrote(args.json ? std::cerr : std::cout, args.out_dir,
                 {"points.csv", "compare.txt", "compare.json"});
    }
    if (comparison.point_exit_code != 0) return comparison.point_exit_code;
    return comparison.passed() ? kExitOk : kExitCheckFailed;
  }
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
    PrintWrote(args.json ? std::cerr : std::cout, args.out_dir,
               {"compare.txt", "compare.json", "deflection.png"});
  }
  return comparison.passed() ? kExitOk : kExitCheckFailed;
}

CLI::App* AddCompareCommand(CLI::App* app, CompareArgs* args) {
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
  return compare;
}

// `sweep`: a grid of scenarios into an output directory (SweepCommand).
CLI::App* AddSweepCommand(CLI::App* app, SweepArgs* args) {
  CLI::App* sweep = app->add_subcommand("sweep", "run a grid of scenarios: results.csv and plots");
  sweep->add_option("sweep", args->file, "sweep file (base:, grid:, ...)")
      ->required()
      ->type_name("SWEEP.yaml");
  AddSetOption(sweep, &args->sets);
  sweep->add_option("--jobs", args->jobs, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096))
      ->type_name("N");
  sweep->add_option("--out", args->out_dir,
                    "output directory (default: sweep_out/NAME); run again to resume")
      ->type_name("DIR");
  sweep->add_option("--shard", args->shard,
                    "run the points p with p % N == I only (I in 0..N-1); join with merge")
      ->type_name("I/N");
  sweep->add_option("--report", args->report, kReportHelp)->type_name("FILE.html");
  sweep->add_flag("--force", args->force, kForceHelp);
  sweep->add_flag("--no-sync", args->no_sync,
                  "do not sync manifest.json and results.csv to the disk (scratch output: a "
                  "crash of the machine may lose them; a killed sweep still resumes)");
  return sweep;
}

// Modes from measured FRFs (bench/output/identify_report.h, docs/measured-data.md).
CLI::App* AddIdentifyCommand(CLI::App* app, IdentifyArgs* args) {
  CLI::App* identify = app->add_subcommand(
      "identify", "modal parameters from measured FRFs (UFF 58): table or JSON, stabilisation diagram");
  identify->add_option("file", args->file, "UFF file of dataset 58 FRF records (ASCII or 58b)")
      ->required()
      ->type_name("FILE.uff");
  identify->add_option("--axis", args->axis, "only the records whose response is along this axis")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->type_name("x|y|z");
  identify->add_option("--band", args->band, "the band in Hz the modes are identified in (default: all lines)")
      ->type_name("MIN:MAX");
  identify->add_option("--max-order", args->max_order, "highest model order in pole pairs (default 30)")
      ->check(CLI::Range(1, 200))
      ->type_name("N");
  identify->add_flag("--json", args->json, "print one JSON object");
  identify->add_option("--out", args->out_dir,
                       "write modes.json and stabilisation.png into DIR (default: identify_out/STEM)")
      ->type_name("DIR");
  return identify;
}

int IdentifyCommand(const IdentifyArgs& args) {
  Doing("identifying the modes of " + args.file);
  return RunIdentify(args, std::cout, args.json ? std::cerr : std::cout);
}

// A shaper recommended from an accelerometer log (bench/output/recommend_report.h).
int RecommendCommand(const RecommendArgs& args) {
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the fit
  Doing("fitting the shapers to " + args.file);
  const RecommendReport report = ComputeRecommendation(args);
  std::vector<std::string> written;
  if (!args.out_dir.empty()) {
    const DeferInterrupts defer;
    written = WriteRecommendOutputs(args.out_dir, report);
    ThrowIfInterrupted("the output in " + args.out_dir + " is complete");
  }
  if (args.json) {
    std::cout << RecommendJson(report).dump(2) << std::endl;
  } else {
    PrintRecommendation(std::cout, report);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

CLI::App* AddRecommendCommand(CLI::App* app, RecommendArgs* args) {
  CLI::App* recommend = app->add_subcommand(
      "recommend", "fit every shaper of the registry to an accelerometer log's PSD and recommend one");
  recommend->add_option("file", args->file, "accelerometer log: #time,accel_x,accel_y,accel_z (s, mm/s^2)")
      ->required()
      ->type_name("FILE.csv");
  recommend->add_option("--axis", args->axis, "x, y, z or all (the sum of the three PSDs; default)")
      ->type_name("AXIS");
  recommend->add_option("--damping-ratio", args->damping_ratio, "the library shapers' design damping (default 0.1)")
      ->type_name("ZETA");
  recommend->add_option("--feed-mm-min", args->feed_mm_min, "feed of the smoothing's circle (default 6000)")
      ->type_name("F");
  recommend->add_option("--accel-mm-s2", args->accel_mm_s2, "acceleration of the smoothing's circle (default 5000)")
      ->type_name("A");
  recommend->add_flag("--json", args->json, "print the fit as one JSON object");
  recommend->add_option("--out", args->out_dir, "write recommend.json, psd.csv and recommend.png into DIR")
      ->type_name("DIR");
  recommend
      ->add_option("--validate", args->validate,
                   "run SCENARIO with the log's modes in place of its machine, unshaped and with the "
                   "recommendation")
      ->type_name("SCENARIO.yaml");
  recommend->footer("docs/measured-data.md#accelerometer-logs");
  return recommend;
}

}  // namespace

int main(int argc, char** argv) {
  InstallInterruptHandlers();  // SIGINT, SIGTERM: complete files only (common/interrupt.h)
  MpiRun mpi;  // under mpirun: sweep and check spread over the ranks (bench/sweep/sweep_mpi.h)
  CheckedStdout stdout_checked;
  CLI::App app{"shapebench: CNC vibration co-simulation testbench"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shapebench ") + SHAPEBENCH_VERSION,
                       "print shapebench and the git describe of its source tree, then exit");

  RunArgs run_args;
  CLI::App* run = app.add_subcommand("run", "simulate one scenario");
  run->add_option("scenario", run_args.scenario, "scenario file")->required()->type_name("SCENARIO.yaml");
  AddSetOption(run, &run_args.sets);
  run->add_flag("--json", run_args.json, "print the metrics as one JSON object");
  run->add_option("--out", run_args.out_dir,
                  "write metrics.json, trace.csv and deflection.png into DIR (created)")
      ->type_name("DIR");
  run->add_option("--report", run_args.report, kReportHelp)->type_name("FILE.html");

  CheckArgs check_args;
  CLI::App* check = app.add_subcommand("check", "run scenarios and evaluate their checks");
  check->add_option("files", check_args.files, "scenario or sweep files with checks:")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(check, &check_args.sets);
  check->add_option("--junit", check_args.junit, "write JUnit XML")->type_name("REPORT.xml");
  check->add_option("--report", check_args.report, kReportHelp)->type_name("FILE.html");
  check->add_flag("--json", check_args.json,
                  "print the results as one JSON object (band checks: worst value and where)");
  check->add_option("--jobs", check_args.jobs, "sweep files: worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096))
      ->type_name("N");
  check->add_flag("--force", check_args.force, kForceHelp);

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

  SensitivityArgs sensitivity_args;
  CLI::App* sensitivity = app.add_subcommand(
      "sensitivity", "residual vibration of shapers vs plant frequency / design frequency");
  sensitivity->add_option("file", sensitivity_args.file, "sensitivity file (shapers:, ratio:, ...)")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(sensitivity, &sensitivity_args.sets);
  sensitivity->add_option("--out", sensitivity_args.out_dir,
                          "write sensitivity.csv and sensitivity.png into DIR (created)")
      ->type_name("DIR");

  SweepArgs sweep_args;
  CLI::App* sweep = AddSweepCommand(&app, &sweep_args);

  MergeArgs merge_args;
  CLI::App* merge = app.add_subcommand("merge", "join the shards of a sweep into one results.csv");
  merge->add_option("dirs", merge_args.dirs, "OUT_DIR then the shards' --out directories")
      ->required()
      ->type_name("DIR");
  merge->add_option("--out", merge_args.out_dir, "output directory (then every DIR is a shard)")
      ->type_name("OUT_DIR");

  CompareArgs compare_args;
  CLI::App* compare = AddCompareCommand(&app, &compare_args);

  IdentifyArgs identify_args;
  CLI::App* identify = AddIdentifyCommand(&app, &identify_args);
  RecommendArgs recommend_args;
  CLI::App* recommend = AddRecommendCommand(&app, &recommend_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return stdout_checked.Checked(app.exit(error));  // --help
    std::cerr << "error: " << Safe(error.what()) << "\n";
    const auto parsed = app.get_subcommands();
    std::cerr << (parsed.empty() ? app.help() : parsed.back()->help());
    return kExitBadInput;
  }

  int code = kExitBadInput;
  if (IsDistributedWorker() && !sweep->parsed() && !check->parsed()) return mpi.Finish(kExitOk);
  if (run->parsed()) code = Guarded([&] { return RunCommand(run_args); });
  if (check->parsed()) code = Guarded([&] { return CheckCommand(check_args); });
  if (modes->parsed()) code = Guarded([&] { return ModesCommand(modes_args); });
  if (pattern->parsed()) code = Guarded([&] { return PatternCommand(pattern_args); });
  if (sensitivity->parsed()) code = Guarded([&] { return SensitivityCommand(sensitivity_args); });
  if (sweep->parsed()) code = Guarded([&] { return SweepCommand(sweep_args); });
  if (merge->parsed()) code = Guarded([&] { return MergeCommand(merge_args); });
  if (compare->parsed()) code = Guarded([&] { return CompareCommand(compare_args); });
  if (identify->parsed()) code = Guarded([&] { return IdentifyCommand(identify_args); });
  if (recommend->parsed()) code = Guarded([&] { return RecommendCommand(recommend_args); });
  return stdout_checked.Checked(mpi.Finish(code));
}
