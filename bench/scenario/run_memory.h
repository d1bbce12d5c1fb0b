// The memory a run needs, estimated before anything is allocated, for limits.max_memory_mb
// (docs/reliability.md, guard rails). Per interpolation period a run holds the command
// (the interpolated pulses, their filtered copy, the per-axis velocities, path position
// and block: controller/controller.cc GenerateProgramCommand), the per-tick samples
// (bench/run/command_samples.h: velocity, acceleration, position, and the positions'
// temporary) and, when recorded, a trace row per output sample (bench/run/run_scenario.h Trace).
// The trace is counted at one sample a period (its lower bound) and always: a run's
// budget is the same whether or not it writes trace.csv.
#pragma once

#include <cstddef>

#include "bench/scenario/scenario.h"

namespace shapebench::bench {

constexpr double kCommandBytesPerTick = 128.0;
constexpr double kSampleBytesPerTick = 104.0;
constexpr double kTraceBytesPerSample = 128.0;
constexpr double kRunBytesPerTick = kCommandBytesPerTick + kSampleBytesPerTick + kTraceBytesPerSample;
// A parsed block (controller/program.h ProgramBlock) with its path element and the speed
// plan's per-block state, rounded up.
constexpr double kBytesPerBlock = 1024.0;

inline double MegabytesToBytes(double megabytes) { return megabytes * 1024.0 * 1024.0; }

// The bytes a run of `ticks` interpolation periods needs at least.
inline double RunBytes(double ticks) { return ticks * kRunBytesPerTick; }

// The most ticks limits.max_memory_mb allows.
inline double MemoryTickLimit(const RunLimits& limits) {
  return MegabytesToBytes(static_cast<double>(limits.max_memory_mb)) / kRunBytesPerTick;
}

}  // namespace shapebench::bench
