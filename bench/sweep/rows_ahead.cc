#include "bench/sweep/rows_ahead.h"

#include <charconv>
#include <filesystem>
#include <stdexcept>

#include "bench/sweep/output_dir.h"  // RequireRegularFile
#include "common/csv.h"
#include "common/fd_stream.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

// The shard's index k of a row whose point field is `text`, when it is a point of the
// shard written as results.csv writes it (digits, no sign, no leading zero).
bool ShardIndexOf(const std::string& text, const ShardPoints& shard, std::uint64_t* k) {
  std::uint64_t point = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), point);
  if (error != std::errc() || end != text.data() + text.size() || std::to_string(point) != text) return false;
  if (point >= shard.total || point < shard.index || (point - shard.index) % shard.count != 0) return false;
  *k = (point - shard.index) / shard.count;
  return true;
}

}  // namespace

RowsAhead RowsAhead::Resume(const std::string& dir, const std::vector<std::string>& columns, const ShardPoints& shard,
                            const GridTexts& grid, std::uint64_t first, Durability durability) {
  RowsAhead ahead;
  const fs::path path = fs::path(dir) / kSweepAheadFile;
  std::error_code ec;
  if (!fs::exists(path, ec)) return ahead;
  RequireRegularFile(path.string());
  std::uint64_t records = 0;  // rows read, kept or not
  bool whole = false;         // the file ended after a good row
  {
    InputFile in(path.string());
    CsvReader reader(in.stream());
    std::vector<std::string> fields;
    const bool header = reader.Next(&fields) && fields == columns;
    in.ThrowIfFailed();
    whole = header;
    while (header && reader.Next(&fields)) {
      std::uint64_t k = 0;
      const bool good = !fields.empty() && ShardIndexOf(fields[0], shard, &k) &&
                        RowProblem(fields, columns.size(), shard.Point(k), grid.Texts(shard.Point(k))).empty();
      if (!good) {
        whole = false;  // a foreign row ends the file, as in the partial file
        break;
      }
      ++records;
      if (k < first || ahead.rows_.size() >= kMaxRowsAhead) continue;  // in the partial file already; or too many
      ahead.rows_.emplace(k, AheadRow{CsvRecord(fields), fields[columns.size() - 2] == "ok"});
    }
    in.ThrowIfFailed();
    whole = whole && !reader.torn();
  }
  if (ahead.rows_.empty()) {
    fs::remove(path, ec);
  } else if (!whole || records != ahead.rows_.size()) {
    WriteFileAtomically(path.string(), [&](std::ostream& out) {
      out << CsvRecord(columns);
      for (const auto& [k, row] : ahead.rows_) out << row.text;
    }, durability);
  }
  return ahead;
}

const AheadRow* RowsAhead::Find(std::uint64_t k) const {
  const auto it = rows_.find(k);
  return it == rows_.end() ? nullptr : &it->second;
}

std::vector<std::uint64_t> RowsAhead::Points() const {
  std::vector<std::uint64_t> points;
  for (const auto& entry : rows_) points.push_back(entry.first);
  return points;
}

}  // namespace shapebench::bench
