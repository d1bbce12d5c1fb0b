// `shapebench sweep SWEEP.yaml`: a grid of scenarios into an output directory
// (bench/sweep/sweep.h, bench/sweep/sweep_runner.h): results.csv, plots, --report.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/output/output_path.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/robust_band.h"
#include "bench/sweep/slurm_array.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_files.h"
#include "bench/sweep/sweep_html.h"
#include "bench/sweep/sweep_runner.h"

namespace shapebench::bench::cli {
namespace {

struct SweepArgs {
  std::string file;
  std::vector<std::string> sets;
  int jobs = 0;
  std::string out_dir;
  std::string shard;
  std::string report;  // --report FILE.html
  bool force = false;
  bool no_sync = false;
};

// --shard I/N: I in 0..N-1 (the points p with p % N == I).
void ParseShard(const std::string& text, SweepRunOptions* options) {
  const std::size_t slash = text.find('/');
  const auto digits = [](const std::string& part) {
    return !part.empty() && part.size() <= 9 && part.find_first_not_of("0123456789") == std::string::npos;
  };
  const std::string index = slash == std::string::npos ? "" : text.substr(0, slash);
  const std::string count = slash == std::string::npos ? "" : text.substr(slash + 1);
  if (!digits(index) || !digits(count) || std::stoul(count) < 1 || std::stoul(index) >= std::stoul(count)) {
    throw std::runtime_error("--shard: expected I/N with N >= 1 and I in 0..N-1 (e.g. 0/4), got '" + text + "'");
  }
  options->shard_index = std::stoul(index);
  options->shard_count = std::stoul(count);
}

void PrintSweepSummary(const Sweep& sweep, const SweepRunOptions& options, const SweepRunSummary& summary) {
  std::cout << "sweep " << Safe(sweep.name) << ": " << summary.points << " points";
  if (options.shard_count > 1) {
    std::cout << " (shard " << options.shard_index << "/" << options.shard_count << " of " << sweep.points << ")";
  }
  std::cout << ", " << summary.ok << " ok, " << summary.errors << " error";
  if (summary.resumed > 0) std::cout << " (" << summary.resumed << " done before)";
  std::cout << " -> " << summary.results << "\n";
  PrintWrote(std::cout, {(std::filesystem::path(summary.results).parent_path() / kSweepManifestFile).string(),
                        summary.results});
  PrintWrote(std::cout, summary.plots);
  // The robust bands, when this run drew them (an unsharded, complete sweep: bands.csv).
  const bool bands = std::any_of(summary.plots.begin(), summary.plots.end(), [](const std::string& path) {
    return std::filesystem::path(path).filename() == "bands.csv";
  });
  if (bands) {
    for (const std::string& line : BandsSummary(SweepBands(SweepLayout::Of(sweep), summary.results))) {
      std::cout << Safe(line) << "\n";
    }
  }
  std::cout.flush();
}

int SweepCommand(const SweepArgs& args) {
  if (!args.report.empty()) RequireWritableOutputFile("--report", args.report);  // before anything runs
  if (!args.out_dir.empty()) RequireWritableOutputDir("--out", args.out_dir);  // before the points
  const std::vector<Override> overrides = ParseOverrides(args.sets);
  SweepRunOptions options;
  if (!args.shard.empty()) ParseShard(args.shard, &options);
  // In a Slurm job array without --shard: this task's shard, in DIR/shard-I-of-N.
  const std::optional<ArrayShard> array = args.shard.empty() ? SlurmArrayShard() : std::nullopt;
  if (array) {
    options.shard_index = array->index;
    options.shard_count = array->count;
  }
  SweepLoadOptions load;
  load.force = args.force;
  Doing("loading " + args.file);
  const Sweep sweep = LoadSweep(args.file, overrides, load);
  if (!sweep.note.empty() && !IsDistributedWorker()) std::cerr << sweep.note << "\n";
  options.out_dir = args.out_dir.empty() ? (std::filesystem::path("sweep_out") / sweep.name).string() : args.out_dir;
  if (array) options.out_dir = ArrayShardDir(options.out_dir, *array);
  options.jobs = JobsOrDefault(args.jobs);
  if (args.no_sync) options.durability = Durability::kUnsynced;
  AgreeAcrossRanks([&] {  // every MPI rank runs this sweep, or none runs (exit 2)
    RunIdentity identity;
    identity.Add("command", "sweep");
    identity.Add("sweep file", sweep.file);
    identity.Add("--set options", SetsText(overrides));
    identity.Add("sweep hash", SweepHash(sweep, overrides));
    identity.Add("shard", std::to_string(options.shard_index) + "/" + std::to_string(options.shard_count));
    return identity;
  });
  if (IsDistributedWorker()) {  // an MPI rank other than 0 (bench/sweep/sweep_mpi.h)
    ServeSweep(sweep, overrides, options);
    return kExitOk;
  }
  options.progress = isatty(STDERR_FILENO) != 0;
  Doing("running sweep '" + sweep.name + "' (" + sweep.file + ") into " + options.out_dir,
        SweepMemory(options.jobs) + "; the complete rows are kept, the same command resumes");
  const SweepRunSummary summary = RunSweep(sweep, overrides, options);
  PrintSweepSummary(sweep, options, summary);
  if (!args.report.empty()) {
    WriteReport(args.report, [&] { return SweepHtmlReport(ReadSweepHtmlData(sweep, overrides, summary.results)); });
  }
  return kExitOk;
}

}  // namespace

Command AddSweepCommand(CLI::App* app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sweep = app->add_subcommand("sweep", "run a grid of scenarios: results.csv and plots");
  sweep->add_option("sweep", args->file, "sweep file (base:, grid:, ...)")->required()->type_name("SWEEP.yaml");
  AddSetOption(sweep, &args->sets);
  sweep->add_option("--jobs", args->jobs, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096))
      ->type_name("N");
  sweep->add_option("--out", args->out_dir, "output directory (default: sweep_out/NAME); run again to resume")
      ->type_name("DIR");
  sweep->add_option("--shard", args->shard, "run the points p with p % N == I only (I in 0..N-1); join with merge")
      ->type_name("I/N");
  sweep->add_option("--report", args->report, kReportHelp)->type_name("FILE.html");
  sweep->add_flag("--force", args->force, kForceHelp);
  sweep->add_flag("--no-sync", args->no_sync,
                  "do not sync manifest.json and results.csv to the disk (scratch output: a "
                  "crash of the machine may lose them; a killed sweep still resumes)");
  return {sweep, [args] { return SweepCommand(*args); }, /*on_every_rank=*/true};
}

}  // namespace shapebench::bench::cli
