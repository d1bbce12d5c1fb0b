#include "common/ordered_pool.h"
#include "bench/sweep/sweep_runner.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/fd_stream.h"
#include "common/csv.h"
#include "common/interrupt.h"
#include "bench/sweep/output_dir.h"
#include "bench/sweep/sweep_plot.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kFormat = "shapebench sweep 1";
constexpr const char* kManifest = "manifest.json";
constexpr const char* kResults = "results.csv";
constexpr const char* kPartial = "results.csv.partial";
// manifest.json is small (its largest part is a grid's value lists); anything larger is
// not one shapebench wrote and is not read into memory.
constexpr std::uint64_t kMaxManifestBytes = 64ull << 20;

// The k-th point of a shard, and how many points it has.
struct ShardPoints {
  std::uint64_t total = 0;
  std::uint64_t index = 0;
  std::uint64_t count = 1;
  std::uint64_t Point(std::uint64_t k) const { return index + k * count; }
  std::uint64_t Size() const { return total > index ? (total - index - 1) / count + 1 : 0; }
};

// The grid's values as the manifest keeps them: an array of axes, each an array of its
// keys' values (a list's texts, or a range's from, to, steps and spacing), so that `merge`
// can tell each point's key values without the sweep file.
nlohmann::ordered_json GridJson(const Sweep& sweep) {
  nlohmann::ordered_json grid = nlohmann::ordered_json::array();
  for (const SweepAxis& axis : sweep.axes) {
    nlohmann::ordered_json keys = nlohmann::ordered_json::array();
    for (const SweepValues& values : axis.keys) {
      nlohmann::ordered_json entry = {{"key", values.key}};
      if (values.kind == SweepValues::Kind::kList) {
        entry["list"] = values.texts;
      } else {
        entry["from"] = values.from;
        entry["to"] = values.to;
        entry["steps"] = values.steps;
        entry["spacing"] = values.log() ? "log" : "linear";
      }
      keys.push_back(entry);
    }
    grid.push_back(keys);
  }
  return grid;
}

// The key values of every point of a grid: results.csv's key columns of point p.
class GridTexts {
 public:
  static GridTexts Of(const Sweep& sweep) {
    GridTexts grid;
    for (const SweepAxis& axis : sweep.axes) grid.axes_.push_back(axis.keys);
    return grid;
  }

  // From a manifest's "grid" (*present false, no keys, when absent: manifests written
  // before it was kept); throws std::runtime_error when it does not fit the manifest's
  // columns and point count.
  static GridTexts FromManifest(const nlohmann::json& manifest, bool* present) {
    GridTexts grid;
    *present = manifest.contains("grid");
    if (!*present) return grid;
    const auto columns = manifest.at("columns").get<std::vector<std::string>>();
    std::uint64_t points = 1;
    std::size_t column = 1;
    for (const auto& axis : manifest.at("grid")) {
      std::vector<SweepValues> keys;
      for (const auto& entry : axis) {
        SweepValues values;
        values.key = entry.at("key").get<std::string>();
        if (entry.contains("list")) {
          values.texts = entry.at("list").get<std::vector<std::string>>();
        } else {
          const std::string spacing = entry.at("spacing").get<std::string>();
          values.kind = spacing == "log" ? SweepValues::Kind::kLog : SweepValues::Kind::kLinear;
          values.from = entry.at("from").get<double>();
          values.to = entry.at("to").get<double>();
          values.steps = entry.at("steps").get<std::uint64_t>();
        }
        if (values.size() == 0 || (!keys.empty() && values.size() != keys.front().size()) ||
            column >= columns.size() || columns[column++] != values.key) {
          throw std::runtime_error("grid: key " + values.key + " does not fit the columns");
        }
        keys.push_back(values);
      }
      if (keys.empty() || keys.front().size() > manifest.at("points").get<std::uint64_t>() / points) {
        throw std::runtime_error("grid: its axes have more points than the manifest's count");
      }
      points *= keys.front().size();
      grid.axes_.push_back(keys);
    }
    if (points != manifest.at("points").get<std::uint64_t>() || column + 2 > columns.size()) {
      throw std::runtime_error("grid: its points do not match the manifest's count");
    }
    return grid;
  }

