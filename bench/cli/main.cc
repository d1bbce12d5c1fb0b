// shapebench command line: run, check, modes, pattern, bode, sensitivity,
// sweep, merge, compare, identify, recommend, design (one file each: bench/cli/*_command.cc).
// Exit codes: 0 ok; 1 a check or a compare gate failed; 2 bad input, usage, unwritable
// output (stdout included) or out of memory; 3 the solver failed. Errors go to stderr as
// "error: ...".
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/cli/shapebench_version.h"  // generated in the build tree: cmake/git_version.cmake
#include "bench/sweep/distribute.h"
#include "bench/sweep/sweep_mpi.h"
#include "common/interrupt.h"

namespace {

using namespace shapebench::bench::cli;
using shapebench::kExitBadInput;
using shapebench::kExitOk;

// The commands in the order `shapebench --help` lists them.
constexpr Command (*kCommands[])(CLI::App*) = {
    AddRunCommand,         AddCheckCommand, AddModesCommand, AddPatternCommand,  AddBodeCommand,
    AddSensitivityCommand, AddSweepCommand, AddMergeCommand, AddCompareCommand,  AddIdentifyCommand,
    AddRecommendCommand,   AddDesignCommand, AddFmuCommand,
};

}  // namespace

int main(int argc, char** argv) {
  shapebench::InstallInterruptHandlers();  // SIGINT, SIGTERM: complete files only (common/interrupt.h)
  shapebench::bench::MpiRun mpi;  // under mpirun: sweep and check spread over the ranks (bench/sweep/sweep_mpi.h)
  CheckedStdout stdout_checked;
  CLI::App app{"shapebench: CNC vibration co-simulation testbench"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("shapebench ") + SHAPEBENCH_VERSION,
                       "print shapebench and the git describe of its source tree, then exit");
  std::vector<Command> commands;
  for (const auto add : kCommands) commands.push_back(add(&app));

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
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    // An MPI rank other than 0 serves sweep and check only.
    if (shapebench::bench::IsDistributedWorker() && !command.on_every_rank) return mpi.Finish(kExitOk);
    code = Guarded(command.run);
  }
  return stdout_checked.Checked(mpi.Finish(code));
}
