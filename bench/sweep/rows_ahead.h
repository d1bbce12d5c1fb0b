// results.csv.ahead (docs/sweeps.md#the-output-directory-and-resume): the rows of points
// that finished while an earlier point still ran. results.csv(.partial) is written in
// point order, so such a row waits in memory for the earlier one; once it has waited
// kAheadAfter it is also appended here (RunSweep; flushed with the partial file), so that
// a sweep stopped before the earlier point ends (a second SIGINT, a kill, a point that
// hangs) does not run it again. The file is results.csv's header, then rows as results.csv
// holds them, in the order they were written (any point order). A sweep started again
// keeps the rows after the partial file's complete ones, each checked as those are (its
// point one of the shard's, its key values the grid's, status ok or error; a torn or
// foreign row ends the file), writes each into the partial file when its turn comes
// instead of running its point, and removes the file when results.csv is complete.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bench/sweep/sweep_files.h"  // ShardPoints, GridTexts
#include "common/atomic_file.h"       // Durability

namespace shapebench::bench {

// How long a row waits behind an earlier point before it is written ahead: a fast
// sweep's rows wait microseconds and are never written twice.
inline constexpr std::chrono::milliseconds kAheadAfter{100};
// At most this many rows ahead are read back (a sweep's window of points in flight is a
// few thousand; more is no file a sweep wrote, and is run again).
inline constexpr std::uint64_t kMaxRowsAhead = 1u << 20;

struct AheadRow {
  std::string text;  // the row as results.csv holds it, '\n' included
  bool ok = false;   // status ok
};

class RowsAhead {
 public:
  // The rows of dir's results.csv.ahead for the shard's points k >= first (k counts the
  // shard's points, as results.csv's rows do), the file left holding just those (written
  // again, atomically, when it held others, a torn or foreign tail or a wrong header;
  // removed when none is left). None when there is no file. Throws std::runtime_error
  // naming the file when it is no regular file or cannot be read or written.
  static RowsAhead Resume(const std::string& dir, const std::vector<std::string>& columns, const ShardPoints& shard,
                          const GridTexts& grid, std::uint64_t first, Durability durability);

  // Point k's row, nullptr when it is not ahead. Safe on any thread (read only).
  const AheadRow* Find(std::uint64_t k) const;
  std::uint64_t size() const { return rows_.size(); }
  std::vector<std::uint64_t> Points() const;

 private:
  std::map<std::uint64_t, AheadRow> rows_;
};

}  // namespace shapebench::bench