  // Point p's values: the mixed-radix digits of p, the last axis varying fastest.
  std::vector<std::string> Texts(std::uint64_t point) const {
    std::vector<std::string> texts;
    std::vector<std::uint64_t> digits(axes_.size());
    for (std::size_t a = axes_.size(); a-- > 0;) {
      digits[a] = point % axes_[a].front().size();
      point /= axes_[a].front().size();
    }
    for (std::size_t a = 0; a < axes_.size(); ++a) {
      for (const SweepValues& values : axes_[a]) texts.push_back(values.Text(digits[a]));
    }
    return texts;
  }

 private:
  std::vector<std::vector<SweepValues>> axes_;
};

// Why `fields` is not point `point`'s row of results.csv ("" when it is): the field
// count, the point index, the key values (`keys`; none to skip them) and the status.
std::string RowProblem(const std::vector<std::string>& fields, std::size_t columns,
                       std::uint64_t point, const std::vector<std::string>& keys) {
  if (fields.size() != columns) {
    return std::to_string(fields.size()) + " fields, not " + std::to_string(columns);
  }
  if (fields[0] != std::to_string(point)) {
    return "point '" + fields[0] + "', expected " + std::to_string(point);
  }
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (fields[1 + k] != keys[k]) {
      return "key value '" + fields[1 + k] + "', not the grid's '" + keys[k] + "'";
    }
  }
  const std::string& status = fields[columns - 2];
  if (status != "ok" && status != "error") return "status '" + status + "', not ok or error";
  return "";
}

nlohmann::ordered_json Manifest(const Sweep& sweep, const std::vector<Override>& sets,
                                const std::vector<std::string>& columns,
                                const SweepRunOptions& options) {
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["hash"] = SweepHash(sweep, sets);
  json["sweep"] = sweep.file;
  json["base"] = sweep.base;
  json["set"] = nlohmann::ordered_json::array();
  for (const Override& set : sets) json["set"].push_back(set.key_path + "=" + set.value_yaml);
  json["points"] = sweep.points;
  json["shard"] = {{"index", options.shard_index}, {"count", options.shard_count}};
  json["columns"] = columns;
  json["layout"] = SweepLayout::Of(sweep).ToJson();
  json["grid"] = GridJson(sweep);
  return json;
}

std::string Describe(const nlohmann::json& manifest) {
  const auto& shard = manifest.at("shard");
  return "sweep " + manifest.value("sweep", std::string("?")) + " (hash " +
         manifest.value("hash", std::string("?")) + ", shard " +
         std::to_string(shard.at("index").get<std::uint64_t>()) + "/" +
         std::to_string(shard.at("count").get<std::uint64_t>()) + ")";
}

nlohmann::json ReadManifest(const fs::path& path) {
  const std::string text = ReadRegularFile(path.string(), kMaxManifestBytes);
  try {
    nlohmann::json json = nlohmann::json::parse(text);
    if (json.value("format", std::string()) != kFormat) {
      throw std::runtime_error("not a shapebench sweep manifest");
    }
    json.at("hash").get<std::string>();
    json.at("points").get<std::uint64_t>();
    json.at("shard").at("index").get<std::uint64_t>();
    json.at("shard").at("count").get<std::uint64_t>();
    const auto columns = json.at("columns").get<std::vector<std::string>>();
    if (columns.size() < 3) throw std::runtime_error("columns: too few");
    const std::uint64_t count = json.at("shard").at("count").get<std::uint64_t>();
    if (count < 1 || json.at("shard").at("index").get<std::uint64_t>() >= count) {
      throw std::runtime_error("shard: expected index in 0..count-1 and count >= 1");
    }
    return json;
  } catch (const std::exception& error) {
    throw std::runtime_error(path.string() + ": " + error.what());
  }
}

