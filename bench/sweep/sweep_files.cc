#include "bench/sweep/sweep_files.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/fd_stream.h"
#include "bench/sweep/output_dir.h"
#include "bench/sweep/sweep_plot.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFormat = "shapebench sweep 1";
// manifest.json is small (its largest part is a grid's value lists); anything larger is
// not one shapebench wrote and is not read into memory.
constexpr std::uint64_t kMaxManifestBytes = 64ull << 20;

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
      } else if (values.kind == SweepValues::Kind::kSampled) {
        // What draws the samples, with the manifest's "sampling" (the k-th distribution key
        // is dimension k): a merge computes each row's values from it. Not the list: 20 MB
        // a million samples.
        entry["distribution"] = values.distribution->Describe();
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

// A whole number >= 0 written as one: "1e9", -1 and 0.5 are not a count or an index
// (and converting 1e30 to an integer is undefined).
std::uint64_t WholeNumber(const nlohmann::json& value, const std::string& what) {
  if (!value.is_number_unsigned()) throw std::runtime_error(what + ": expected a whole number >= 0 (digits only)");
  return value.get<std::uint64_t>();
}

const std::string& Text(const nlohmann::json& object, const char* key) {
  const nlohmann::json& value = object.at(key);
  if (!value.is_string()) throw std::runtime_error(std::string(key) + ": expected a string");
  return value.get_ref<const std::string&>();
}

// One key's values as the manifest's grid keeps them (GridJson), checked as the sweep
// loader checks them (bench/sweep/sweep.cc, ReadRange): a list of at least one text, or a
// range of at least one step (one only when from equals to), log spaced above 0.
SweepValues GridValues(const nlohmann::json& entry, const std::optional<SweepSampling>& sampling,
                       std::size_t* dimensions) {
  if (!entry.is_object()) throw std::runtime_error("grid: expected each key an object");
  SweepValues values;
  values.key = Text(entry, "key");
  const std::string where = "grid: key " + values.key + ": ";
  if (entry.contains("distribution") && !entry.contains("list")) {
    if (!sampling) throw std::runtime_error(where + "a distribution without the manifest's sampling");
    const std::size_t dimension = (*dimensions)++;
    try {
      CheckSampleDesign(*sampling, dimension + 1);
      values.distribution = ParseDistribution(Text(entry, "distribution"));
    } catch (const std::exception& error) {
      throw std::runtime_error(where + error.what());
    }
    values.kind = SweepValues::Kind::kSampled;
    values.draw = std::make_shared<const SampleDraw>(*sampling, dimension, *values.distribution);
    return values;
  }
  if (entry.contains("list")) {  // a list (or a sampled key's values, as manifests listed them once)
    const nlohmann::json& list = entry.at("list");
    if (!list.is_array() || list.empty()) throw std::runtime_error(where + "expected a list of values");
    for (const auto& text : list) {
      if (!text.is_string()) throw std::runtime_error(where + "expected the list's values as strings");
      values.texts.push_back(text.get<std::string>());
    }
    return values;
  }
  const std::string& spacing = Text(entry, "spacing");
  if (spacing != "linear" && spacing != "log") throw std::runtime_error(where + "spacing: expected linear or log");
  values.kind = spacing == "log" ? SweepValues::Kind::kLog : SweepValues::Kind::kLinear;
  if (!entry.at("from").is_number() || !entry.at("to").is_number()) {
    throw std::runtime_error(where + "expected from and to as numbers");
  }
  values.from = entry.at("from").get<double>();
  values.to = entry.at("to").get<double>();
  values.steps = WholeNumber(entry.at("steps"), where + "steps");
  if (values.steps == 0 || (values.steps == 1 && values.from != values.to)) {
    throw std::runtime_error(where + "steps: expected at least 1 (2 unless from equals to)");
  }
  if (values.log() && !(values.from > 0.0 && values.to > 0.0)) {
    throw std::runtime_error(where + "log spacing needs from > 0 and to > 0");
  }
  return values;
}

// The manifest's "sampling" ({samples, seed, design}), nullopt when absent.
std::optional<SweepSampling> ManifestSampling(const nlohmann::json& manifest) {
  if (!manifest.contains("sampling")) return std::nullopt;
  const nlohmann::json& json = manifest.at("sampling");
  if (!json.is_object()) throw std::runtime_error("sampling: expected {samples, seed, design}");
  SweepSampling sampling;
  sampling.samples = WholeNumber(json.at("samples"), "sampling.samples");
  sampling.seed = WholeNumber(json.at("seed"), "sampling.seed");
  const std::string& design = Text(json, "design");
  for (const SampleDesign known : {SampleDesign::kRandom, SampleDesign::kLatinHypercube, SampleDesign::kSobol}) {
    if (design == DesignName(known)) sampling.design = known;
  }
  if (design != DesignName(sampling.design)) {
    throw std::runtime_error("sampling.design: expected random, latin_hypercube or sobol");
  }
  if (sampling.samples < 1) throw std::runtime_error("sampling.samples: expected at least 1");
  return sampling;
}

}  // namespace

