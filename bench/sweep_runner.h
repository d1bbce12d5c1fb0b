// Running a sweep (SPEC section 2, issue 5): points on worker threads, results.csv
// streamed in point order, shards, resume after a kill, merging shards, and `check` on a
// sweep.
//
// The output directory holds:
//   manifest.json        what the rows belong to: the sweep's hash (base scenario as read,
//                        expanded grid, --set options, kept metrics), the shard, the
//                        columns and what the plots need. Written before any row.
//   results.csv.partial  the rows so far, appended and flushed one by one, in point order;
//   results.csv          the finished file: the partial file renamed when the last row is
//                        written (so a results.csv is always complete);
//   *.png                the plots (not for a shard; `merge` draws them).
// results.csv: `point` (0-based index in the whole grid; the last key varies fastest),
// the swept keys as written in the grid, the kept metrics (%.17g, empty when undefined
// or the point failed), `status` (ok|error) and `error` (the message); RFC 4180 quoting.
// Started again with the same --out, a sweep keeps the partial file's complete rows (a
// torn last row is cut off), runs the points after them and ends with the same bytes as
// an uninterrupted run. A directory holding another sweep (or another shard) is refused.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "bench/checks.h"
#include "bench/override.h"
#include "bench/sweep.h"

namespace shapebench::bench {

struct SweepRunOptions {
  std::string out_dir;
  int jobs = 1;
  // --shard I/N: the points p with p % N == I (I in 0..N-1).
  std::uint64_t shard_index = 0;
  std::uint64_t shard_count = 1;
  bool progress = false;  // a progress bar on stderr (the CLI sets it when stderr is a tty)
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

// The header of results.csv.
std::vector<std::string> ResultColumns(const Sweep& sweep);

// Runs the sweep (this shard of it) into options.out_dir (created), resuming what a
// previous run with the same directory left. Throws std::runtime_error (exit 2) for a
// directory that holds something else or cannot be written; plot failures come after
// results.csv is complete.
SweepRunSummary RunSweep(const Sweep& sweep, const std::vector<Override>& sets,
                         const SweepRunOptions& options);

struct MergeSummary {
  std::uint64_t points = 0;
  std::uint64_t shards = 0;
  std::string results;
  std::vector<std::string> plots;
};

// Joins the finished shards 0..N-1 of one sweep into out_dir: results.csv (byte for byte
// the unsharded run's), manifest.json (the unsharded one's) and the plots. Refuses shards
// of different sweeps, missing, repeated or unfinished shards (std::runtime_error).
MergeSummary MergeShards(const std::string& out_dir, const std::vector<std::string>& shard_dirs);

// `check` on a sweep: runs every point on `jobs` threads and evaluates the sweep's checks
// on it. Prints a FAIL line per failing point-check and one summary line per check to
// `out`, a line per failed point to `err`; `report` receives every point-check (JUnit).
// Returns 0, 1 (a check failed), 2 (a point's bad input) or 3 (a point's solver failure):
// the most severe as `check` ranks them (2, 3, 1, 0).
int CheckSweep(const Sweep& sweep, const std::vector<Override>& sets, int jobs,
               std::ostream& out, std::ostream& err, ScenarioCheckReport* report);

// Runs work(k) for k = 0..count-1 on `jobs` threads and hands each result to consume(k,
// result) on the calling thread, in order of k. Workers stay at most `window` items
// ahead of the consumer, so memory does not grow with `count`. An exception from work or
// consume stops the workers and is rethrown here. When `cancelled` (polled) turns true,
// workers take no new items, the ones in progress finish, and the consumer takes every
// result that is complete and in order, then returns. Returns how many were consumed.
template <typename Result>
std::uint64_t RunOrdered(std::uint64_t count, int jobs,
                         const std::function<Result(std::uint64_t)>& work,
                         const std::function<void(std::uint64_t, Result&&)>& consume,
                         std::uint64_t window = 0,
                         const std::function<bool()>& cancelled = {}) {
  if (count == 0) return 0;
  if (jobs < 1) jobs = 1;
  if (static_cast<std::uint64_t>(jobs) > count) jobs = static_cast<int>(count);
  if (window == 0) window = 64 * static_cast<std::uint64_t>(jobs);
  constexpr auto kPoll = std::chrono::milliseconds(20);
  auto is_cancelled = [&] { return cancelled && cancelled(); };
  std::mutex mutex;
  std::condition_variable ready_changed;
  std::condition_variable consumed_changed;
  std::map<std::uint64_t, Result> ready;
  std::uint64_t next = 0;
  std::uint64_t consumed = 0;
  int running = jobs;  // worker threads not yet returned
  bool stop = false;
  std::exception_ptr failure;

  auto work_loop = [&] {
    while (true) {
      std::uint64_t k = 0;
      {
        std::unique_lock<std::mutex> lock(mutex);
        if (stop || next >= count || is_cancelled()) return;
        k = next++;
        while (!consumed_changed.wait_for(lock, kPoll, [&] { return stop || k < consumed + window; })) {
          if (is_cancelled()) return;
        }
        if (stop) return;
      }
      try {
        Result result = work(k);
        std::lock_guard<std::mutex> lock(mutex);
        ready.emplace(k, std::move(result));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        consumed_changed.notify_all();
      }
      ready_changed.notify_one();
    }
  };
  auto worker = [&] {
    work_loop();
    {
      std::lock_guard<std::mutex> lock(mutex);
      --running;
    }
    ready_changed.notify_all();
  };
  std::vector<std::thread> threads;
  for (int i = 0; i < jobs; ++i) threads.emplace_back(worker);
  auto finish = [&] {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    consumed_changed.notify_all();
    for (auto& thread : threads) thread.join();
  };
  std::uint64_t done = 0;
  try {
    for (std::uint64_t k = 0; k < count; ++k) {
      Result result;
      {
        std::unique_lock<std::mutex> lock(mutex);
        // Cancelled: what is ready in order is still taken; a gap no worker will fill ends it.
        auto settled = [&] { return failure || ready.count(k) > 0 || running == 0; };
        while (!ready_changed.wait_for(lock, kPoll, settled)) {
        }
        if (failure) break;
        auto it = ready.find(k);
        if (it == ready.end()) break;  // cancelled: nobody computes k
        result = std::move(it->second);
        ready.erase(it);
      }
      consume(k, std::move(result));
      done = k + 1;
      {
        std::lock_guard<std::mutex> lock(mutex);
        consumed = k + 1;
      }
      consumed_changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (failure) std::rethrow_exception(failure);
  return done;
}

}  // namespace shapebench::bench
