// The files of a sweep's output directory (bench/sweep/sweep_runner.h has the layout):
// manifest.json written and read back, and the rows of results.csv(.partial) checked
// against the grid. `sweep` into an interrupted --out (resume) and `merge` read them with
// these functions, and so do the fuzz targets fuzz_manifest and fuzz_rows
// (fuzz/fuzz_targets.h). Whatever the files hold, the readers accept them or throw
// std::runtime_error naming the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/config/override.h"
#include "bench/sweep/sweep.h"

namespace shapebench::bench {

inline constexpr const char* kSweepManifestFile = "manifest.json";
inline constexpr const char* kSweepResultsFile = "results.csv";
inline constexpr const char* kSweepPartialFile = "results.csv.partial";
// Rows that finished ahead of their turn (bench/sweep/rows_ahead.h).
inline constexpr const char* kSweepAheadFile = "results.csv.ahead";

// The k-th point of a shard (--shard index/count: the points p with p % count == index),
// and how many points it has.
struct ShardPoints {
  std::uint64_t total = 0;
  std::uint64_t index = 0;
  std::uint64_t count = 1;
  std::uint64_t Point(std::uint64_t k) const { return index + k * count; }
  std::uint64_t Size() const { return total > index ? (total - index - 1) / count + 1 : 0; }
};

// The key values of every point of a grid: results.csv's key columns of point p.
class GridTexts {
 public:
  static GridTexts Of(const Sweep& sweep);
  // From a manifest's "grid" (*present false, no keys, when absent: manifests written
  // before it was kept); throws std::runtime_error when it does not fit the manifest's
  // columns and point count.
  static GridTexts FromManifest(const nlohmann::json& manifest, bool* present);

  // Point p's values: the mixed-radix digits of p, the last axis varying fastest.
  std::vector<std::string> Texts(std::uint64_t point) const;
  // Each axis' keys' values (a zip group's keys share an axis).
  const std::vector<std::vector<SweepValues>>& axes() const { return axes_; }

 private:
  std::vector<std::vector<SweepValues>> axes_;
};

// The header of results.csv.
std::vector<std::string> ResultColumns(const Sweep& sweep);

// manifest.json of this shard of the sweep: what the rows belong to (format, hash, files,
// --set options, points, shard, columns, plot layout, grid).
nlohmann::ordered_json ManifestJson(const Sweep& sweep, const std::vector<Override>& sets,
                                    std::uint64_t shard_index, std::uint64_t shard_count);

// Reads and checks a manifest.json (a regular file of at most 64 MiB) for everything
// resume and merge take from it: format, hash, points, shard, columns, and when present
// the grid (GridTexts::FromManifest) and the plot layout (one the plotter can draw from
// the columns and points). `text`, when given, receives its bytes. Throws
// std::runtime_error "PATH: why" for anything else.
nlohmann::json ReadManifest(const std::string& path, std::string* text = nullptr);

// The merged output's manifest.json: a shard's manifest (the text ReadManifest accepted)
// as shard 0/1, its key order kept (the unsharded run's bytes).
std::string MergedManifestText(const std::string& shard_manifest_text);

// "sweep FILE (hash H, shard I/N)" of a manifest ReadManifest accepted.
std::string DescribeManifest(const nlohmann::json& manifest);

// Before a sweep writes into `dir`: refuses (std::runtime_error) a directory holding
// another sweep's or another shard's results, or rows without a manifest.
void CheckResumeDirectory(const std::string& dir, const nlohmann::ordered_json& manifest);

// Before a merge writes into `dir`: refuses (std::runtime_error) a directory that is not
// empty and not this sweep's merged result, or holds an unfinished run of it.
void CheckMergeOutput(const std::string& dir, const nlohmann::json& shard_manifest);

// Why `fields` is not point `point`'s row of results.csv ("" when it is): the field
// count, the point index, the key values (`keys`; none to skip them) and the status.
std::string RowProblem(const std::vector<std::string>& fields, std::size_t columns,
                       std::uint64_t point, const std::vector<std::string>& keys);

// What a results file of a shard holds: the header, then rows for points Point(0),
// Point(1), ... each without a RowProblem.
struct RowScan {
  std::uint64_t rows = 0;        // how many rows hold
  std::uint64_t good_bytes = 0;  // where the last of them ends
  std::uint64_t errors = 0;      // how many of them have status error
  bool header_ok = false;        // whether the header is `columns`
};
RowScan ScanRows(const std::string& path, const std::vector<std::string>& columns,
                 const ShardPoints& shard, const GridTexts& grid);

// The rows a sweep started again in `dir` keeps. A results.csv must hold all the shard's
// rows (then `finished`); otherwise results.csv.partial keeps its good rows (a torn or
// foreign tail cut off; just the header when it has no good header) and the sweep appends
// the rest. Throws std::runtime_error naming results.csv when it is damaged.
struct ResumedRows {
  std::uint64_t rows = 0;
  std::uint64_t errors = 0;
  bool finished = false;
};
ResumedRows KeepResumableRows(const std::string& dir, const std::vector<std::string>& columns,
                              const ShardPoints& shard, const GridTexts& grid);

// Writes `results` (results.csv of the whole grid) from the shards' results files, shard i
// at `paths[i]`, row by row in point order, each row checked as a resumed sweep checks its
// own (RowProblem, against the manifest's grid). Throws std::runtime_error naming the
// shard file and row.
void WriteMergedRows(const std::string& results, const std::vector<std::string>& paths,
                     const nlohmann::json& manifest);

}  // namespace shapebench::bench
