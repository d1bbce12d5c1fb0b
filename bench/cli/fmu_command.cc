// `shapebench fmu FILE.yaml --part machine|controller --out NAME.fmu [--fmi-version 2|3]`:
// the scenario's machine or controller as an FMI co-simulation FMU (docs/fmi.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/fmu/fmu_export.h"
#include "common/exit_codes.h"

namespace shapebench::bench::cli {
namespace {

struct FmuArgs {
  std::string file;
  std::string part;
  std::string out;
  int fmi_version = 2;
  std::vector<std::string> sets;
};

int FmuCommand(const FmuArgs& args) {
  Doing("exporting the " + args.part + " of " + args.file + " as an FMU");
  fmu::ExportRequest request;
  request.scenario_path = args.file;
  request.overrides = ParseOverrides(args.sets);
  request.part = args.part == "machine" ? fmu::Part::kMachine : fmu::Part::kController;
  request.fmi_version = args.fmi_version;
  request.out_path = args.out;
  request.library_path = fmu::LibraryBesideExecutable();
  const fmu::ExportResult result = fmu::ExportFmu(request);
  std::cout << "fmu " << Safe(result.model_identifier) << ": FMI " << args.fmi_version << ".0 co-simulation, "
            << args.part << ", " << result.variables << " variables\n";
  PrintWrote(std::cout, {args.out});
  return kExitOk;
}

}  // namespace

Command AddFmuCommand(CLI::App* app) {
  auto args = std::make_shared<FmuArgs>();
  CLI::App* fmu = app->add_subcommand("fmu", "export the machine or the controller as an FMI co-simulation FMU");
  fmu->add_option("file", args->file, "scenario file")->required()->type_name("FILE.yaml");
  fmu->add_option("--part", args->part, "which part: the machine (base accelerations in, deflections out) or the "
                                        "controller (the commanded motion out)")
      ->required()
      ->check(CLI::IsMember({"machine", "controller"}));
  fmu->add_option("--out", args->out, "the FMU to write; NAME is its model identifier")
      ->required()
      ->type_name("NAME.fmu");
  fmu->add_option("--fmi-version", args->fmi_version, "FMI 2.0 (default, binaries/linux64) or 3.0 (binaries/x86_64-linux)")
      ->check(CLI::IsMember({2, 3}))
      ->type_name("2|3");
  AddSetOption(fmu, &args->sets);
  return {fmu, [args] { return FmuCommand(*args); }};
}

}  // namespace shapebench::bench::cli
