// The bodies of the libFuzzer targets (fuzz/fuzz_*.cc), shared with the regression test
// (tests/fuzz/fuzz_regressions_test.cc) that runs every file of fuzz/regressions/TARGET/
// through them. Each takes the input's bytes and returns normally when the bench accepts
// the input or refuses it with its documented, located error. Anything else is a finding:
// a Violation thrown (an invariant broken), another exception escaping, a crash, a
// sanitizer report or a hang.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/config/config_error.h"
#include "bench/measured/modal_file_reader.h"
#include "bench/config/override.h"
#include "bench/scenario/scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/structure_numbers.h"
#include "bench/measured/uff58_reader.h"
#include "bench/measured/accel_log.h"
#include "bench/measured/accel_spectrum.h"
#include "bench/measured/psd_peaks.h"
#include "bench/measured/shaper_fit.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_files.h"
#include "bench/sweep/sweep_plot.h"
#include "bench/sweep/sweep_runner.h"
#include "common/csv.h"
#include "common/validation_error.h"
#include "controller/controller.h"
#include "controller/gcode_parser.h"
#include "model/modal_identification.h"
#include "model/multi_axis_machine.h"
#include "fuzz/fuzz_support.h"

namespace shapebench::fuzz {

// An invariant the input broke (not derived from std::exception: nothing catches it).
struct Violation {
  std::string what;
};

// The small limits every target loads with (after the input's own options, so they
// hold): the loader refuses longer runs before planning, so each input stays quick.
inline std::vector<bench::Override> SmallLimits() {
  return {{"limits.max_simulated_s", "20"}, {"limits.max_ticks", "50000"}};
}

// G-code parser (controller/gcode_parser.h): any bytes are a program or a ProgramError
// at a line and column; a parsed program is finite, and one short enough (64 blocks,
// 5 s) goes through the whole controller (planner, interpolation, filters) on the
// default settings.
inline void GcodeTarget(const std::string& text) {
  controller::Program program;
  try {
    // Loops and subprograms repeat blocks: a block cap keeps a looping input's memory
    // bounded, as the scenario loader's limits do.
    controller::GcodeLimits limits;
    limits.max_blocks = 100000;
    limits.max_blocks_key = "max_blocks";
    program = controller::ParseGcode(text, Eigen::Vector3d::Zero(), limits);
  } catch (const controller::ProgramError& error) {
    if (error.line() < 1 || error.column() < 0) throw Violation{"unlocated: " + std::string(error.what())};
    return;
  }
  for (const controller::ProgramBlock& block : program.blocks) {
    if (!block.start_m.allFinite() || !block.end_m.allFinite() || !block.center_m.allFinite() ||
        !std::isfinite(block.dwell_s)) {
      throw Violation{"a parsed program with a non-finite block"};
    }
  }
  // Long programs only slow the search down (the parser is the target; the scenario
  // target plans programs too).
  if (program.blocks.size() > 64) return;
  bench::Scenario scenario;
  scenario.program = program;
  scenario.machine.axes = {};  // rigid: the residual window is short
  scenario.limits.max_simulated_s = 5.0;
  scenario.limits.max_ticks = 5000;
  try {
    const double seconds = bench::MinimumRunSeconds(scenario);
    if (seconds > scenario.limits.max_simulated_s ||
        seconds / scenario.controller.period_s > static_cast<double>(scenario.limits.max_ticks)) {
      return;  // the loader refuses these (limits:)
    }
    controller::GenerateProgramCommand(scenario.controller, program);
  } catch (const ValidationError& error) {
    if (error.field().empty()) throw Violation{"a ValidationError without a key: " + std::string(error.what())};
  }
}

// Scenario loader (bench/scenario/scenario_loader.h): any bytes as a scenario file are a Scenario
// or a ConfigError at FILE:LINE:COL; a loaded scenario's command is generated, or refused
// with a ValidationError naming a scenario key.
inline void ScenarioTarget(const std::string& bytes) {
  ConfigsCopy();
  const std::string path = WriteInput("scenarios/input.yaml", bytes);
  bench::Scenario scenario;
  try {
    scenario = bench::LoadScenario(path, SmallLimits());
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
    return;
  }
  try {
    controller::ControllerConfig config = scenario.controller;
    config.stroke_limits = scenario.machine.stroke_m;
    controller::GenerateProgramCommand(config, scenario.RunProgram());
  } catch (const ValidationError& error) {
    if (error.field().empty()) throw Violation{"a ValidationError without a key: " + std::string(error.what())};
  }
}

// Sweep points' structure numbers (bench/scenario/structure_numbers.h), differentially: the
// overrides that are structure numbers, set on the loaded base, must give what the loader
// reads with them, bit for bit (or not be set at all: the loader then decides).
inline void StructureNumbersAgree(const std::string& path, const std::vector<bench::Override>& overrides) {
  std::vector<bench::Override> numbers;
  for (const bench::Override& o : overrides) {
    if (bench::IsStructureNumberKey(o.key_path)) numbers.push_back(o);
  }
  if (numbers.empty()) return;
  bench::Scenario set = bench::LoadScenario(path, SmallLimits());  // a shipped scenario: loads
  if (!bench::SetStructureNumbers(&set, numbers)) return;
  std::vector<bench::Override> with_limits = numbers;
  for (const bench::Override& limit : SmallLimits()) with_limits.push_back(limit);
  bench::Scenario loaded;
  try {
    loaded = bench::LoadScenario(path, with_limits);
  } catch (const bench::ConfigError& error) {
    throw Violation{"structure numbers set where the loader refuses them: " + std::string(error.what())};
  }
  const model::MachinePlant a = model::BuildMachinePlant(set.machine, set.drive);
  const model::MachinePlant b = model::BuildMachinePlant(loaded.machine, loaded.drive);
  if (!(a.plant.A == b.plant.A) || !(a.plant.B_accel == b.plant.B_accel) ||
      !(a.plant.B_vel == b.plant.B_vel) || !(a.plant.C == b.plant.C) || !(a.static_gain == b.static_gain)) {
    throw Violation{"structure numbers set give another plant than the loader reads"};
  }
}

// --set parser (bench/config/override.h, ConfigDocument::ApplyOverride): the first byte picks a
// shipped file, every following line is one --set KEY=VALUE; parsed, applied and loaded
// (a machine file as `modes` reads it); the structure numbers among them, differentially
// (StructureNumbersAgree).
inline void SetTarget(const std::string& bytes) {
  static const char* const kBases[] = {"demo.yaml",
                                       "scenarios/method2.yaml",
                                       "scenarios/pocket_corner.yaml",
                                       "scenarios/pocket_gcode.yaml",
                                       "scenarios/circle_test.yaml",
                                       "scenarios/um_zv.yaml",
                                       "scenarios/stroke_end.yaml",
                                       "machines/moving_column.yaml"};
  if (bytes.empty()) return;
  const std::filesystem::path root = ConfigsCopy();
  const std::string base =
      kBases[static_cast<unsigned char>(bytes[0]) % (sizeof kBases / sizeof kBases[0])];
  std::vector<std::string> texts;
  std::string line;
  for (std::size_t i = 1; i < bytes.size(); ++i) {
    if (bytes[i] == '\n') {
      texts.push_back(line);
      line.clear();
    } else {
      line += bytes[i];
    }
  }
  if (!line.empty()) texts.push_back(line);
  try {
    std::vector<bench::Override> overrides = bench::ParseOverrides(texts);
    const std::string path = (root / base).string();
    if (base.rfind("machines/", 0) == 0) {
      bench::LoadMachineAxes(path, overrides);
    } else {
      StructureNumbersAgree(path, overrides);
      for (const bench::Override& limit : SmallLimits()) overrides.push_back(limit);
      bench::LoadScenario(path, overrides);
    }
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
  }
}

// Sweep loader (bench/sweep/sweep.h): any bytes as a sweep file (in sweeps/, beside copies of
// the shipped scenarios) are a Sweep or a located ConfigError; a loaded sweep's columns,
// hash and first, middle and last points are computed (points are not run).
inline void SweepTarget(const std::string& bytes) {
  ConfigsCopy();
  const std::string path = WriteInput("sweeps/input.yaml", bytes);
  bench::IsSweepFile(path);
  try {
    const bench::Sweep sweep = bench::LoadSweep(path, {});
    if (sweep.points == 0) throw Violation{"a sweep without points"};
    bench::ResultColumns(sweep);
    bench::SweepHash(sweep, {});
    for (const std::uint64_t point : {std::uint64_t{0}, sweep.points / 2, sweep.points - 1}) {
      bench::MakePoint(sweep, point, {}).Label();
    }
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
  }
}

// The readers of a sweep's output directory (bench/sweep/sweep_files.h) refuse what they
// cannot use with a std::runtime_error (exactly that type) naming the file or directory.
// Returns whether `read` refused; anything else it throws goes on (a finding).
template <typename Read>
bool RefusedNaming(const std::vector<std::string>& places, Read&& read) {
  try {
    read();
    return false;
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) {
      throw Violation{std::string("a ") + typeid(error).name() + ": " + error.what()};
    }
    const std::string what = error.what();
    for (const std::string& place : places) {
      if (what.find(place) != std::string::npos) return true;
    }
    throw Violation{"unlocated: " + what};
  }
}

