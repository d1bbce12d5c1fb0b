// The one loop over a sweep's points that `sweep` (RunSweep), `check` (CheckSweep),
// `compare` (CompareSweeps) and Python's Sweep share: point k of [first, end) computed by
// `run` on `jobs` threads and handed to `consume` in order of k on the calling thread; no
// new point starts once `cancelled` turns true, and the complete results in order are
// still consumed. With a PointCodec an MPI run (distribute.h) computes on every rank,
// the results crossing as the codec's bytes (the same bytes whichever rank computed them);
// without one the points stay on this process's threads. PointHooks add what a sweep
// writing an output directory needs: points already known (a resume's rows ahead) and the
// results that wait behind an earlier point (bench/sweep/rows_ahead.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "bench/sweep/distribute.h"
#include "common/ordered_pool.h"

namespace shapebench::bench {

// A point's result as bytes between MPI ranks (the same binary on every rank).
template <typename Result>
struct PointCodec {
  std::function<std::string(const Result&)> encode;
  std::function<Result(const std::string&)> decode;
};

template <typename Result>
struct PointHooks {
  // Points whose result `run` returns at once (read from disk): an MPI run computes them
  // on rank 0 and never hands them to another rank.
  std::function<bool(std::uint64_t)> known;
  // Results waiting behind an earlier point (common/ordered_pool.h's Spill, point k as
  // ForEachSweepPoint numbers it; under MPI on rank 0's calling thread).
  Spill<Result> spill;
};

// Returns how many points were consumed.
template <typename Result>
std::uint64_t ForEachSweepPoint(std::uint64_t first, std::uint64_t end, int jobs,
                                const std::function<Result(std::uint64_t)>& run,
                                const std::function<void(std::uint64_t, Result&&)>& consume,
                                const std::function<bool()>& cancelled = {},
                                const PointCodec<Result>* codec = nullptr,
                                const PointHooks<Result>* hooks = nullptr) {
  Distributor* distributor = codec != nullptr ? CurrentDistributor() : nullptr;
  if (distributor != nullptr) {
    DistributionHooks encoded;
    if (hooks != nullptr) {
      encoded.known = hooks->known;
      encoded.spill_after = hooks->spill.after;
      if (hooks->spill.take) {
        encoded.spill = [&](std::uint64_t k, const std::string& bytes) { hooks->spill.take(k, codec->decode(bytes)); };
      }
    }
    return distributor->Coordinate(
        first, end, jobs, [&](std::uint64_t k) { return codec->encode(run(k)); },
        [&](std::uint64_t k, std::string&& bytes) { consume(k, codec->decode(bytes)); }, cancelled, encoded);
  }
  Spill<Result> spill;
  if (hooks != nullptr && hooks->spill.take) {
    spill.after = hooks->spill.after;
    spill.take = [&](std::uint64_t k, const Result& result) { hooks->spill.take(first + k, result); };
  }
  return RunOrdered<Result>(
      end - first, jobs, [&](std::uint64_t k) { return run(first + k); },
      [&](std::uint64_t k, Result&& result) { consume(first + k, std::move(result)); }, 0,
      cancelled, spill.take ? &spill : nullptr);
}

}  // namespace shapebench::bench