std::string Fields(const std::vector<std::string>& fields) { return CsvRecord(fields); }

// Scans a results file of the shard: the header, then rows for points Point(0), Point(1),
// ... with the right number of fields. Returns how many rows hold; *good_bytes is where
// the last of them ends; *header_ok whether the header is this sweep's.
std::uint64_t ScanRows(const fs::path& path, const std::vector<std::string>& columns,
                       const ShardPoints& shard, const GridTexts& grid, std::uint64_t* good_bytes,
                       bool* header_ok, std::uint64_t* errors) {
  *good_bytes = 0;
  *header_ok = false;
  *errors = 0;
  std::error_code ec;
  if (!fs::exists(path, ec)) return 0;
  RequireRegularFile(path.string());
  InputFile in(path.string());
  CsvReader reader(in.stream());
  std::vector<std::string> fields;
  const bool header = reader.Next(&fields);
  // A failed read is not the end of the rows: cutting the file there would lose good ones.
  in.ThrowIfFailed();
  if (!header || fields != columns) return 0;
  *header_ok = true;
  *good_bytes = reader.offset();
  std::uint64_t rows = 0;
  while (rows < shard.Size() && reader.Next(&fields)) {
    const std::uint64_t point = shard.Point(rows);
    if (!RowProblem(fields, columns.size(), point, grid.Texts(point)).empty()) break;
    if (fields[columns.size() - 2] == "error") ++*errors;
    ++rows;
    *good_bytes = reader.offset();
  }
  in.ThrowIfFailed();
  return rows;
}

void CheckDirectory(const fs::path& dir, const nlohmann::ordered_json& ordered) {
  const nlohmann::json manifest = nlohmann::json::parse(ordered.dump());
  const fs::path manifest_path = dir / kManifest;
  if (!fs::exists(manifest_path)) {
    for (const char* name : {kResults, kPartial}) {
      if (fs::exists(dir / name)) {
        throw std::runtime_error(dir.string() + " holds " + name +
                                 " but no manifest.json: not this sweep's output; remove it or "
                                 "choose another --out");
      }
    }
    return;
  }
  const nlohmann::json existing = ReadManifest(manifest_path);
  if (existing.at("hash") != manifest.at("hash") ||
      existing.at("points") != manifest.at("points") ||
      existing.at("columns") != manifest.at("columns")) {
    throw std::runtime_error(dir.string() + " holds the results of another " + Describe(existing) +
                             "; its grid, base scenario, --set options or metrics differ from " +
                             "this one's (hash " + manifest.at("hash").get<std::string>() +
                             "); remove it or choose another --out");
  }
  if (existing.at("shard") != manifest.at("shard")) {
    throw std::runtime_error(dir.string() + " holds " + Describe(existing) +
                             ", not shard " + std::to_string(manifest.at("shard").at("index").get<std::uint64_t>()) +
                             "/" + std::to_string(manifest.at("shard").at("count").get<std::uint64_t>()) +
                             "; give each shard its own --out");
  }
}

// A progress bar on stderr: done/total, rate and time left; at most ten redraws a second.
class ProgressBar {
 public:
  ProgressBar(bool enabled, std::uint64_t total, std::uint64_t already)
      : enabled_(enabled), total_(total), already_(already), start_(Clock::now()) {}