inline std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A sweep of the test data or the shipped configs (read in place: the files are only read).
inline const bench::Sweep& SourceSweep(const std::string& relative) {
  static std::map<std::string, bench::Sweep> sweeps;
  auto found = sweeps.find(relative);
  if (found == sweeps.end()) {
    const std::string path = (std::filesystem::path(SHAPEBENCH_SOURCE_DIR) / relative).string();
    found = sweeps.emplace(relative, bench::LoadSweep(path, {})).first;
  }
  return found->second;
}

// A results row of point p that `merge` and resume keep: the grid's key values, no
// metrics, status error.
inline std::string SynthesizedRow(std::size_t columns, std::uint64_t point,
                                  const std::vector<std::string>& keys) {
  std::vector<std::string> fields = {std::to_string(point)};
  fields.insert(fields.end(), keys.begin(), keys.end());
  while (fields.size() + 2 < columns) fields.emplace_back();
  fields.emplace_back("error");
  fields.emplace_back("no run (fuzz)");
  return CsvRecord(fields);
}

// What `merge` derives from a manifest ReadManifest accepted must hold: the merged
// manifest's text, the grid's key values of every point (rows made from them merge), and
// a plot layout the plotter can draw from merged rows (bench/sweep/sweep_plot.cc,
// ReadSlice: keys and metrics the columns', axes whose sizes multiply to the points, a
// plot's two keys on two axes).
inline void AcceptedManifestHolds(const nlohmann::json& manifest, const std::string& text) {
  bench::DescribeManifest(manifest);
  bench::MergedManifestText(text);
  const auto columns = manifest.at("columns").get<std::vector<std::string>>();
  const std::uint64_t points = manifest.at("points").get<std::uint64_t>();
  if (manifest.contains("layout")) {
    const bench::SweepLayout layout = bench::SweepLayout::FromJson(manifest.at("layout"));
    if (layout.keys.size() + layout.metrics.size() + 3 != columns.size()) {
      throw Violation{"a layout whose keys and metrics are not the columns"};
    }
    std::uint64_t product = 1;
    for (const std::uint64_t size : layout.axis_sizes) {
      if (size == 0 || product > points / size) throw Violation{"a layout with more points than the manifest"};
      product *= size;
    }
    if (product != points) throw Violation{"a layout whose axes are not the manifest's points"};
    const auto axis = [&](const std::string& key) -> std::uint64_t {
      for (std::size_t k = 0; k < layout.keys.size(); ++k) {
        if (layout.keys[k] == key) return layout.key_axis[k];
      }
      throw Violation{"a plot of a key '" + key + "' the layout does not have"};
    };
    for (const bench::SweepPlot& plot : layout.plots) {
      bool metric = false;
      for (const std::string& m : layout.metrics) metric = metric || m == plot.metric;
      if (!metric) throw Violation{"a plot of a metric the layout does not have"};
      const std::uint64_t x = axis(plot.heatmap() ? plot.heatmap_x : plot.x);
      const std::string y = plot.heatmap() ? plot.heatmap_y : plot.series;
      if (!y.empty() && axis(y) == x) throw Violation{"a plot whose two keys move together"};
    }
  }
  bool grid_present = false;
  const bench::GridTexts grid = bench::GridTexts::FromManifest(manifest, &grid_present);
  if (points > 2000) return;  // rows made from the grid: small grids only (the rows target reads rows)
  const std::string rows_path = (ScratchDir() / "manifest_rows/results.csv").string();
  {
    std::ofstream rows(rows_path, std::ios::binary | std::ios::trunc);
    rows << CsvRecord(columns);
    for (std::uint64_t point = 0; point < points; ++point) {
      const std::vector<std::string> keys = grid_present ? grid.Texts(point) : std::vector<std::string>();
      if (keys.size() + 3 > columns.size()) throw Violation{"a grid with more keys than columns"};
      rows << SynthesizedRow(columns.size(), point, keys);
    }
  }
  bench::WriteMergedRows((ScratchDir() / "manifest_rows/merged.csv").string(), {rows_path}, manifest);
}

