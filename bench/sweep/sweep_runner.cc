#include "common/ordered_pool.h"
#include "bench/sweep/sweep_runner.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/fd_stream.h"
#include "common/csv.h"
#include "common/interrupt.h"
#include "bench/output/mat_file.h"
#include "bench/run/closed_form_sampler.h"
#include "bench/sweep/distribute.h"
#include "bench/sweep/output_dir.h"
#include "bench/sweep/point_loop.h"
#include "bench/sweep/rows_ahead.h"
#include "bench/sweep/sweep_rows.h"
#include "bench/sweep/sweep_plot.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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

// SHAPEBENCH_TEST_HANG_POINT=P[,P...]: these points of `sweep` never end (they sleep
// until the process does), as points the solver cannot finish would; how the tests
// (tests/cli/reliability_cli_test.cc, sweep_cli_test.cc) hang a point at a known place,
// and show that a resumed sweep does not run again a point it has the row of.
bool HangsForTests(std::uint64_t point_index) {
  static const std::string hang = [] {
    const char* text = std::getenv("SHAPEBENCH_TEST_HANG_POINT");
    return text == nullptr ? std::string() : "," + std::string(text) + ",";
  }();
  return !hang.empty() && hang.find("," + std::to_string(point_index) + ",") != std::string::npos;
}

// CsvField's test (a comma, a quote or a line break: quoted), a character at a time.
bool NeedsCsvQuotes(const std::string& text) {
  for (const char c : text) {
    if (c == ',' || c == '"' || c == '\r' || c == '\n') return true;
  }
  return false;
}

// A metric's text in a row (AppendExactDouble's), the last one kept per column and
// thread: a column a sweep does not change (motion_time_s along a natural-period sweep)
// is converted once.
void AppendMetricText(std::size_t column, double value, std::string* line) {
  struct Last {
    double value = NAN;
    char text[40];
    std::size_t size = 0;
  };
  thread_local std::vector<Last> last;
  if (last.size() <= column) last.resize(column + 1);
  Last& kept = last[column];
  if (std::memcmp(&kept.value, &value, sizeof value) != 0) {
    kept.size = static_cast<std::size_t>(AppendExactDouble(kept.text, kept.text + sizeof kept.text, value) - kept.text);
    kept.value = value;
  }
  line->append(kept.text, kept.size);
}

Row FormatRow(const Sweep& sweep, const std::vector<Override>& sets,
              const std::vector<const MetricInfo*>& metric_columns, std::uint64_t point_index) {
  while (HangsForTests(point_index)) std::this_thread::sleep_for(std::chrono::seconds(1));
  // The thread's point, its strings' capacity kept from the last one (no allocation a point).
  thread_local SweepPoint point;
  MakePointInto(sweep, point_index, sets, &point);
  // The row reads only its columns: without the contour error's, the closed form skips it.
  const bool contour_read =
      std::any_of(metric_columns.begin(), metric_columns.end(),
                  [](const MetricInfo* info) { return info->field == &Metrics::max_contour_error_m; });
  const ContourUnreadScope contour_unread(!contour_read);
  const PointOutcome outcome = RunPoint(sweep, point);
  // CsvRecord's line, written in place into one string (no temporary a field): a number
  // (ExactDouble's text) never needs quotes.
  std::string line;
  line.reserve(64 + 24 * (point.texts.size() + metric_columns.size()));
  char number[40];
  line.append(number, std::to_chars(number, number + sizeof number, point_index).ptr);
  for (const std::string& text : point.texts) {
    line += ',';
    if (NeedsCsvQuotes(text)) {
      line += CsvField(text);
    } else {
      line += text;  // as CsvField would give it, without its copy
    }
  }
  for (std::size_t c = 0; c < metric_columns.size(); ++c) {
    line += ',';
    const double value = outcome.metrics.*metric_columns[c]->field;
    if (outcome.ok() && !std::isnan(value)) AppendMetricText(c, value, &line);
  }
  line += outcome.ok() ? ",ok," : ",error,";
  line += CsvField(outcome.error);
  line += '\n';
  return Row{std::move(line), outcome.ok()};
}