  void Update(std::uint64_t done, bool force = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (!force && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0.0 ? static_cast<double>(done - already_) / elapsed : 0.0;
    const double left_s = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
    constexpr int kWidth = 30;
    const int filled = total_ == 0 ? kWidth : static_cast<int>(kWidth * done / total_);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    const long left = static_cast<long>(left_s + 0.5);
    char line[160];
    std::snprintf(line, sizeof line, "\r[%s] %llu/%llu points  %.1f points/s  %ld:%02ld:%02ld left ",
                  bar.c_str(), static_cast<unsigned long long>(done),
                  static_cast<unsigned long long>(total_), rate, left / 3600, left / 60 % 60,
                  left % 60);
    std::cerr << line << std::flush;
    drawn_ = true;
  }

  void Finish(std::uint64_t done) {
    if (!enabled_) return;
    Update(done, true);
    if (drawn_) std::cerr << "\n" << std::flush;
  }

 private:
  bool enabled_;
  std::uint64_t total_;
  std::uint64_t already_;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool drawn_ = false;
};

struct Row {
  std::string text;
  bool ok = false;
};

// The metric table rows of results.csv's columns, in `metrics` order.
std::vector<const MetricInfo*> MetricColumns(const std::vector<std::string>& metrics) {
  std::vector<const MetricInfo*> columns;
  for (const auto& metric : metrics) {
    if (const MetricInfo* info = FindMetric(metric)) columns.push_back(info);
  }
  return columns;
}

Row FormatRow(const Sweep& sweep, const std::vector<Override>& sets,
              const std::vector<const MetricInfo*>& metric_columns, std::uint64_t point_index) {
  const SweepPoint point = MakePoint(sweep, point_index, sets);
  const PointOutcome outcome = RunPoint(sweep, sets, point_index);
  std::vector<std::string> fields;
  fields.reserve(3 + point.texts.size() + metric_columns.size());
  fields.push_back(std::to_string(point_index));
  fields.insert(fields.end(), point.texts.begin(), point.texts.end());
  for (const MetricInfo* info : metric_columns) {
    fields.push_back(outcome.ok() ? ExactDouble(outcome.metrics.*info->field) : std::string());
  }
  fields.push_back(outcome.ok() ? "ok" : "error");
  fields.push_back(outcome.error);
  return Row{CsvRecord(fields), outcome.ok()};
}

void WriteAll(std::FILE* file, const std::string& text, const std::string& path) {
  if (std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fflush(file) != 0) {
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  }
}

}  // namespace

std::vector<std::string> ResultColumns(const Sweep& sweep) {
  std::vector<std::string> columns = {"point"};
  for (const auto& key : sweep.Keys()) columns.push_back(key);
  columns.insert(columns.end(), sweep.metrics.begin(), sweep.metrics.end());
  columns.push_back("status");
  columns.push_back("error");
  return columns;
}

