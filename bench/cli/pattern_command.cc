// `shapebench pattern FILE.yaml`: the scenario's shaping pattern as steps, impulses and
// profile table, with its residual and the time penalty of its move or program.
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/output/pattern_report.h"
#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench::cli {
namespace {

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

}  // namespace

Command AddPatternCommand(CLI::App* app) {
  auto args = std::make_shared<PatternArgs>();
  CLI::App* pattern = app->add_subcommand(
      "pattern", "the shaping pattern as steps, impulses and profile table, with its residual");
  pattern->add_option("file", args->file, "scenario file")->required()->type_name("FILE.yaml");
  AddSetOption(pattern, &args->sets);
  return {pattern, [args] { return PatternCommand(*args); }};
}

}  // namespace shapebench::bench::cli
