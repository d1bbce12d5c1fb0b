#include "bench/cli/cli_support.h"

#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>
#include <utility>

#include <unistd.h>

#include "bench/cli/shapebench_version.h"  // generated in the build tree: cmake/git_version.cmake
#include "bench/config/config_error.h"
#include "bench/run/located_run.h"
#include "bench/sweep/distribute.h"
#include "common/interrupt.h"
#include "common/shown_text.h"
#include "model/integrator.h"

namespace shapebench::bench::cli {
namespace {

struct Activity {
  std::string doing = "starting";
  std::string memory;  // "" when no limit applies
};
Activity activity;

// Out of memory is exit 2 like the memory guard's refusal (limits.max_memory_mb): the
// input asks for more than the machine gives, as an unwritable output is the machine's too.
int OutOfMemory() {
  std::cerr << "error: out of memory while " << Safe(activity.doing);
  if (!activity.memory.empty()) std::cerr << "; " << Safe(activity.memory);
  std::cerr << "\n";
  return kExitBadInput;
}

}  // namespace

std::string Safe(const std::string& text) { return TerminalSafe(text, /*keep_newlines=*/true); }

void Doing(std::string doing, std::string memory) {
  activity.doing = std::move(doing);
  activity.memory = std::move(memory);
}

// A run's bound: the estimate stayed under limits.max_memory_mb (bench/scenario/run_memory.h),
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
      std::cerr << "error: " << Safe(SolverFailureText(*solver)) << "\n";
      return kExitSolverFailed;
    }
    std::cerr << "error: " << Safe(error.what()) << "\n";  // ValidationError without a file, I/O
    return kExitBadInput;
  }
}

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

void WriteReport(const std::string& path, const std::function<HtmlReport()>& build) {
  Doing("writing the report " + path);
  const HtmlReport report = build();  // gnuplot runs here: before the deferral, so ^C stops it
  const DeferInterrupts defer;
  WriteHtmlReport(path, report);
  ThrowIfInterrupted(path + " is complete");
}

void PrintRunWarnings(const std::string& file, const RunResult& result) {
  for (const std::string& warning : result.command.warnings) {
    std::cerr << "warning: " << Safe(file) << ": " << Safe(warning) << "\n";
  }
  for (const std::string& warning : result.warnings) {
    std::cerr << "warning: " << Safe(file) << ": " << Safe(warning) << "\n";
  }
}

int JobsOrDefault(int jobs) { return jobs > 0 ? jobs : DefaultJobs(); }

void AgreeAcrossRanks(const std::function<RunIdentity()>& identity) {
  if (CurrentDistributor() == nullptr) return;  // no MPI: one process, nothing to compare
  RunIdentity mine = identity();
  mine.Add("shapebench version", SHAPEBENCH_VERSION);
  CurrentDistributor()->Agree(mine.Encode());
}

std::string SetsText(const std::vector<Override>& sets) {
  std::string text;
  for (const Override& set : sets) text += (text.empty() ? "" : ", ") + set.key_path + "=" + set.value_yaml;
  return text;
}

void AddSetOption(CLI::App* command, std::vector<std::string>* sets, const std::string& name,
                  const std::string& help) {
  command->add_option(name, *sets, help)->allow_extra_args(false)->type_name("KEY=VALUE");
}

CheckedStdout::CheckedStdout()
    : buffer_(STDOUT_FILENO, isatty(STDOUT_FILENO) != 0), stdio_(std::cout.rdbuf(&buffer_)) {}

CheckedStdout::~CheckedStdout() {
  std::cout.flush();
  std::cout.rdbuf(stdio_);
}

int CheckedStdout::Checked(int code) {
  std::cout.flush();
  if (buffer_.error() == 0) return code;
  std::cerr << "error: cannot write standard output: " << std::strerror(buffer_.error()) << "\n";
  return code == kExitOk || code == kExitCheckFailed ? kExitBadInput : code;
}

}  // namespace shapebench::bench::cli