SweepRunSummary RunSweep(const Sweep& sweep, const std::vector<Override>& sets,
                         const SweepRunOptions& options) {
  const auto start = Clock::now();
  const DeferInterrupts defer;  // a signal stops the sweep after its complete rows
  if (options.shard_count < 1 || options.shard_index >= options.shard_count) {
    throw std::runtime_error("--shard I/N needs N >= 1 and I in 0..N-1");
  }
  const fs::path dir(options.out_dir);
  const std::vector<std::string> columns = ResultColumns(sweep);
  const nlohmann::ordered_json manifest = Manifest(sweep, sets, columns, options);
  const ShardPoints shard{sweep.points, options.shard_index, options.shard_count};
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw std::runtime_error("cannot create " + dir.string() + ": " +
                             (ec ? ec.message() : "not a directory"));
  }
  const OutputDirLock lock(dir.string());  // one writer at a time, until we return
  CheckDirectory(dir, manifest);
  const GridTexts grid = GridTexts::Of(sweep);
  WriteFileAtomically((dir / kManifest).string(),
                      [&](std::ostream& out) { out << manifest.dump(2) << "\n"; });

  SweepRunSummary summary;
  summary.points = shard.Size();
  summary.results = (dir / kResults).string();
  const fs::path partial = dir / kPartial;
  std::uint64_t good_bytes = 0;
  bool header_ok = false;
  if (fs::exists(dir / kResults)) {
    const std::uint64_t rows =
        ScanRows(dir / kResults, columns, shard, grid, &good_bytes, &header_ok, &summary.errors);
    if (rows != shard.Size() || good_bytes != fs::file_size(dir / kResults)) {
      throw std::runtime_error(summary.results + " does not hold this sweep's " +
                               std::to_string(shard.Size()) + " rows (damaged?); remove it to run again");
    }
    fs::remove(partial, ec);
    summary.resumed = rows;
  } else {
    summary.resumed = ScanRows(partial, columns, shard, grid, &good_bytes, &header_ok, &summary.errors);
    if (!header_ok) {
      WriteFileAtomically(partial.string(), [&](std::ostream& out) { out << Fields(columns); });
    } else if (good_bytes != fs::file_size(partial)) {
      fs::resize_file(partial, good_bytes);  // a torn or foreign tail is run again
    }
    std::FILE* file = std::fopen(partial.c_str(), "ab");
    if (file == nullptr) {
      throw std::runtime_error("cannot write " + partial.string() + ": " + std::strerror(errno));
    }
    const std::vector<const MetricInfo*> columns = MetricColumns(sweep.metrics);
    ProgressBar progress(options.progress, shard.Size(), summary.resumed);
    std::uint64_t written = summary.resumed;
    try {
      RunOrdered<Row>(
          shard.Size() - summary.resumed, options.jobs,
          [&](std::uint64_t k) {
            return FormatRow(sweep, sets, columns, shard.Point(summary.resumed + k));
          },
          [&](std::uint64_t, Row&& row) {
            WriteAll(file, row.text, partial.string());
            if (!row.ok) ++summary.errors;
            progress.Update(++written);
          },
          0, [] { return PendingInterrupt() != 0; });
      progress.Finish(written);
      if (fsync(fileno(file)) != 0) {
        throw std::runtime_error("cannot write " + partial.string() + ": " + std::strerror(errno));
      }
    } catch (...) {
      std::fclose(file);
      throw;
    }
    if (std::fclose(file) != 0) {
      throw std::runtime_error("cannot write " + partial.string() + ": " + std::strerror(errno));
    }
    if (written < shard.Size()) {
      // SIGINT/SIGTERM: the rows so far are complete and flushed; the same command resumes.
      ThrowIfInterrupted(std::to_string(written) + " of " + std::to_string(shard.Size()) +
                         " points done, kept in " + partial.string() +
                         "; run the same command again to resume");
    }
    fs::rename(partial, dir / kResults);
  }
  summary.ok = summary.points - summary.errors;
  ThrowIfInterrupted("all " + std::to_string(summary.points) + " points done, " + summary.results +
                     " is complete; run the same command again to draw the plots");
  if (options.shard_count == 1) {
    try {
      summary.plots = WriteSweepPlots(dir.string(), SweepLayout::Of(sweep), summary.results);
    } catch (const std::exception&) {
      // gnuplot gets the terminal's SIGINT too: report the interruption, not its failure.
      ThrowIfInterrupted(summary.results + " is complete; run the same command again to draw the plots");
      throw;
    }
    ThrowIfInterrupted(summary.results + " and the plots are complete");
  }
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

