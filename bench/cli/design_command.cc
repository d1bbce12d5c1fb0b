// `shapebench design SCENARIO.yaml`: the shortest pattern whose residual vibration stays
// within a tolerance over a band around each participating mode of the scenario's machine
// (controller/pattern_design.h, docs/design.md); the table or JSON, the scenario fragment,
// --out DIR with design.json, design.yaml and design.png.
#include <iostream>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/output/design_report.h"
#include "bench/output/design_request.h"
#include "bench/output/output_path.h"
#include "common/interrupt.h"

namespace shapebench::bench::cli {
namespace {

struct DesignArgs {
  DesignRequest request;
  bool json = false;
  std::string out_dir;
};

int DesignCommand(const DesignArgs& args) {
  const DesignRequest& request = args.request;
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  Doing("designing a pattern for " + request.file);
  Scenario scenario;
  DesignReport report = PrepareDesign(request, &scenario);
  try {
    report.result = controller::DesignPattern(report.spec);
  } catch (const controller::DesignError& error) {
    std::cerr << "error: " << request.file << ": design: " << Safe(error.what()) << "\n";
    return kExitSolverFailed;
  }
  FinishDesign(request, scenario, &report);
  if (request.validate) {
    Doing("running the design across its bands (--validate) for " + request.file, RunMemory(scenario));
    report.validation = ValidateDesign(scenario, report.spec, report.result, report.form == DesignForm::kImpulses);
  }
  std::vector<std::string> written;
  if (!args.out_dir.empty()) {
    const DeferInterrupts defer;
    written = WriteDesignOutputs(args.out_dir, report);
    ThrowIfInterrupted("the output in " + args.out_dir + " is complete");
  }
  if (args.json) {
    std::cout << DesignJson(report).dump(2) << std::endl;
  } else {
    PrintDesignReport(std::cout, report);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

}  // namespace

Command AddDesignCommand(CLI::App* app) {
  auto args = std::make_shared<DesignArgs>();
  CLI::App* design = app->add_subcommand(
      "design", "the shortest pattern whose residual vibration stays within a tolerance over each mode's band");
  design->add_option("file", args->request.file, "scenario file (its machine's participating modes)")
      ->required()
      ->type_name("SCENARIO.yaml");
  AddSetOption(design, &args->request.sets);
  design->add_option("--band", args->request.bands, "the frequency band of mode MODE (0 the lowest), Hz; "
                                            "default every mode +/- 10% (repeatable)")
      ->type_name("MODE=LO:HI");
  design->add_option("--damping", args->request.dampings, "the damping ratio band of mode MODE; default the mode's own")
      ->type_name("MODE=LO:HI");
  design->add_option("--tolerance", args->request.tolerance, "the residual vibration V allowed over every band, in [0, 1) "
                                                     "(default 0.05)")
      ->type_name("V");
  design->add_option("--derivatives", args->request.derivatives,
                     "also zero the first N frequency derivatives of the residual at each band's centre, 0 to 4")
      ->type_name("N");
  design->add_option("--form", args->request.form, "profile_table (one coefficient per controller.period_s; default) or "
                                           "impulses (on --grid-s)")
      ->check(CLI::IsMember({"profile_table", "impulses"}));
  design->add_option("--grid-s", args->request.grid_s, "the impulses form's time grid, s (default 0.0001)")->type_name("S");
  design->add_option("--margin", args->request.margin, "the sampling margin: V between the band's samples stays within "
                                               "the tolerance plus this (default tolerance/5, at least 0.001)")
      ->type_name("M");
  design->add_flag("--registry,!--no-registry", args->request.registry,
                   "compare the registry's shapers and the patent's methods (default on)");
  design->add_flag("--validate", args->request.validate,
                   "run the scenario with the design across each band, one mode at a time, unshaped and shaped, "
                   "and report the worst residual ratio and peak_ratio");
  design->add_flag("--json", args->json, "print the design as one JSON object");
  design->add_option("--out", args->out_dir, "write design.json, design.yaml and design.png into DIR")
      ->type_name("DIR");
  design->footer("docs/design.md");
  return {design, [args] { return DesignCommand(*args); }};
}

}  // namespace shapebench::bench::cli
