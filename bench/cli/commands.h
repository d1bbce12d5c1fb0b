// The subcommands of shapebench, one file each (bench/cli/*_command.cc). main.cc adds
// them in the order of its table and runs the one parsed.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace shapebench::bench::cli {

// One subcommand: added to the app with its options; `run` runs it once parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
  bool on_every_rank = false;  // sweep, check: the MPI ranks other than 0 serve it
};

Command AddRunCommand(CLI::App* app);
Command AddCheckCommand(CLI::App* app);
Command AddModesCommand(CLI::App* app);
Command AddPatternCommand(CLI::App* app);
Command AddBodeCommand(CLI::App* app);
Command AddSensitivityCommand(CLI::App* app);
Command AddSweepCommand(CLI::App* app);
Command AddMergeCommand(CLI::App* app);
Command AddCompareCommand(CLI::App* app);
Command AddIdentifyCommand(CLI::App* app);
Command AddRecommendCommand(CLI::App* app);
Command AddDesignCommand(CLI::App* app);
Command AddFmuCommand(CLI::App* app);

}  // namespace shapebench::bench::cli