namespace {

// The shards' manifests, checked to be all the shards of one sweep; *order[i] is the
// position in `shard_dirs` of shard i.
std::vector<nlohmann::json> ReadShards(const std::vector<std::string>& shard_dirs,
                                       std::vector<std::size_t>* order) {
  std::vector<nlohmann::json> manifests;
  for (const std::string& dir : shard_dirs) {
    if (!fs::exists(fs::path(dir) / kManifest)) {
      throw std::runtime_error(dir + ": no manifest.json; not the output of `shapebench sweep`");
    }
    manifests.push_back(ReadManifest(fs::path(dir) / kManifest));
  }
  const nlohmann::json& first = manifests.front();
  const std::uint64_t count = first.at("shard").at("count").get<std::uint64_t>();
  std::vector<int> given(std::min<std::uint64_t>(count, shard_dirs.size()), -1);
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const nlohmann::json& manifest = manifests[i];
    if (manifest.at("hash") != first.at("hash") || manifest.at("points") != first.at("points") ||
        manifest.at("columns") != first.at("columns")) {
      throw std::runtime_error(shard_dirs[i] + " holds " + Describe(manifest) + ", " +
                               shard_dirs[0] + " " + Describe(first) +
                               ": shards of different sweeps (grid, base, --set or metrics) "
                               "cannot be merged");
    }
    if (manifest.at("shard").at("count").get<std::uint64_t>() != count) {
      throw std::runtime_error(shard_dirs[i] + " holds " + Describe(manifest) + ", " + shard_dirs[0] +
                               " " + Describe(first) + ": shards of different --shard N");
    }
    const std::uint64_t index = manifest.at("shard").at("index").get<std::uint64_t>();
    // Fewer directories than shards: one is missing (reported below, for the lowest index).
    if (index >= given.size()) continue;
    if (given[index] >= 0) {
      throw std::runtime_error(shard_dirs[i] + " and " + shard_dirs[given[index]] + " are both shard " +
                               std::to_string(index) + "/" + std::to_string(count));
    }
    given[index] = static_cast<int>(i);
    if (!fs::exists(fs::path(shard_dirs[i]) / kResults)) {
      throw std::runtime_error(shard_dirs[i] + ": shard " + std::to_string(index) + "/" +
                               std::to_string(count) +
                               " is not finished (no results.csv); run its sweep again with the "
                               "same --out to finish it");
    }
  }
  for (std::uint64_t index = 0; index < count; ++index) {
    if (index >= given.size() || given[index] < 0) {
      throw std::runtime_error("shard " + std::to_string(index) + "/" + std::to_string(count) +
                               " is missing; merge needs all " + std::to_string(count) + " shards");
    }
  }
  order->assign(given.begin(), given.end());
  return manifests;
}

// Merging writes only into an empty directory or one holding this sweep's merged (or
// unsharded, the same bytes) result: never over another sweep's results, whose plots
// would stay behind, nor over an unfinished run's results.csv.partial.
void CheckMergeOutput(const fs::path& dir, const nlohmann::json& shard_manifest) {
  bool empty = true;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != kOutputLockFile) empty = false;
  }
  if (empty) return;
  const std::string refused = "merge: " + dir.string() + " is not empty and ";
  if (!fs::exists(dir / kManifest)) {
    throw std::runtime_error(refused + "holds no sweep's manifest.json; choose an empty or new directory");
  }
  const nlohmann::json existing = ReadManifest(dir / kManifest);
  if (existing.at("hash") != shard_manifest.at("hash") ||
      existing.at("points") != shard_manifest.at("points") ||
      existing.at("columns") != shard_manifest.at("columns") ||
      existing.at("shard").at("count").get<std::uint64_t>() != 1) {
    throw std::runtime_error(refused + "holds " + Describe(existing) +
                             ", not this sweep's merged result; remove it or choose another directory");
  }
  if (fs::exists(dir / kPartial)) {
    throw std::runtime_error(refused + "holds an unfinished run of this sweep (" + kPartial +
                             "); finish it with `shapebench sweep` or choose another directory");
  }
}