// A row between MPI ranks: '1' (ok) or '0', then its text.
std::string EncodeRow(const Row& row) { return (row.ok ? "1" : "0") + row.text; }
Row DecodeRow(const std::string& bytes) {
  return Row{bytes.empty() ? std::string() : bytes.substr(1), !bytes.empty() && bytes[0] == '1'};
}

// The output directory, created when missing.
void CreateOutputDir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw std::runtime_error("cannot create " + dir.string() + ": " +
                             (ec ? ec.message() : "not a directory"));
  }
}

// The shard's points from `first` on, their rows appended to the partial file in order
// (after the manifest `preparing` writes, if any) and, while one waits behind an earlier
// point, to results.csv.ahead (rows_ahead.h); the rows `ahead` holds are not run again.
// The partial file is renamed results.csv once complete. An interruption keeps the rows
// so far and says how to resume.
void RunRemainingPoints(const Sweep& sweep, const std::vector<Override>& sets, const SweepRunOptions& options,
                        const ShardPoints& shard, std::uint64_t first, const RowsAhead& ahead,
                        std::future<ResumedRows>* preparing, SweepRunSummary* summary) {
  const std::vector<const MetricInfo*> columns = MetricColumns(sweep.metrics);
  const fs::path dir(options.out_dir);
  // From `first`, as `written` counts (summary->resumed adds the rows ahead: done - already
  // would wrap below zero until they are written).
  ProgressBar progress(options.progress, shard.Size(), first);
  std::uint64_t written = first;
  SweepRows rows(dir, ResultColumns(sweep), preparing, options.durability, ahead.Points());
  try {
    rows.OpenIfReady();
    // k: the shard's k-th point, as ServeSweep's ranks compute it (MPI, distribute.h).
    const PointCodec<Row> codec{EncodeRow, DecodeRow};
    PointHooks<Row> hooks;
    hooks.known = [&](std::uint64_t k) { return ahead.Find(k) != nullptr; };
    hooks.spill.after = kAheadAfter;
    hooks.spill.take = [&](std::uint64_t k, const Row& row) { rows.Ahead(k, row.text); };
    ForEachSweepPoint<Row>(
        first, shard.Size(), options.jobs,
        [&](std::uint64_t k) {
          const AheadRow* done = ahead.Find(k);
          return done != nullptr ? Row{done->text, done->ok} : FormatRow(sweep, sets, columns, shard.Point(k));
        },
        [&](std::uint64_t k, Row&& row) {
          rows.Add(k, row.text);
          if (!row.ok) ++summary->errors;
          progress.Update(++written);
        },
        [] { return PendingInterrupt() != 0; }, &codec, &hooks);
    progress.Finish(written);
    rows.Close();
  } catch (...) {
    rows.KeepComputed();  // the rows computed before the failure are kept, as those written
    throw;
  }
  if (written < shard.Size()) {
    // SIGINT/SIGTERM: the rows so far are complete and flushed; the same command resumes.
    const std::uint64_t waiting = rows.WaitingAhead();
    ThrowIfInterrupted(std::to_string(written + waiting) + " of " + std::to_string(shard.Size()) +
                       " points done, kept in " + (dir / kSweepPartialFile).string() +
                       (waiting > 0 ? " (" + std::to_string(waiting) + " of them, finished ahead of their turn, in " +
                                          (dir / kSweepAheadFile).string() + ")"
                                    : std::string()) +
                       "; run the same command again to resume");
  }
  fs::rename(dir / kSweepPartialFile, summary->results);  // dir / kSweepResultsFile
  std::error_code ec;
  fs::remove(dir / kSweepAheadFile, ec);  // every row of it is in results.csv
}

// results.mat beside a complete results.csv (bench/output/mat_file.h); its path.
// Synced as results.csv is (`sweep --no-sync`: not).
std::string WriteResultsMatBeside(const std::string& results_csv, Durability durability = Durability::kSynced) {
  const std::string path = (fs::path(results_csv).parent_path() / "results.mat").string();
  WriteResultsMat(results_csv, path, durability);
  return path;
}

