#include "bench/sweep/slurm_array.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace shapebench::bench {
namespace {

// The variable's value as a count (at most 9 digits, as --shard takes), or `fallback`
// when unset.
std::uint64_t Number(const std::function<const char*(const char*)>& get, const char* name,
                     std::optional<std::uint64_t> fallback) {
  const char* text = get(name);
  if (text == nullptr) {
    if (fallback) return *fallback;
    throw std::runtime_error(std::string("Slurm job array: ") + name +
                             " is not set; pass --shard I/N explicitly");
  }
  const std::string value(text);
  if (value.size() > 1 && value[0] == '-' && value.find_first_not_of("0123456789", 1) == std::string::npos) {
    throw std::runtime_error(std::string("Slurm job array: ") + name + "='" + value +
                             "' is negative: Slurm's array ids, steps and counts are whole numbers >= 0; "
                             "pass --shard I/N explicitly");
  }
  if (value.empty() || value.size() > 9 || value.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error(std::string("Slurm job array: ") + name + "='" + value +
                             "' is not a whole number; pass --shard I/N explicitly");
  }
  return std::stoull(value);
}

}  // namespace

std::optional<ArrayShard> SlurmArrayShard(const std::function<const char*(const char*)>& get) {
  if (get("SLURM_ARRAY_TASK_ID") == nullptr) return std::nullopt;
  const std::uint64_t id = Number(get, "SLURM_ARRAY_TASK_ID", std::nullopt);
  const std::uint64_t min = Number(get, "SLURM_ARRAY_TASK_MIN", 0);
  const std::uint64_t step = Number(get, "SLURM_ARRAY_TASK_STEP", 1);
  std::optional<std::uint64_t> count_from_max;
  if (get("SLURM_ARRAY_TASK_MAX") != nullptr && step > 0) {
    const std::uint64_t max = Number(get, "SLURM_ARRAY_TASK_MAX", std::nullopt);
    if (max >= min) count_from_max = (max - min) / step + 1;
  }
  const std::uint64_t count = Number(get, "SLURM_ARRAY_TASK_COUNT", count_from_max);
  const std::string ids = "SLURM_ARRAY_TASK_ID=" + std::to_string(id) + " (min " + std::to_string(min) +
                          ", step " + std::to_string(step) + ", count " + std::to_string(count) + ")";
  if (step == 0 || id < min || (id - min) % step != 0 || (id - min) / step >= count) {
    throw std::runtime_error("Slurm job array: " + ids +
                             " is not task I of evenly spaced ids MIN + I * STEP, I < COUNT "
                             "(e.g. --array=0-7); pass --shard I/N explicitly");
  }
  return ArrayShard{(id - min) / step, count};
}

std::string ArrayShardDir(const std::string& out_dir, const ArrayShard& shard) {
  return (std::filesystem::path(out_dir) /
          ("shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count)))
      .string();
}

}  // namespace shapebench::bench