GridTexts GridTexts::Of(const Sweep& sweep) {
  GridTexts grid;
  for (const SweepAxis& axis : sweep.axes) grid.axes_.push_back(axis.keys);
  return grid;
}

GridTexts GridTexts::FromManifest(const nlohmann::json& manifest, bool* present) {
  GridTexts grid;
  *present = manifest.contains("grid");
  if (!*present) return grid;
  const auto columns = manifest.at("columns").get<std::vector<std::string>>();
  const std::uint64_t manifest_points = WholeNumber(manifest.at("points"), "points");
  const nlohmann::json& axes = manifest.at("grid");
  if (!axes.is_array()) throw std::runtime_error("grid: expected an array of axes");
  const std::optional<SweepSampling> sampling = ManifestSampling(manifest);
  std::size_t dimensions = 0;
  std::uint64_t points = 1;
  std::size_t column = 1;
  for (const auto& axis : axes) {
    if (!axis.is_array() || axis.empty()) throw std::runtime_error("grid: expected each axis an array of keys");
    std::vector<SweepValues> keys;
    for (const auto& entry : axis) {
      SweepValues values = GridValues(entry, sampling, &dimensions);
      if ((!keys.empty() && values.size() != keys.front().size()) || column >= columns.size() ||
          columns[column++] != values.key) {
        throw std::runtime_error("grid: key " + values.key + " does not fit the columns");
      }
      keys.push_back(std::move(values));
    }
    if (keys.front().size() > manifest_points / points) {
      throw std::runtime_error("grid: its axes have more points than the manifest's count");
    }
    points *= keys.front().size();
    grid.axes_.push_back(std::move(keys));
  }
  if (points != manifest_points || column + 2 > columns.size()) {
    throw std::runtime_error("grid: its points do not match the manifest's count");
  }
  return grid;
}

