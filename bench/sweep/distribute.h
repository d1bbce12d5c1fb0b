// Where a sweep's points are computed: on this process's threads (common/ordered_pool.h),
// or, when the process is one rank of an MPI run (bench/sweep/sweep_mpi.h installs a
// Distributor), on every rank's threads with rank 0 consuming the results in order
// (docs/scaling.md). RunSweep and CheckSweep go through it (ForEachSweepPoint with a codec,
// point_loop.h); the other ranks call Serve with the same work, so a result is the same
// bytes whichever rank computed it.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "common/ordered_pool.h"

namespace shapebench::bench {

using EncodedWork = std::function<std::string(std::uint64_t)>;
using EncodedConsume = std::function<void(std::uint64_t, std::string&&)>;

// What a distribution is told besides its work (point_loop.h's PointHooks, encoded).
struct DistributionHooks {
  // Points work(k) returns at once (a resumed sweep's rows ahead): never handed to
  // another rank.
  std::function<bool(std::uint64_t)> known;
  // Results that waited spill_after behind an earlier point, and those left when a
  // cancelled distribution ends: each handed once to `spill` on rank 0's calling thread.
  std::chrono::milliseconds spill_after{100};
  std::function<void(std::uint64_t, const std::string&)> spill;
};

class Distributor {
 public:
  virtual ~Distributor() = default;
  // Rank 0: work(k) for k in [first, end), `jobs` threads here and the other ranks' Serve,
  // handed to consume(k, bytes) in order of k on the calling thread. When `cancelled`
  // turns true no new points start and the complete results in order are consumed; the
  // run then ends abnormally (the other ranks are stopped when the process ends).
  // Returns how many were consumed.
  virtual std::uint64_t Coordinate(std::uint64_t first, std::uint64_t end, int jobs,
                                   const EncodedWork& work, const EncodedConsume& consume,
                                   const std::function<bool()>& cancelled,
                                   const DistributionHooks& hooks) = 0;
  // Every rank, once, before its first distribution and before the command writes
  // anything: `identity` (RunIdentity's bytes, bench/sweep/run_identity.h) is compared
  // with rank 0's. Rank 0 throws std::runtime_error naming the first rank whose identity
  // differs (and what differs) or that failed before; the other ranks then serve nothing.
  virtual void Agree(const std::string& identity) = 0;
  // The other ranks: work(k) on `jobs` threads for the points rank 0's next Coordinate
  // hands out, until it has all of them (or the run has no more Coordinate).
  virtual void Serve(int jobs, const EncodedWork& work) = 0;
  // Processes of this run on this host (ranks sharing its cores).
  virtual int ProcessesOnHost() const = 0;
  virtual bool coordinator() const = 0;
};

// The process-wide Distributor (MPI is initialised once per process); nullptr: none.
Distributor* CurrentDistributor();
void SetDistributor(Distributor* distributor);

// Whether this process is an MPI rank other than 0: it serves points instead of writing.
inline bool IsDistributedWorker() {
  return CurrentDistributor() != nullptr && !CurrentDistributor()->coordinator();
}

// The default of --jobs: this host's hardware threads shared by its ranks (at least 1).
int DefaultJobs();

}  // namespace shapebench::bench
