#include "common/ordered_pool.h"
#include "bench/sweep/sweep_runner.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/interrupt.h"
#include "bench/sweep/sweep_plot.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kFormat = "shapebench sweep 1";
constexpr const char* kManifest = "manifest.json";
constexpr const char* kResults = "results.csv";
constexpr const char* kPartial = "results.csv.partial";

// The k-th point of a shard, and how many points it has.
struct ShardPoints {
  std::uint64_t total = 0;
  std::uint64_t index = 0;
  std::uint64_t count = 1;
  std::uint64_t Point(std::uint64_t k) const { return index + k * count; }
  std::uint64_t Size() const { return total > index ? (total - index - 1) / count + 1 : 0; }
};

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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot read");
  try {
    nlohmann::json json = nlohmann::json::parse(in);
    if (json.value("format", std::string()) != kFormat) {
      throw std::runtime_error("not a shapebench sweep manifest");
    }
    json.at("hash").get<std::string>();
    json.at("points").get<std::uint64_t>();
    json.at("shard").at("index").get<std::uint64_t>();
    json.at("shard").at("count").get<std::uint64_t>();
    json.at("columns").get<std::vector<std::string>>();
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
                       const ShardPoints& shard, std::uint64_t* good_bytes, bool* header_ok,
                       std::uint64_t* errors) {
  *good_bytes = 0;
  *header_ok = false;
  *errors = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  CsvReader reader(in);
  std::vector<std::string> fields;
  if (!reader.Next(&fields) || fields != columns) return 0;
  *header_ok = true;
  *good_bytes = reader.offset();
  std::uint64_t rows = 0;
  while (rows < shard.Size() && reader.Next(&fields)) {
    const bool status_ok = fields.size() == columns.size() &&
                           (fields[columns.size() - 2] == "ok" || fields[columns.size() - 2] == "error");
    if (!status_ok || fields[0] != std::to_string(shard.Point(rows))) break;
    if (fields[columns.size() - 2] == "error") ++*errors;
    ++rows;
    *good_bytes = reader.offset();
  }
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
  CheckDirectory(dir, manifest);
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
        ScanRows(dir / kResults, columns, shard, &good_bytes, &header_ok, &summary.errors);
    if (rows != shard.Size() || good_bytes != fs::file_size(dir / kResults)) {
      throw std::runtime_error(summary.results + " does not hold this sweep's " +
                               std::to_string(shard.Size()) + " rows (damaged?); remove it to run again");
    }
    fs::remove(partial, ec);
    summary.resumed = rows;
  } else {
    summary.resumed = ScanRows(partial, columns, shard, &good_bytes, &header_ok, &summary.errors);
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

MergeSummary MergeShards(const std::string& out_dir, const std::vector<std::string>& shard_dirs) {
  if (shard_dirs.empty()) throw std::runtime_error("merge: no shard directories given");
  std::vector<nlohmann::json> manifests;
  for (const std::string& dir : shard_dirs) {
    if (!fs::exists(fs::path(dir) / kManifest)) {
      throw std::runtime_error(dir + ": no manifest.json; not the output of `shapebench sweep`");
    }
    manifests.push_back(ReadManifest(fs::path(dir) / kManifest));
  }
  const nlohmann::json& first = manifests.front();
  const std::uint64_t count = first.at("shard").at("count").get<std::uint64_t>();
  std::vector<int> given(count, -1);
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
    if (index >= count) throw std::runtime_error(shard_dirs[i] + ": shard index out of range");
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
    if (given[index] < 0) {
      throw std::runtime_error("shard " + std::to_string(index) + "/" + std::to_string(count) +
                               " is missing; merge needs all " + std::to_string(count) + " shards");
    }
  }
  const std::vector<std::string> columns = first.at("columns").get<std::vector<std::string>>();
  const std::uint64_t points = first.at("points").get<std::uint64_t>();

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
  std::vector<std::unique_ptr<std::ifstream>> streams;
  std::vector<CsvReader> readers;
  std::vector<std::string> paths;
  for (std::uint64_t index = 0; index < count; ++index) {
    paths.push_back((fs::path(shard_dirs[given[index]]) / kResults).string());
    streams.push_back(std::make_unique<std::ifstream>(paths.back(), std::ios::binary));
    if (!*streams.back()) throw std::runtime_error("cannot read " + paths.back());
  }
  for (auto& stream : streams) readers.emplace_back(*stream);
  std::vector<std::string> fields;
  for (std::uint64_t index = 0; index < count; ++index) {
    if (!readers[index].Next(&fields) || fields != columns) {
      throw std::runtime_error(paths[index] + ": its header is not the manifest's columns");
    }
  }
  MergeSummary summary;
  summary.points = points;
  summary.shards = count;
  summary.results = (fs::path(out_dir) / kResults).string();
  WriteFileAtomically(summary.results, [&](std::ostream& out) {
    out << CsvRecord(columns);
    for (std::uint64_t point = 0; point < points; ++point) {
      const std::uint64_t index = point % count;
      if (!readers[index].Next(&fields) || fields.size() != columns.size() ||
          fields[0] != std::to_string(point)) {
        throw std::runtime_error(paths[index] + ": expected the row of point " +
                                 std::to_string(point) + " (a damaged shard?)");
      }
      out << CsvRecord(fields);
    }
    for (std::uint64_t index = 0; index < count; ++index) {
      if (readers[index].Next(&fields) || readers[index].torn()) {
        throw std::runtime_error(paths[index] + ": rows beyond the sweep's points (a damaged shard?)");
      }
    }
  });
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(
      std::ifstream(fs::path(shard_dirs[given[0]]) / kManifest, std::ios::binary));
  manifest["shard"] = {{"index", 0}, {"count", 1}};
  WriteFileAtomically((fs::path(out_dir) / kManifest).string(),
                      [&](std::ostream& out) { out << manifest.dump(2) << "\n"; });
  fs::remove(fs::path(out_dir) / kPartial, ec);
  if (manifest.contains("layout")) {
    summary.plots = WriteSweepPlots(out_dir, SweepLayout::FromJson(manifest.at("layout")), summary.results);
  }
  return summary;
}

}  // namespace shapebench::bench