std::vector<std::string> GridTexts::Texts(std::uint64_t point) const {
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

std::vector<std::string> ResultColumns(const Sweep& sweep) {
  std::vector<std::string> columns = {"point"};
  for (const auto& key : sweep.Keys()) columns.push_back(key);
  columns.insert(columns.end(), sweep.metrics.begin(), sweep.metrics.end());
  columns.push_back("status");
  columns.push_back("error");
  return columns;
}

nlohmann::ordered_json ManifestJson(const Sweep& sweep, const std::vector<Override>& sets,
                                    std::uint64_t shard_index, std::uint64_t shard_count) {
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["hash"] = SweepHash(sweep, sets);
  json["sweep"] = sweep.file;
  json["base"] = sweep.base;
  json["set"] = nlohmann::ordered_json::array();
  for (const Override& set : sets) json["set"].push_back(set.key_path + "=" + set.value_yaml);
  json["points"] = sweep.points;
  json["shard"] = {{"index", shard_index}, {"count", shard_count}};
  json["columns"] = ResultColumns(sweep);
  json["layout"] = SweepLayout::Of(sweep).ToJson();
  json["grid"] = GridJson(sweep);
  if (sweep.sampling) {
    json["sampling"] = {{"samples", sweep.sampling->samples},
                        {"seed", sweep.sampling->seed},
                        {"design", DesignName(sweep.sampling->design)}};
  }
  return json;
}

std::string MergedManifestText(const std::string& shard_manifest_text) {
  nlohmann::ordered_json manifest = nlohmann::ordered_json::parse(shard_manifest_text);
  manifest["shard"] = {{"index", 0}, {"count", 1}};
  return manifest.dump(2) + "\n";
}

std::string DescribeManifest(const nlohmann::json& manifest) {
  const auto& shard = manifest.at("shard");
  return "sweep " + manifest.value("sweep", std::string("?")) + " (hash " +
         manifest.value("hash", std::string("?")) + ", shard " +
         std::to_string(shard.at("index").get<std::uint64_t>()) + "/" +
         std::to_string(shard.at("count").get<std::uint64_t>()) + ")";
}

namespace {

// The plot layout merge draws with (bench/sweep/sweep_plot.cc reads results.csv's rows
// with it): its keys and metrics the columns', its axes (the grid's, when kept) with as
// many points as the manifest, and each plot's metric and keys among them, a plot's two
// keys on two axes as the sweep loader demands. Else a hostile layout would have the
// plotter allocate for 10^12 values of an axis from a 22-row results.csv.
void CheckLayout(const SweepLayout& layout, const std::vector<std::string>& columns,
                 std::uint64_t points, const GridTexts* grid) {
  const std::vector<std::string> keys(columns.begin() + 1, columns.end() - 2);
  std::vector<std::string> layout_columns = layout.keys;
  layout_columns.insert(layout_columns.end(), layout.metrics.begin(), layout.metrics.end());
  if (layout_columns != keys) throw std::runtime_error("layout: its keys and metrics are not the columns");
  std::uint64_t product = 1;
  for (const std::uint64_t size : layout.axis_sizes) {
    if (size > points / product) throw std::runtime_error("layout: its axes have more points than the manifest");
    product *= size;
  }
  if (product != points) throw std::runtime_error("layout: its axes do not have the manifest's points");
  if (grid != nullptr) {
    const SweepLayout expected = [&] {
      Sweep sweep;
      for (const auto& axis : grid->axes()) sweep.axes.push_back(SweepAxis{axis});
      return SweepLayout::Of(sweep);
    }();
    if (layout.keys != expected.keys || layout.key_axis != expected.key_axis ||
        layout.key_log != expected.key_log || layout.axis_sizes != expected.axis_sizes) {
      throw std::runtime_error("layout: its axes are not the grid's");
    }
  }
  const auto axis_of = [&](const std::string& key) {
    for (std::size_t k = 0; k < layout.keys.size(); ++k) {
      if (layout.keys[k] == key) return layout.key_axis[k];
    }
    throw std::runtime_error("layout: a plot of '" + key + "', not a key of the grid");
  };
  for (const SweepPlot& plot : layout.plots) {
    if (std::find(layout.metrics.begin(), layout.metrics.end(), plot.metric) == layout.metrics.end()) {
      throw std::runtime_error("layout: a plot of '" + plot.metric + "', not a kept metric");
    }
    const std::uint64_t x_axis = axis_of(plot.heatmap() ? plot.heatmap_x : plot.x);
    const std::string& y = plot.heatmap() ? plot.heatmap_y : plot.series;
    if (!y.empty() && axis_of(y) == x_axis) {
      throw std::runtime_error("layout: a plot whose two keys move together");
    }
  }
}

// Everything ReadManifest checks, on the parsed text.
void CheckManifest(const nlohmann::json& json) {
  if (!json.is_object() || !json.contains("format") || json.at("format") != kFormat) {
    throw std::runtime_error("not a shapebench sweep manifest");
  }
  Text(json, "hash");
  if (json.contains("sweep")) Text(json, "sweep");
  const std::uint64_t points = WholeNumber(json.at("points"), "points");
  const nlohmann::json& shard = json.at("shard");
  if (!shard.is_object()) throw std::runtime_error("shard: expected {index, count}");
  const std::uint64_t index = WholeNumber(shard.at("index"), "shard.index");
  const std::uint64_t count = WholeNumber(shard.at("count"), "shard.count");
  if (count < 1 || index >= count) {
    throw std::runtime_error("shard: expected index in 0..count-1 and count >= 1");
  }
  const nlohmann::json& columns_json = json.at("columns");
  if (!columns_json.is_array() || columns_json.size() < 3) {
    throw std::runtime_error("columns: expected point, the keys, the metrics, status and error");
  }
  for (const auto& column : columns_json) {
    if (!column.is_string()) throw std::runtime_error("columns: expected strings");
  }
  const auto columns = columns_json.get<std::vector<std::string>>();
  if (columns.front() != "point" || columns[columns.size() - 2] != "status" || columns.back() != "error") {
    throw std::runtime_error("columns: expected point first, status and error last");
  }
  bool grid_present = false;
  const GridTexts grid = GridTexts::FromManifest(json, &grid_present);
  if (json.contains("layout")) {
    CheckLayout(SweepLayout::FromJson(json.at("layout")), columns, points, grid_present ? &grid : nullptr);
  }
}

// Whether a manifest lists a sampled key's values (as manifests did before the samples
// were computed per point).
bool ListsSamples(const nlohmann::json& manifest) {
  if (!manifest.contains("grid")) return false;
  for (const auto& axis : manifest.at("grid")) {
    for (const auto& entry : axis) {
      if (entry.contains("distribution") && entry.contains("list")) return true;
    }
  }
  return false;
}

}  // namespace

nlohmann::json ReadManifest(const std::string& path, std::string* text_out) {
  const std::string text = ReadRegularFile(path, kMaxManifestBytes);
  try {
    nlohmann::json json = nlohmann::json::parse(text);
    CheckManifest(json);
    if (text_out != nullptr) *text_out = text;
    return json;
  } catch (const std::exception& error) {
    throw std::runtime_error(path + ": " + error.what());
  }
}

void CheckResumeDirectory(const std::string& dir_name, const nlohmann::ordered_json& ordered) {
  const fs::path dir(dir_name);
  const nlohmann::json manifest = nlohmann::json::parse(ordered.dump());
  const fs::path manifest_path = dir / kSweepManifestFile;
  if (!fs::exists(manifest_path)) {
    for (const char* name : {kSweepResultsFile, kSweepPartialFile, kSweepAheadFile}) {
      if (fs::exists(dir / name)) {
        throw std::runtime_error(dir.string() + " holds " + name +
                                 " but no manifest.json: not this sweep's output; remove it or "
                                 "choose another --out");
      }
    }
    return;
  }
  const nlohmann::json existing = ReadManifest(manifest_path.string());
  if (existing.at("hash") != manifest.at("hash") && ListsSamples(existing) && manifest.contains("sampling")) {
    // Its hash listed every sample; this version's does not: the same sweep, another hash.
    throw std::runtime_error(dir.string() + " holds " + DescribeManifest(existing) +
                             ", written by an earlier shapebench that listed every sample in its manifest; "
                             "this version cannot resume it: remove it or choose another --out");
  }
  if (existing.at("hash") != manifest.at("hash") ||
      existing.at("points") != manifest.at("points") ||
      existing.at("columns") != manifest.at("columns")) {
    throw std::runtime_error(dir.string() + " holds the results of another " + DescribeManifest(existing) +
                             "; its grid, base scenario, --set options or metrics differ from " +
                             "this one's (hash " + manifest.at("hash").get<std::string>() +
                             "); remove it or choose another --out");
  }
  if (existing.at("shard") != manifest.at("shard")) {
    throw std::runtime_error(dir.string() + " holds " + DescribeManifest(existing) +
                             ", not shard " + std::to_string(manifest.at("shard").at("index").get<std::uint64_t>()) +
                             "/" + std::to_string(manifest.at("shard").at("count").get<std::uint64_t>()) +
                             "; give each shard its own --out");
  }
}

// Merging writes only into an empty directory or one holding this sweep's merged (or
// unsharded, the same bytes) result: never over another sweep's results, whose plots
// would stay behind, nor over an unfinished run's results.csv.partial.
void CheckMergeOutput(const std::string& dir_name, const nlohmann::json& shard_manifest) {
  const fs::path dir(dir_name);
  bool empty = true;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != kOutputLockFile) empty = false;
  }
  if (empty) return;
  const std::string refused = "merge: " + dir.string() + " is not empty and ";
  if (!fs::exists(dir / kSweepManifestFile)) {
    throw std::runtime_error(refused + "holds no sweep's manifest.json; choose an empty or new directory");
  }
  const nlohmann::json existing = ReadManifest((dir / kSweepManifestFile).string());
  if (existing.at("hash") != shard_manifest.at("hash") ||
      existing.at("points") != shard_manifest.at("points") ||
      existing.at("columns") != shard_manifest.at("columns") ||
      existing.at("shard").at("count").get<std::uint64_t>() != 1) {
    throw std::runtime_error(refused + "holds " + DescribeManifest(existing) +
                             ", not this sweep's merged result; remove it or choose another directory");
  }
  if (fs::exists(dir / kSweepPartialFile) || fs::exists(dir / kSweepAheadFile)) {
    throw std::runtime_error(refused + "holds an unfinished run of this sweep (" + kSweepPartialFile +
                             "); finish it with `shapebench sweep` or choose another directory");
  }
}

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