// manifest.json readers (bench/sweep/sweep_files.h): any bytes as the manifest.json of a
// directory are accepted or refused with a std::runtime_error naming it, by the reader
// itself, by resume's check of its --out (against the test data's map.yaml sweep) and by
// merge's check of its output directory; an accepted manifest gives merge what it needs
// (AcceptedManifestHolds).
inline void ManifestTarget(const std::string& bytes) {
  static const nlohmann::ordered_json expected = [] {
    std::filesystem::create_directories(ScratchDir() / "manifest");
    std::filesystem::create_directories(ScratchDir() / "manifest_rows");
    return bench::ManifestJson(SourceSweep("tests/bench/data/sweeps/map.yaml"), {}, 0, 1);
  }();
  const std::string dir = (ScratchDir() / "manifest").string();
  const std::string path = WriteInput("manifest/manifest.json", bytes);
  RefusedNaming({dir}, [&] { bench::CheckResumeDirectory(dir, expected); });
  static const nlohmann::json expected_json = nlohmann::json::parse(expected.dump());
  RefusedNaming({dir}, [&] { bench::CheckMergeOutput(dir, expected_json); });
  nlohmann::json manifest;
  std::string text;
  if (RefusedNaming({path}, [&] { manifest = bench::ReadManifest(path, &text); })) return;
  if (text != bytes) throw Violation{"ReadManifest's text is not the file's"};
  const std::uint64_t count = manifest.at("shard").at("count").get<std::uint64_t>();
  if (count < 1 || manifest.at("shard").at("index").get<std::uint64_t>() >= count) {
    throw Violation{"an accepted manifest with a shard outside 0..count-1"};
  }
  AcceptedManifestHolds(manifest, text);
}