// The plots of a complete, unsharded sweep, and results.mat.
void DrawPlots(const Sweep& sweep, const fs::path& dir, const SweepRunOptions& options, SweepRunSummary* summary) {
  try {
    summary->plots = WriteSweepPlots(dir.string(), SweepLayout::Of(sweep), summary->results);
    if (options.write_mat) summary->plots.push_back(WriteResultsMatBeside(summary->results, options.durability));
  } catch (const std::exception&) {
    // gnuplot gets the terminal's SIGINT too: report the interruption, not its failure.
    ThrowIfInterrupted(summary->results + " is complete; run the same command again to draw the plots");
    throw;
  }
  ThrowIfInterrupted(summary->results + " and the plots are complete");
}

}  // namespace

SweepRunSummary RunSweep(const Sweep& sweep, const std::vector<Override>& sets,
                         const SweepRunOptions& options) {
  const auto start = Clock::now();
  const DeferInterrupts defer;  // a signal stops the sweep after its complete rows
  if (options.shard_count < 1 || options.shard_index >= options.shard_count) {
    throw std::runtime_error("--shard I/N needs N >= 1 and I in 0..N-1");
  }
  const fs::path dir(options.out_dir);
  const std::vector<std::string> columns = ResultColumns(sweep);
  const nlohmann::ordered_json manifest =
      ManifestJson(sweep, sets, options.shard_index, options.shard_count);
  const ShardPoints shard{sweep.points, options.shard_index, options.shard_count};
  CreateOutputDir(dir);
  const OutputDirLock lock(dir.string());  // one writer at a time, until we return
  SweepRunSummary summary;
  summary.points = shard.Size();
  summary.results = (dir / kSweepResultsFile).string();
  const fs::path partial = dir / kSweepPartialFile;
  // The manifest (synced: two syncs of the disk; none with --no-sync) and the partial
  // file's header, before any row. A new directory's are written while the first points
  // run: the first row waits for them, so no row is on disk before the manifest that says
  // whose it is. A directory with files (a resume) is prepared here: its rows decide where
  // to start.
  const bool fresh = !fs::exists(dir / kSweepManifestFile) && !fs::exists(partial) &&
                     !fs::exists(dir / kSweepResultsFile);
  CheckResumeDirectory(dir.string(), manifest);
  auto prepare = [&] {
    WriteFileAtomically((dir / kSweepManifestFile).string(),
                        [&](std::ostream& out) { out << manifest.dump(2) << "\n"; }, options.durability);
    return KeepResumableRows(dir.string(), columns, shard, GridTexts::Of(sweep));
  };
  // With several jobs on this process's threads, this thread is one of them: it prepares
  // the directory when its first row is ready while the others compute. A thread of its
  // own would be one more than the cores, and on a busy 2-core machine it waited for the
  // scheduler's next tick (about 4 ms) and then took turns with the points (docs/performance.md).
  const bool here = options.jobs > 1 && CurrentDistributor() == nullptr;
  std::future<ResumedRows> preparing;
  const ResumedRows resumed = fresh ? ResumedRows{} : prepare();
  if (fresh) preparing = std::async(here ? std::launch::deferred : std::launch::async, prepare);
  // Rows that finished ahead of their turn before the last run stopped: not run again.
  const RowsAhead ahead = resumed.finished ? RowsAhead{}
                                            : RowsAhead::Resume(dir.string(), columns, shard, GridTexts::Of(sweep),
                                                                resumed.rows, options.durability);
  summary.resumed = resumed.rows + ahead.size();
  summary.errors = resumed.errors;
  if (!resumed.finished) {
    RunRemainingPoints(sweep, sets, options, shard, resumed.rows, ahead, &preparing, &summary);
  }
  summary.ok = summary.points - summary.errors;
  ThrowIfInterrupted("all " + std::to_string(summary.points) + " points done, " + summary.results +
                     " is complete; run the same command again to draw the plots");
  if (options.shard_count == 1) DrawPlots(sweep, dir, options, &summary);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

void ServeSweep(const Sweep& sweep, const std::vector<Override>& sets, const SweepRunOptions& options) {
  const ShardPoints shard{sweep.points, options.shard_index, options.shard_count};
  const std::vector<const MetricInfo*> columns = MetricColumns(sweep.metrics);
  CurrentDistributor()->Serve(options.jobs, [&](std::uint64_t k) {
    return EncodeRow(FormatRow(sweep, sets, columns, shard.Point(k)));
  });
}

namespace {

// The shards' manifests, checked to be all the shards of one sweep; *order[i] is the
// position in `shard_dirs` of shard i.
std::vector<nlohmann::json> ReadShards(const std::vector<std::string>& shard_dirs,
                                       std::vector<std::size_t>* order, std::vector<std::string>* texts) {
  std::vector<nlohmann::json> manifests;
  texts->assign(shard_dirs.size(), "");
  for (const std::string& dir : shard_dirs) {
    if (!fs::exists(fs::path(dir) / kSweepManifestFile)) {
      throw std::runtime_error(dir + ": no manifest.json; not the output of `shapebench sweep`");
    }
    manifests.push_back(ReadManifest((fs::path(dir) / kSweepManifestFile).string(), &(*texts)[manifests.size()]));
  }
  const nlohmann::json& first = manifests.front();
  const std::uint64_t count = first.at("shard").at("count").get<std::uint64_t>();
  std::vector<int> given(std::min<std::uint64_t>(count, shard_dirs.size()), -1);
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const nlohmann::json& manifest = manifests[i];
    if (manifest.at("hash") != first.at("hash") || manifest.at("points") != first.at("points") ||
        manifest.at("columns") != first.at("columns")) {
      throw std::runtime_error(shard_dirs[i] + " holds " + DescribeManifest(manifest) + ", " +
                               shard_dirs[0] + " " + DescribeManifest(first) +
                               ": shards of different sweeps (grid, base, --set or metrics) "
                               "cannot be merged");
    }
    if (manifest.at("shard").at("count").get<std::uint64_t>() != count) {
      throw std::runtime_error(shard_dirs[i] + " holds " + DescribeManifest(manifest) + ", " + shard_dirs[0] +
                               " " + DescribeManifest(first) + ": shards of different --shard N");
    }
    const std::uint64_t index = manifest.at("shard").at("index").get<std::uint64_t>();
    // Fewer directories than shards: one is missing (reported below, for the lowest index).
    if (index >= given.size()) continue;
    if (given[index] >= 0) {
      throw std::runtime_error(shard_dirs[i] + " and " + shard_dirs[given[index]] + " are both shard " +
                               std::to_string(index) + "/" + std::to_string(count));
    }
    given[index] = static_cast<int>(i);
    if (!fs::exists(fs::path(shard_dirs[i]) / kSweepResultsFile)) {
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

}  // namespace

MergeSummary MergeShards(const std::string& out_dir, const std::vector<std::string>& shard_dirs) {
  if (shard_dirs.empty()) throw std::runtime_error("merge: no shard directories given");
  std::vector<std::size_t> order;
  std::vector<std::string> texts;
  const std::vector<nlohmann::json> manifests = ReadShards(shard_dirs, &order, &texts);
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
  for (const std::size_t i : order) paths.push_back((fs::path(shard_dirs[i]) / kSweepResultsFile).string());
  MergeSummary summary;
  summary.points = manifests.front().at("points").get<std::uint64_t>();
  summary.shards = order.size();
  summary.results = (fs::path(out_dir) / kSweepResultsFile).string();
  // Shard 0's manifest as shard 0/1, written first, as a sweep does, so that a merge
  // stopped halfway may be run again.
  const std::string manifest = MergedManifestText(texts[order[0]]);
  WriteFileAtomically((fs::path(out_dir) / kSweepManifestFile).string(),
                      [&](std::ostream& out) { out << manifest; });
  WriteMergedRows(summary.results, paths, manifests[order[0]]);
  if (manifests[order[0]].contains("layout")) {
    summary.plots =
        WriteSweepPlots(out_dir, SweepLayout::FromJson(manifests[order[0]].at("layout")), summary.results);
  }
  summary.plots.push_back(WriteResultsMatBeside(summary.results));
  return summary;
}

}  // namespace shapebench::bench
