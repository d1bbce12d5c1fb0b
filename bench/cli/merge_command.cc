// `shapebench merge OUT_DIR SHARD_DIR...`: the shards of a sweep joined into the
// unsharded results.csv (bench/sweep/sweep_runner.h).
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/cli/cli_support.h"
#include "bench/cli/commands.h"
#include "bench/sweep/sweep_files.h"
#include "bench/sweep/sweep_runner.h"
#include "common/interrupt.h"

namespace shapebench::bench::cli {
namespace {

struct MergeArgs {
  std::vector<std::string> dirs;
  std::string out_dir;
};

int MergeCommand(const MergeArgs& args) {
  std::vector<std::string> shards = args.dirs;
  std::string out_dir = args.out_dir;
  if (out_dir.empty()) {
    if (shards.size() < 2) {
      throw std::runtime_error("merge: expected OUT_DIR SHARD_DIR... (or --out OUT_DIR SHARD_DIR...)");
    }
    out_dir = shards.front();
    shards.erase(shards.begin());
  }
  const DeferInterrupts defer;
  Doing("merging shards into " + out_dir);
  const MergeSummary summary = MergeShards(out_dir, shards);
  ThrowIfInterrupted("the merged output in " + out_dir + " is complete");
  std::cout << "merged " << summary.shards << " shards: " << summary.points << " points -> "
            << summary.results << "\n";
  PrintWrote(std::cout, {(std::filesystem::path(summary.results).parent_path() / kSweepManifestFile).string(),
                        summary.results});
  PrintWrote(std::cout, summary.plots);
  return kExitOk;
}

}  // namespace

Command AddMergeCommand(CLI::App* app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* merge = app->add_subcommand("merge", "join the shards of a sweep into one results.csv");
  merge->add_option("dirs", args->dirs, "OUT_DIR then the shards' --out directories")->required()->type_name("DIR");
  merge->add_option("--out", args->out_dir, "output directory (then every DIR is a shard)")->type_name("OUT_DIR");
  return {merge, [args] { return MergeCommand(*args); }};
}

}  // namespace shapebench::bench::cli