RowScan ScanRows(const std::string& path, const std::vector<std::string>& columns,
                 const ShardPoints& shard, const GridTexts& grid) {
  RowScan scan;
  std::error_code ec;
  if (!fs::exists(path, ec)) return scan;
  RequireRegularFile(path);
  InputFile in(path);
  CsvReader reader(in.stream());
  std::vector<std::string> fields;
  const bool header = reader.Next(&fields);
  // A failed read is not the end of the rows: cutting the file there would lose good ones.
  in.ThrowIfFailed();
  if (!header || fields != columns) return scan;
  scan.header_ok = true;
  scan.good_bytes = reader.offset();
  while (scan.rows < shard.Size() && reader.Next(&fields)) {
    const std::uint64_t point = shard.Point(scan.rows);
    if (!RowProblem(fields, columns.size(), point, grid.Texts(point)).empty()) break;
    if (fields[columns.size() - 2] == "error") ++scan.errors;
    ++scan.rows;
    scan.good_bytes = reader.offset();
  }
  in.ThrowIfFailed();
  return scan;
}

ResumedRows KeepResumableRows(const std::string& dir_name, const std::vector<std::string>& columns,
                              const ShardPoints& shard, const GridTexts& grid) {
  const fs::path dir(dir_name);
  const fs::path results = dir / kSweepResultsFile;
  const fs::path partial = dir / kSweepPartialFile;
  ResumedRows resumed;
  std::error_code ec;
  if (fs::exists(results)) {
    const RowScan scan = ScanRows(results.string(), columns, shard, grid);
    if (scan.rows != shard.Size() || scan.good_bytes != fs::file_size(results)) {
      throw std::runtime_error(results.string() + " does not hold this sweep's " +
                               std::to_string(shard.Size()) + " rows (damaged?); remove it to run again");
    }
    fs::remove(partial, ec);
    fs::remove(dir / kSweepAheadFile, ec);  // its rows are all in results.csv
    resumed.rows = scan.rows;
    resumed.errors = scan.errors;
    resumed.finished = true;
    return resumed;
  }
  const RowScan scan = ScanRows(partial.string(), columns, shard, grid);
  if (!scan.header_ok && !fs::exists(partial)) {
    // A new sweep: the header is written as the rows will be, synced with them at the end
    // (RunSweep). A crash before that leaves at worst a torn header, which the next run
    // finds not ok and writes again (below): no need for two syncs of its own.
    std::ofstream out(partial, std::ios::binary);
    out << CsvRecord(columns);
    if (!out.flush()) throw std::runtime_error("cannot write " + partial.string());
  } else if (!scan.header_ok) {
    WriteFileAtomically(partial.string(), [&](std::ostream& out) { out << CsvRecord(columns); });
  } else if (scan.good_bytes != fs::file_size(partial)) {
    fs::resize_file(partial, scan.good_bytes);  // a torn or foreign tail is run again
  }
  resumed.rows = scan.rows;
  resumed.errors = scan.errors;
  return resumed;
}

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

}  // namespace shapebench::bench