// One sweep and shard whose results rows fuzz_rows reads.
struct RowsCase {
  const char* sweep;
  std::uint64_t index;
  std::uint64_t count;
};
inline constexpr RowsCase kRowsCases[] = {
    {"tests/bench/data/sweeps/map.yaml", 0, 1},          {"tests/bench/data/sweeps/map.yaml", 1, 3},
    {"tests/bench/data/sweeps/quoting.yaml", 0, 1},      {"tests/bench/data/sweeps/failing_point.yaml", 0, 1},
    {"tests/bench/data/sweeps/natural_period.yaml", 1, 2}, {"configs/sweeps/natural_period.yaml", 2, 4},
    {"configs/sweeps/frequency_accel_map.yaml", 0, 8}};

// A RowsCase set up once: its columns, grid and manifest (written, then read back as
// merge reads it) and the other shards' results files (rows made from the grid).
struct RowsSetup {
  std::vector<std::string> columns;
  bench::ShardPoints shard;
  bench::GridTexts grid;
  nlohmann::json manifest;
  std::vector<std::string> shard_paths;  // shard i's results file; the fuzzed one at `index`
  std::string dir;
};

inline const RowsSetup& RowsSetupOf(std::size_t which) {
  static std::map<std::size_t, RowsSetup> setups;
  auto found = setups.find(which);
  if (found != setups.end()) return found->second;
  const RowsCase& c = kRowsCases[which];
  const bench::Sweep& sweep = SourceSweep(c.sweep);
  RowsSetup setup;
  setup.dir = (ScratchDir() / ("rows" + std::to_string(which))).string();
  for (const char* sub : {"", "/done", "/partial"}) std::filesystem::create_directories(setup.dir + sub);
  setup.columns = bench::ResultColumns(sweep);
  setup.shard = bench::ShardPoints{sweep.points, c.index, c.count};
  setup.grid = bench::GridTexts::Of(sweep);
  const std::string manifest_path = setup.dir + "/manifest.json";
  std::ofstream(manifest_path, std::ios::binary) << bench::ManifestJson(sweep, {}, c.index, c.count).dump(2) << "\n";
  setup.manifest = bench::ReadManifest(manifest_path);
  for (std::uint64_t i = 0; i < c.count; ++i) {
    setup.shard_paths.push_back(setup.dir + "/shard" + std::to_string(i) + ".csv");
    if (i == c.index) continue;
    std::ofstream rows(setup.shard_paths.back(), std::ios::binary);
    rows << CsvRecord(setup.columns);
    for (std::uint64_t point = i; point < sweep.points; point += c.count) {
      rows << SynthesizedRow(setup.columns.size(), point, setup.grid.Texts(point));
    }
  }
  return setups.emplace(which, std::move(setup)).first->second;
}