// Writes results.csv of the whole grid from the shards' results, row by row in point
// order, each row checked as a resumed sweep checks its own (RowProblem).
void WriteMergedRows(const std::string& results, const std::vector<std::string>& paths,
                     const nlohmann::json& manifest) {
  const std::vector<std::string> columns = manifest.at("columns").get<std::vector<std::string>>();
  const std::uint64_t points = manifest.at("points").get<std::uint64_t>();
  const std::uint64_t count = paths.size();
  bool grid_present = false;
  const GridTexts grid = GridTexts::FromManifest(manifest, &grid_present);
  std::vector<std::unique_ptr<InputFile>> files;
  std::vector<CsvReader> readers;
  for (const std::string& path : paths) {
    RequireRegularFile(path);
    files.push_back(std::make_unique<InputFile>(path));
  }
  for (auto& file : files) readers.emplace_back(file->stream());
  // Shard `index` ended (or was torn) where rows were expected: a failed read says so first.
  auto ended = [&](std::uint64_t index, const std::string& what) {
    files[index]->ThrowIfFailed();
    return std::runtime_error(paths[index] + ": " + what);
  };
  std::vector<std::string> fields;
  for (std::uint64_t index = 0; index < count; ++index) {
    if (!readers[index].Next(&fields)) throw ended(index, "its header is not the manifest's columns");
    if (fields != columns) throw std::runtime_error(paths[index] + ": its header is not the manifest's columns");
  }
  WriteFileAtomically(results, [&](std::ostream& out) {
    out << CsvRecord(columns);
    for (std::uint64_t point = 0; point < points; ++point) {
      const std::uint64_t index = point % count;
      const std::string row = "row " + std::to_string(point / count + 1) + " (point " + std::to_string(point) + ")";
      if (!readers[index].Next(&fields)) throw ended(index, row + " is missing (a damaged shard?)");
      const std::string problem = RowProblem(fields, columns.size(), point,
                                             grid_present ? grid.Texts(point) : std::vector<std::string>());
      if (!problem.empty()) {
        throw std::runtime_error(paths[index] + ": " + row + ": " + problem + " (a damaged shard?)");
      }
      out << CsvRecord(fields);
    }
    for (std::uint64_t index = 0; index < count; ++index) {
      const bool more = readers[index].Next(&fields);
      files[index]->ThrowIfFailed();
      if (more || readers[index].torn()) {
        throw std::runtime_error(paths[index] + ": rows beyond the sweep's points (a damaged shard?)");
      }
    }
  });
}

}  // namespace

MergeSummary MergeShards(const std::string& out_dir, const std::vector<std::string>& shard_dirs) {
  if (shard_dirs.empty()) throw std::runtime_error("merge: no shard directories given");
  std::vector<std::size_t> order;
  const std::vector<nlohmann::json> manifests = ReadShards(shard_dirs, &order);
  std::error_code ec;
  for (const std::string& dir : shard_dirs) {
    if (fs::exists(out_dir) && fs::equivalent(out_dir, dir, ec)) {
      throw std::runtime_error("merge: the output directory " + out_dir +
                               " is one of the shards; choose another");
    }
  }
  fs::create_directories(out_dir, ec);
  if (ec || !fs::is_directory(out_dir)) {
    throw std::runtime_error("cannot create " + out_dir + ": " + (ec ? ec.message() : "not a directory"));
  }
  const OutputDirLock lock(out_dir);  // one writer at a time, until we return
  CheckMergeOutput(out_dir, manifests.front());
  std::vector<std::string> paths;
  for (const std::size_t i : order) paths.push_back((fs::path(shard_dirs[i]) / kResults).string());
  MergeSummary summary;
  summary.points = manifests.front().at("points").get<std::uint64_t>();
  summary.shards = order.size();
  summary.results = (fs::path(out_dir) / kResults).string();
  // Shard 0's manifest in its own key order (the unsharded run's bytes), as shard 0/1;
  // written first, as a sweep does, so that a merge stopped halfway may be run again.
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(
      ReadRegularFile((fs::path(shard_dirs[order[0]]) / kManifest).string(), kMaxManifestBytes));
  manifest["shard"] = {{"index", 0}, {"count", 1}};
  WriteFileAtomically((fs::path(out_dir) / kManifest).string(),
                      [&](std::ostream& out) { out << manifest.dump(2) << "\n"; });
  WriteMergedRows(summary.results, paths, manifests[order[0]]);
  if (manifest.contains("layout")) {
    summary.plots = WriteSweepPlots(out_dir, SweepLayout::FromJson(manifest.at("layout")), summary.results);
  }
  return summary;
}

}  // namespace shapebench::bench
