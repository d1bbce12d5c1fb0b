// `shapebench sensitivity FILE.yaml`: residual vibration of shapers against plant
// frequency / design frequency (bench/sensitivity/sensitivity.h); a table, --out DIR with
// sensitivity.csv and sensitivity.png.
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/output/output_path.h"
#include "bench/sensitivity/sensitivity.h"
#include "common/interrupt.h"

namespace shapebench::bench::cli {
namespace {

struct SensitivityArgs {
  std::string file;
  std::vector<std::string> sets;
  std::string out_dir;
};

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
      throw std::runtime_error("cannot create " + args.out_dir + ": " + (ec ? ec.message() : "not a directory"));
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

}  // namespace

Command AddSensitivityCommand(CLI::App* app) {
  auto args = std::make_shared<SensitivityArgs>();
  CLI::App* sensitivity = app->add_subcommand(
      "sensitivity", "residual vibration of shapers vs plant frequency / design frequency");
  sensitivity->add_option("file", args->file, "sensitivity file (shapers:, ratio:, ...)")
      ->required()
      ->type_name("FILE.yaml");
  AddSetOption(sensitivity, &args->sets);
  sensitivity->add_option("--out", args->out_dir, "write sensitivity.csv and sensitivity.png into DIR (created)")
      ->type_name("DIR");
  return {sensitivity, [args] { return SensitivityCommand(*args); }};
}

}  // namespace shapebench::bench::cli