// Results rows readers (bench/sweep/sweep_files.h): the first byte picks a sweep and
// shard (kRowsCases), the rest is that shard's results file. A sweep started again
// finds it as results.csv (all the shard's rows, or refused naming the file) and as
// results.csv.partial (its good rows kept, the rest cut off: a prefix of the file, kept
// again unchanged); merge joins it with the other shards (or refuses naming the file)
// exactly when resume takes it as finished, and what it merges is a whole results.csv.
inline void RowsTarget(const std::string& bytes) {
  if (bytes.empty()) return;
  const std::size_t which = static_cast<unsigned char>(bytes[0]) % (sizeof kRowsCases / sizeof kRowsCases[0]);
  const RowsSetup& setup = RowsSetupOf(which);
  const std::string rows = bytes.substr(1);
  namespace fs = std::filesystem;
  std::error_code ec;

  const std::string done_dir = setup.dir + "/done";
  fs::remove(done_dir + "/results.csv.partial", ec);
  WriteBytes(done_dir + "/results.csv", rows);
  bench::ResumedRows done;
  const bool done_refused =
      RefusedNaming({done_dir + "/results.csv"}, [&] { done = bench::KeepResumableRows(done_dir, setup.columns, setup.shard, setup.grid); });
  if (!done_refused && (!done.finished || done.rows != setup.shard.Size() || done.errors > done.rows)) {
    throw Violation{"a finished results.csv taken without all its rows"};
  }

  const std::string partial_dir = setup.dir + "/partial";
  const std::string partial = partial_dir + "/results.csv.partial";
  fs::remove(partial_dir + "/results.csv", ec);
  WriteBytes(partial, rows);
  const bench::ResumedRows kept = bench::KeepResumableRows(partial_dir, setup.columns, setup.shard, setup.grid);
  const std::string after = FileBytes(partial);
  if (kept.finished || kept.rows > setup.shard.Size() || kept.errors > kept.rows) {
    throw Violation{"results.csv.partial kept as more than the shard's rows"};
  }
  if (after != CsvRecord(setup.columns) && after != rows.substr(0, after.size())) {
    throw Violation{"results.csv.partial cut to something that is not its beginning"};
  }
  if (!done_refused && kept.rows != done.rows) throw Violation{"resume keeps fewer rows of a partial file"};
  const bench::ResumedRows again = bench::KeepResumableRows(partial_dir, setup.columns, setup.shard, setup.grid);
  if (again.rows != kept.rows || again.errors != kept.errors || FileBytes(partial) != after) {
    throw Violation{"results.csv.partial kept again is not kept as it was"};
  }

  const std::string fuzzed = setup.shard_paths[setup.shard.index];
  WriteBytes(fuzzed, rows);
  const std::string merged = setup.dir + "/merged.csv";
  const bool merge_refused =
      RefusedNaming({fuzzed}, [&] { bench::WriteMergedRows(merged, setup.shard_paths, setup.manifest); });
  if (merge_refused != done_refused) {
    throw Violation{merge_refused ? "merge refuses rows a finished sweep keeps"
                                  : "merge takes rows a finished sweep refuses"};
  }
  if (merge_refused) return;
  const bench::RowScan scan = bench::ScanRows(merged, setup.columns, bench::ShardPoints{setup.shard.total, 0, 1}, setup.grid);
  if (scan.rows != setup.shard.total || scan.good_bytes != fs::file_size(merged)) {
    throw Violation{"merge wrote a results.csv a sweep would not keep"};
  }
}

