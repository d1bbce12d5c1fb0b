// `sweep` in a Slurm job array (docs/scaling.md): without --shard, each array task runs
// its own shard of the grid, and --out DIR means DIR/shard-I-of-N so that the tasks of one
// array never share a directory; `merge` then joins DIR/shard-*-of-N. An explicit --shard
// wins (and --out is then used as given).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace shapebench::bench {

struct ArrayShard {
  std::uint64_t index = 0;
  std::uint64_t count = 1;
};

// This task's shard: index (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) /
// SLURM_ARRAY_TASK_STEP of SLURM_ARRAY_TASK_COUNT (or (MAX - MIN) / STEP + 1 when COUNT is
// unset; MIN 0 and STEP 1 when unset), as `get` (getenv; nullptr: unset) reads them.
// nullopt outside a job array (no SLURM_ARRAY_TASK_ID). Throws std::runtime_error for ids
// that are no shard (not a number, not evenly spaced from MIN, index >= count): such an
// array (e.g. --array=1,4,9) needs an explicit --shard.
std::optional<ArrayShard> SlurmArrayShard(
    const std::function<const char*(const char*)>& get = [](const char* name) { return std::getenv(name); });

// "DIR/shard-I-of-N".
std::string ArrayShardDir(const std::string& out_dir, const ArrayShard& shard);

}  // namespace shapebench::bench
