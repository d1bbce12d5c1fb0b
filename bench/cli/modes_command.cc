// `shapebench modes FILE.yaml`: the modal analysis of a machine model, every modelled axis.
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/output/modes_report.h"
#include "bench/scenario/scenario_loader.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench::cli {
namespace {

struct ModesArgs {
  std::string file;
  std::vector<std::string> sets;
  bool json = false;
};

int ModesCommand(const ModesArgs& args) {
  // Every modelled axis; the static deflection reported is the driven axis'.
  Doing("analysing the modes of " + args.file);
  const model::MultiAxisMachineConfig machine = LoadMachineAxes(args.file, ParseOverrides(args.sets));
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

}  // namespace

Command AddModesCommand(CLI::App* app) {
  auto args = std::make_shared<ModesArgs>();
  CLI::App* modes = app->add_subcommand("modes", "modal analysis of the machine model");
  modes->add_option("file", args->file, "machine or scenario file")->required()->type_name("FILE.yaml");
  AddSetOption(modes, &args->sets);
  modes->add_flag("--json", args->json, "print one JSON object");
  return {modes, [args] { return ModesCommand(*args); }};
}

}  // namespace shapebench::bench::cli