// UFF dataset 58 reader (bench/measured/uff58_reader.h): any bytes are FRF records or a
// ConfigError at a line of the file; the records read list their non-finite values, are ascending in frequency,
// as long as their values; a short one goes through the identification (low orders), which
// returns modes inside the band or refuses the band with a ValidationError naming it.
inline void Uff58Target(const std::string& bytes) {
  bench::Uff58File file;
  try {
    file = bench::ParseUff58(bytes, "input.uff");
  } catch (const bench::ConfigError& error) {
    if (error.file() != "input.uff" || error.line() < 1) throw Violation{"unlocated: " + std::string(error.what())};
    return;
  }
  if (file.records.empty()) throw Violation{"a file read without records"};
  for (const bench::Uff58Record& record : file.records) {
    if (record.values.size() != record.frequency_hz.size() || record.values.empty()) {
      throw Violation{"values and frequencies differ in length"};
    }
    std::size_t listed = 0;  // the non-finite values are exactly the points listed
    for (std::size_t i = 0; i < record.values.size(); ++i) {
      const bool finite = std::isfinite(record.values[i].real()) && std::isfinite(record.values[i].imag());
      if (!finite && !(listed < record.non_finite.size() && record.non_finite[listed].point == i)) {
        throw Violation{"a record read with a non-finite value it does not list"};
      }
      if (!finite) ++listed;
      if (!std::isfinite(record.frequency_hz[i]) || (i > 0 && !(record.frequency_hz[i] > record.frequency_hz[i - 1]))) {
        throw Violation{"a record read with a non-finite or not ascending frequency"};
      }
    }
    if (listed != record.non_finite.size()) throw Violation{"a finite value listed as not finite"};
  }
  const bench::Uff58Record& first = file.records.front();
  if (first.values.size() > 512 || !first.non_finite.empty()) return;
  model::IdentificationOptions options;
  options.max_order = 4;
  try {
    const model::ModalIdentification id =
        model::IdentifyModes(first.frequency_hz, {first.values}, first.DerivativeOrder(), options);
    for (const model::IdentifiedMode& mode : id.modes) {
      if (!(mode.frequency_hz >= id.frequency_hz.front() && mode.frequency_hz <= id.frequency_hz.back()) ||
          !(mode.damping_ratio > 0.0 && mode.damping_ratio < 0.5)) {
        throw Violation{"a mode outside the band or not physical"};
      }
    }
  } catch (const ValidationError& error) {
    if (error.field().empty()) throw Violation{"a ValidationError without a key: " + std::string(error.what())};
  }
}

