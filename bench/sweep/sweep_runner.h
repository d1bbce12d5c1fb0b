// Running a sweep (docs/sweeps.md): points on worker threads, results.csv
// streamed in point order, shards, resume after a kill, merging shards, and `check` on a
// sweep.
//
// The output directory holds:
//   manifest.json        what the rows belong to: the sweep's hash (base scenario as read,
//                        expanded grid, --set options, kept metrics), the shard, the
//                        columns and what the plots need. Written before any row.
//   results.csv.partial  the rows so far, appended in point order, flushed every 0.1 s;
//   results.csv.ahead    rows that finished while an earlier point still ran, written once
//                        they have waited 0.1 s (bench/sweep/rows_ahead.h): a resume does
//                        not run them again;
//   results.csv          the finished file: the partial file renamed when the last row is
//                        written (so a results.csv is always complete);
//   *.png                the plots (not for a shard; `merge` draws them);
//   results.mat          results.csv as a MAT file (bench/output/mat_file.h; not for a
//                        shard, `merge` writes it), listed in the summaries' `plots`.
// results.csv: `point` (0-based index in the whole grid; the last key varies fastest),
// the swept keys as written in the grid, the kept metrics (ExactDouble, common/csv.h: the
// shortest text that reads back exactly; empty when undefined or the point failed),
// `status` (ok|error) and `error` (the message); RFC 4180 quoting.
// Started again with the same --out, a sweep keeps the partial file's complete rows (a
// torn last row is cut off) and the rows ahead, runs the other points and ends with the
// same bytes as an uninterrupted run. A directory holding another sweep (or another shard) is refused.
// A sweep or merge holds an exclusive lock on the directory (.shapebench.lock, with its
// PID; bench/sweep/output_dir.h) while it writes there: a second one is refused (exit 2).
// manifest.json also keeps the grid's values, so that a merge checks each row's keys.
// Only regular files are read (a FIFO or a device is refused), the manifest up to 64 MiB.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "bench/config/override.h"
#include "bench/scenario/checks.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_files.h"  // ResultColumns, the readers of resume and merge
#include "common/atomic_file.h"       // Durability

namespace shapebench::bench {

struct SweepRunOptions {
  std::string out_dir;
  int jobs = 1;
  // --shard I/N: the points p with p % N == I (I in 0..N-1).
  std::uint64_t shard_index = 0;
  std::uint64_t shard_count = 1;
  bool progress = false;  // a progress bar on stderr (the CLI sets it when stderr is a tty)
  // manifest.json and results.csv synced to the disk (kSynced) or not (--no-sync:
  // common/atomic_file.h's Durability; the plots are synced either way).
  Durability durability = Durability::kSynced;
  // results.mat beside a complete results.csv (the CLI always). make bench's sweep cases
  // leave it out to time what every earlier version wrote (bench-compare's like for like)
  // and time it in a row of its own (BM_Case3_ExactWithMat).
  bool write_mat = true;
};

struct SweepRunSummary {
  std::uint64_t points = 0;   // this shard's points
  std::uint64_t resumed = 0;  // found done in the output directory
  std::uint64_t ok = 0;
  std::uint64_t errors = 0;
  std::string results;  // results.csv
  std::vector<std::string> plots;
  double seconds = 0.0;
};

// Runs the sweep (this shard of it) into options.out_dir (created), resuming what a
// previous run with the same directory left. Throws std::runtime_error (exit 2) for a
// directory that holds something else or cannot be written; plot failures come after
// results.csv is complete.
SweepRunSummary RunSweep(const Sweep& sweep, const std::vector<Override>& sets,
                         const SweepRunOptions& options);

// An MPI rank other than 0 (bench/sweep/distribute.h): computes the rows of the points
// rank 0's RunSweep hands out, the same bytes as RunSweep's own; writes nothing.
void ServeSweep(const Sweep& sweep, const std::vector<Override>& sets, const SweepRunOptions& options);

struct MergeSummary {
  std::uint64_t points = 0;
  std::uint64_t shards = 0;
  std::string results;
  std::vector<std::string> plots;
};

// Joins the finished shards 0..N-1 of one sweep into out_dir: results.csv (byte for byte
// the unsharded run's), manifest.json (the unsharded one's) and the plots. Refuses shards
// of different sweeps, missing, repeated or unfinished shards, rows a resumed sweep would
// not keep (status, point index or key values), and an out_dir that is neither empty nor
// this sweep's merged result (std::runtime_error).
MergeSummary MergeShards(const std::string& out_dir, const std::vector<std::string>& shard_dirs);

// `check` on a sweep: runs every point on `jobs` threads and evaluates the sweep's checks
// on it. Prints a FAIL line per failing point-check and one summary line per check to
// `out`, a line per failed point to `err`; `report` receives every point-check (JUnit).
// A sampled sweep's quantile and yield gates (SampleGate) follow: one line and result per
// gate and combination of the other keys' values, with the 95% interval.
// Returns 0, 1 (a check failed), 2 (a point's bad input) or 3 (a point's solver failure):
// the most severe as `check` ranks them (2, 3, 1, 0).
int CheckSweep(const Sweep& sweep, const std::vector<Override>& sets, int jobs,
               std::ostream& out, std::ostream& err, ScenarioCheckReport* report);
// An MPI rank other than 0: runs the points rank 0's CheckSweep of the same sweep hands out.
void ServeCheckSweep(const Sweep& sweep, const std::vector<Override>& sets, int jobs);

}  // namespace shapebench::bench
