// Where a running sweep's rows go (RunSweep, bench/sweep/sweep_runner.h): each row in
// point order to results.csv.partial, and a row that waits behind an earlier point to
// results.csv.ahead too (bench/sweep/rows_ahead.h). No row reaches the disk before the
// manifest that says whose rows they are (`ready`: the manifest and the partial file's
// header, being written meanwhile); until then rows wait in memory. A thread of its own
// flushes both files every kFlushEvery while they hold rows not flushed, so a row reaches
// the disk within about that long of its turn (or of being written ahead), whatever the
// sweep does next: a point that runs for minutes, or hangs, and then a second SIGINT or a
// kill lose no row computed before them. That thread starts with the first row added or
// written ahead kFlushEvery or more after the sweep began: a sweep of a few milliseconds
// never has it (one thread more than the cores cost a 2-job sweep of 1000 points 12% of
// its time), and a sweep that hangs before then has at most kFlushEvery of rows to lose.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <future>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bench/sweep/sweep_files.h"  // ResumedRows
#include "common/atomic_file.h"       // Durability

namespace shapebench::bench {

// Rows reach the files at least this often (a watcher sees the sweep progress), not one
// write a row (a fast sweep's rows cost microseconds each).
inline constexpr std::chrono::milliseconds kFlushEvery{100};

class SweepRows {
 public:
  // `ahead_on_disk`: the points (shard indices) results.csv.ahead already holds.
  SweepRows(const std::filesystem::path& dir, const std::vector<std::string>& columns,
            std::future<ResumedRows>* ready, Durability durability, const std::vector<std::uint64_t>& ahead_on_disk);
  ~SweepRows();
  SweepRows(const SweepRows&) = delete;
  SweepRows& operator=(const SweepRows&) = delete;

  // Opens the partial file now when nothing is being prepared (a resumed directory): a
  // file that cannot be written is said before any point runs.
  void OpenIfReady();
  // Point k's row, the next in point order (the consuming thread).
  void Add(std::uint64_t k, const std::string& row);
  // Point k's row while it waits behind an earlier point (any thread): appended to
  // results.csv.ahead, unless its turn has come. Waits for the manifest if need be.
  void Ahead(std::uint64_t k, const std::string& row);
  // How many rows results.csv.ahead holds whose turn has not come (kept for a resume).
  std::uint64_t WaitingAhead() const;
  // Every row on disk (synced, unless kUnsynced), the files closed; throws what could not
  // be written.
  void Close();
  // After a failure: the rows computed so far kept as far as they can be, nothing thrown.
  // None when the manifest could not be written: no row goes to disk without it.
  void KeepComputed() noexcept;

 private:
  bool Prepared(bool wait);  // under mutex_: the manifest written (waited for when `wait`)
  void OpenPartial();        // under mutex_, prepared
  void OpenAhead();          // under mutex_, prepared
  void ThrowIfFailed() const;
  void StartFlusherIfDue();  // under mutex_
  void FlushLoop();
  void StopFlusher();
  [[noreturn]] static void Fail(const std::filesystem::path& path);

  const std::filesystem::path partial_path_;
  const std::filesystem::path ahead_path_;
  const std::string header_;
  std::future<ResumedRows>* ready_;
  const Durability durability_;
  mutable std::mutex mutex_;
  std::condition_variable stop_flusher_;
  std::FILE* partial_ = nullptr;
  std::FILE* ahead_ = nullptr;
  std::string waiting_;  // rows in order computed before the manifest was written
  std::uint64_t next_ = 0;               // the shard index after the last row added
  std::set<std::uint64_t> ahead_rows_;   // in results.csv.ahead, their turn not come
  bool dirty_ = false;                   // rows written since the last flush
  bool unprepared_ = false;              // the manifest failed: nothing may be written
  std::exception_ptr failure_;           // of the manifest or of a flush
  bool stopping_ = false;
  const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::thread flusher_;
};

}  // namespace shapebench::bench