// Accelerometer log reader (bench/measured/accel_log.h) and what `recommend` does with a
// log it takes: any bytes are a log or a ConfigError at FILE:LINE:COL naming the column;
// a log has finite, strictly increasing times and finite values; its spectrum is finite
// and non-negative or refused at a line; every method fitted (on a coarse 5 Hz scan, to
// keep each input quick) leaves a finite, non-negative vibration, the recommendation is
// one of them, and the log's modes lie in the band with shares summing to 1.
inline void AccelLogTarget(const std::string& bytes) {
  auto located = [](const bench::ConfigError& error) {
    if (error.file() != "input.csv" || error.line() < 1 || error.column() < 1 || error.key_path().empty()) {
      throw Violation{"unlocated: " + std::string(error.what())};
    }
  };
  bench::AccelLog log;
  try {
    log = bench::ParseAccelLog(bytes, "input.csv");
  } catch (const bench::ConfigError& error) {
    located(error);
    return;
  }
  const std::size_t n = log.time_s.size();
  if (n == 0 || log.line.size() != n) throw Violation{"a log without samples or lines"};
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(log.time_s[i]) || (i > 0 && !(log.time_s[i] > log.time_s[i - 1]))) {
      throw Violation{"a log whose times are not finite and increasing"};
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (log.accel_mm_s2[axis].size() != n || !std::isfinite(log.accel_mm_s2[axis][i])) {
        throw Violation{"a log with a non-finite or missing acceleration"};
      }
    }
  }
  bench::AccelSpectrum spectrum;
  try {
    spectrum = bench::ComputeAccelSpectrum(log, bench::AccelAxis::kAll);
  } catch (const bench::ConfigError& error) {
    located(error);
    return;
  }
  if (spectrum.psd.empty() || spectrum.psd.size() != spectrum.frequency_hz.size()) throw Violation{"an empty fit band"};
  for (const double p : spectrum.psd) {
    if (!std::isfinite(p) || p < 0.0) throw Violation{"a PSD value not finite and non-negative"};
  }
  bench::ShaperFitOptions options;
  options.step_hz = 5.0;
  const bench::ShaperRecommendation r = bench::RecommendShapers(spectrum.frequency_hz, spectrum.psd, options);
  if (r.recommended >= r.fits.size()) throw Violation{"a recommendation that is not one of the fits"};
  for (const bench::ShaperFit& fit : r.fits) {
    if (!std::isfinite(fit.remaining_vibration) || fit.remaining_vibration < 0.0 || !std::isfinite(fit.smoothing_m) ||
        !std::isfinite(fit.added_time_s)) {
      throw Violation{"a fit of " + fit.method + " with a non-finite or negative number"};
    }
  }
  double shares = 0.0;
  for (const bench::LogMode& mode : bench::PickPsdPeaks(spectrum.frequency_hz, spectrum.psd)) {
    if (!(mode.frequency_hz >= bench::kFitMinHz - 2.0 && mode.frequency_hz <= bench::kFitMaxHz + 2.0) ||
        !(mode.damping_ratio > 0.0 && mode.damping_ratio < 1.0)) {
      throw Violation{"a mode outside the band or with a damping ratio outside (0, 1)"};
    }
    shares += mode.share;
  }
  if (std::abs(shares - 1.0) > 1e-9) throw Violation{"mode shares that do not sum to 1"};
}

// FE modal export reader (bench/measured/modal_file_reader.h): any bytes are coupled modes
// or a ConfigError at the file, a line and a column >= 1, naming a column or row; accepted
// modes number 1 to kMaxModelEntries, each with participation and shape, and pass the
// modal form's validate() (finite numbers, frequency > 0, damping in [0, 1)).
inline void ModalFileTarget(const std::string& text) {
  const std::string file = "fuzz.csv";
  std::vector<model::ModalMode> modes;
  try {
    modes = bench::ParseModalFile(text, file);
  } catch (const bench::ConfigError& error) {
    if (error.file() != file || error.line() < 1 || error.column() < 1 || error.key_path().empty()) {
      throw Violation{"unlocated: " + std::string(error.what())};
    }
    return;
  }
  if (modes.empty() || modes.size() > model::kMaxModelEntries) {
    throw Violation{"accepted " + std::to_string(modes.size()) + " modes"};
  }
  model::ModalMachineConfig config;
  config.modes = modes;
  for (const model::ModalMode& mode : modes) {
    if (!mode.participation || !mode.shape) throw Violation{"an accepted mode without participation or shape"};
  }
  try {
    config.validate();
  } catch (const ValidationError& error) {
    throw Violation{"accepted modes fail validate(): " + std::string(error.what())};
  }
}

}  // namespace shapebench::fuzz
