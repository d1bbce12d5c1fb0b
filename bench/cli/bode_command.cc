// `shapebench bode FILE.yaml [--axis A] [--out DIR] [--json] [--report FILE.html]`: the
// machine model's frequency response per axis and the pattern's V(f, zeta) and phase on one
// frequency axis; for a measured machine the measured FRF under the identified model.
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/config/override.h"
#include "bench/output/bode.h"
#include "bench/output/output_path.h"
#include "bench/scenario/frf_machine_reader.h"
#include "bench/scenario/scenario_loader.h"
#include "common/atomic_file.h"
#include "common/interrupt.h"

namespace shapebench::bench::cli {
namespace {

struct BodeArgs {
  std::string file;
  std::vector<std::string> sets;
  std::string axis;  // "" every modelled axis
  std::string out_dir;
  std::string report;
  bool json = false;
};

// --axis x|y|z, which the machine must model; -1 without --axis.
int ChosenAxis(const BodeArgs& args, const Scenario& scenario) {
  if (args.axis.empty()) return -1;
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    if (args.axis != model::AxisName(axis)) continue;
    if (!scenario.machine.Models(axis)) {
      throw ConfigError(args.file, 0, 0, "--axis",
                        "the machine has no model along " + args.axis + " (a rigid axis has no frequency response)");
    }
    return axis;
  }
  throw ConfigError("--axis", 0, 0, "--axis", "expected one of x|y|z, got '" + args.axis + "'");
}

std::vector<std::string> WriteBodeOutputs(const std::string& out_dir, const BodeData& data,
                                          const Scenario& scenario) {
  const DeferInterrupts defer;
  StagedDirectory staged(out_dir);
  std::vector<std::string> written;
  try {
    WriteFileAtomically((std::filesystem::path(staged.path()) / "bode.json").string(), [&](std::ostream& out) {
      out << BodeJson(data, scenario.name).dump(2) << "\n";
    });
    written = {"bode.json"};
    for (const std::string& name : WriteBodePlots(staged.path(), data, scenario.name)) written.push_back(name);
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));
  }
  staged.Commit();
  ThrowIfInterrupted("the output in " + out_dir + " is complete");
  return written;
}

HtmlReport BodeHtmlReport(const BodeData& data, const Scenario& scenario) {
  HtmlReport report;
  report.title = "shapebench bode: " + scenario.name;
  report.subtitle = scenario.source_file;
  std::ostringstream table;
  PrintBodeTable(table, data, scenario);
  for (const auto& [name, svg] : BodePlotsSvg(data, scenario.name)) {
    HtmlSection section;
    section.heading = name == "bode.svg" ? "Frequency response and pattern" : "Measured FRF and identified model";
    section.svg = svg;
    report.sections.push_back(section);
  }
  report.sections.front().preformatted = table.str();
  return report;
}

int BodeCommand(const BodeArgs& args) {
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);
  if (!args.report.empty()) RequireWritableOutputFile("--report", args.report);
  Doing("loading " + args.file);
  LoadOptions options;
  options.plan_move = false;  // the response is shown whatever the move
  MeasuredFrfCapture measured;  // the FRFs a measured machine is identified from, as it loads
  const Scenario scenario = LoadScenario(args.file, ParseOverrides(args.sets), options);
  const int axis = ChosenAxis(args, scenario);
  Doing("computing the frequency response of " + args.file);
  const BodeData data = ComputeBode(scenario, measured.axes(), axis);
  std::vector<std::string> written;
  if (!args.out_dir.empty()) written = WriteBodeOutputs(args.out_dir, data, scenario);
  if (!args.report.empty()) WriteReport(args.report, [&] { return BodeHtmlReport(data, scenario); });
  if (args.json) {
    std::cout << BodeJson(data, scenario.name).dump(2) << std::endl;
  } else {
    PrintBodeTable(std::cout, data, scenario);
    std::cout.flush();
  }
  PrintWrote(args.json ? std::cerr : std::cout, args.out_dir, written);
  return kExitOk;
}

}  // namespace

Command AddBodeCommand(CLI::App* app) {
  auto args = std::make_shared<BodeArgs>();
  CLI::App* bode = app->add_subcommand(
      "bode", "the machine's frequency response per axis and the pattern's V(f) and phase on one frequency axis");
  bode->add_option("file", args->file, "scenario file")->required()->type_name("FILE.yaml");
  AddSetOption(bode, &args->sets);
  bode->add_option("--axis", args->axis, "one axis only (default: every modelled axis)")->type_name("x|y|z");
  bode->add_option("--out", args->out_dir, "write bode.json, bode.png (and frf.png for a measured machine) into DIR")
      ->type_name("DIR");
  bode->add_flag("--json", args->json, "print the curves as one JSON object");
  bode->add_option("--report", args->report, "write a self-contained HTML page of the plots to FILE")
      ->type_name("FILE.html");
  return {bode, [args] { return BodeCommand(*args); }};
}

}  // namespace shapebench::bench::cli
