// What the commands of bench/cli share: exit codes, the exception-to-exit-code mapping,
// what the command is doing (for an out-of-memory message), the "wrote" lines, the
// common options, and stdout checked for write errors.
#pragma once

#include <functional>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/output/html_report.h"
#include "bench/run/run_scenario.h"
#include "bench/config/override.h"
#include "bench/scenario/scenario.h"
#include "bench/sweep/run_identity.h"
#include "common/exit_codes.h"
#include "common/fd_stream.h"

namespace shapebench::bench::cli {

// Text from the input as printed: its control characters visible, not obeyed by the terminal.
std::string Safe(const std::string& text);

// What the command is doing and what bounds its memory, for the message of a
// std::bad_alloc (which names neither). Set by each command as it goes.
void Doing(std::string doing, std::string memory = "");

// The memory bound of one run (limits.max_memory_mb) and of a sweep's `jobs` runs at once.
std::string RunMemory(const Scenario& scenario);
std::string SweepMemory(int jobs);

// Maps the exceptions of loading, running and writing onto exit codes.
int Guarded(const std::function<int()>& command);

// Every command with --out lists the files it wrote, one "wrote PATH" line each (PATH as
// DIR/FILE with DIR as given), after its report: on stdout, or on stderr with --json, so
// that stdout stays one JSON document (docs/concepts.md#what-a-run-writes).
void PrintWrote(std::ostream& out, const std::string& dir, const std::vector<std::string>& files);
void PrintWrote(std::ostream& out, const std::vector<std::string>& paths);

// --report FILE.html (bench/output/html_report.h), written complete or not at all.
void WriteReport(const std::string& path, const std::function<HtmlReport()>& build);

// The controller's warnings (a short-block clamp, a stroke alarm that dropped the rest of
// the program) and the run's (a cross-check that disagreed) on stderr.
void PrintRunWarnings(const std::string& file, const RunResult& result);

// --jobs: 0 means every hardware thread (MPI ranks on one host share its cores).
int JobsOrDefault(int jobs);

// Under mpirun (bench/sweep/sweep_mpi.h), before anything runs or is written: what
// `identity` makes plus this shapebench's version compared across the ranks
// (Distributor::Agree); rank 0 throws (exit 2) naming a rank that runs something else.
// Nothing (identity not called) without MPI.
void AgreeAcrossRanks(const std::function<RunIdentity()>& identity);
// The --set options as an identity shows them: "KEY=VALUE" joined by ", " ("" for none).
std::string SetsText(const std::vector<Override>& sets);

// --report of run, check, sweep and compare.
constexpr const char* kReportHelp =
    "write a self-contained HTML report (metrics, plots, checks, effective scenario) to FILE";

// --force of `sweep` and `check` (SweepLoadOptions::max_points).
constexpr const char* kForceHelp = "run a grid of more than 2,000,000 points";

void AddSetOption(CLI::App* command, std::vector<std::string>* sets, const std::string& name = "--set",
                  const std::string& help =
                      "override one key, VALUE parsed as YAML (repeatable): --set a.b[0].c=VALUE");

// stdout goes through a buffer that keeps write(2)'s errno: `run --json > FULL_DISK` fails
// naming the cause instead of exiting 0 with nothing written (stdio keeps no errno for a
// failed flush). Line-buffered on a terminal, as stdio is.
class CheckedStdout {
 public:
  CheckedStdout();
  ~CheckedStdout();
  CheckedStdout(const CheckedStdout&) = delete;
  CheckedStdout& operator=(const CheckedStdout&) = delete;

  // `code`, or 2 when stdout could not be written (a solver failure or an interruption kept).
  int Checked(int code);

 private:
  FdStreamBuf buffer_;
  std::streambuf* stdio_;
};

}  // namespace shapebench::bench::cli
