#include "bench/sweep/sweep.h"

#include "common/field_list.h"

#include <algorithm>
#include <charconv>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>
#include <memory>
#include <set>
#include <stdexcept>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "bench/config/config_document.h"
#include "bench/run/run_scenario.h"
#include "common/csv.h"
#include "common/ends_with.h"
#include "bench/config/key_path.h"
#include "bench/run/located_run.h"
#include "bench/config/node_reader.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/structure_numbers.h"
#include "bench/sweep/shared_command.h"
#include "bench/sweep/sweep_grid_reader.h"
#include "bench/sweep/sweep_metrics_reader.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kSweepKeys = {"name",   "base",    "grid", "metrics", "plots",
                                             "checks", "samples", "seed", "design", "band_threshold"};

std::string WithThousands(std::uint64_t n) {
  std::string digits = std::to_string(n);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(at, ",");
  return digits;
}

// Point 0 against the base: a swept key must fit the scenario's tree and be a scenario
// key. Values are the points' business (a bad one is that point's error row).
void CheckGridAgainstBase(const Sweep& sweep, const std::vector<Override>& sets) {
  const SweepPoint point = MakePoint(sweep, 0, sets);
  try {
    BuildScenarioTree(sweep.base, point.overrides);
  } catch (const ConfigError& error) {
    if (IsGridOverrideError(point, error)) {
      const ConfigError located = RelocatePointError(sweep, point, error);
      throw ConfigError(located.file(), located.line(), located.column(), error.key_path(),
                        error.message() + " (in the base scenario " + sweep.base + ")");
    }
    throw;
  }
  try {
    LoadOptions options;
    options.design_modes = sweep.design_modes;
    LoadScenario(sweep.base, point.overrides, options);
  } catch (const ConfigError& error) {
    const std::string unknown = "unknown key";
    if (IsGridOverrideError(point, error) &&
        error.message().compare(0, unknown.size(), unknown) == 0 &&
        error.key_path() == point.overrides[error.line() - 1].key_path) {
      throw RelocatePointError(sweep, point, error);
    }
  }
}

// The note of a sweep whose pattern is left to the machine while grid keys change the
// machine: the points keep the base's design (Sweep::design_modes); empty otherwise.
std::string MachineDefaultsNote(const Sweep& sweep, const Scenario& base) {
  const controller::PatternConfig& pattern = base.controller.pattern;
  std::string keys;
  bool pattern_swept = false;
  for (const std::string& key : sweep.Keys()) {
    if (IsPathPrefix("machine", key)) keys += (keys.empty() ? "" : ", ") + key;
    pattern_swept = pattern_swept || IsPathPrefix("controller.pattern", key) || IsPathPrefix(key, "controller.pattern");
  }
  const bool defaulted = pattern.frequency_from_machine || pattern.frequencies_from_machine || pattern.damping_from_machine;
  const bool shapes = controller::FindShaper(pattern.method).kind != controller::ShaperKind::kNone;
  if (keys.empty() || !defaulted || !(shapes || pattern_swept) || !sweep.design_modes ||
      sweep.design_modes->modes.empty()) {
    return "";
  }
  std::string design;
  for (const double f : pattern.DesignFrequencies()) design += (design.empty() ? "" : ", ") + ShortestDouble(f);
  return "note: " + sweep.file + ": the pattern's design is left to the machine; every point takes the "
         "base scenario's (" + design + " Hz, from its participating modes along " + sweep.design_modes->axes +
         "), not its own: the swept keys " + keys + " move the plant, not the pattern "
         "(give controller.pattern.frequency_hz to choose it)";
}

void CheckSetsAvoidGrid(const Sweep& sweep, const std::vector<Override>& sets) {
  for (std::size_t i = 0; i < sets.size(); ++i) {
    for (const auto& axis : sweep.axes) {
      for (const auto& values : axis.keys) {
        if (IsPathPrefix(values.key, sets[i].key_path) ||
            IsPathPrefix(sets[i].key_path, values.key)) {
          throw ConfigError(kOverrideSource, static_cast<int>(i) + 1, 1, sets[i].key_path,
                            "'" + values.key + "' is swept by the grid (" + sweep.file + ":" +
                                std::to_string(values.line) +
                                "); change the grid, not the swept key");
        }
      }
    }
  }
}

std::string ResolveBase(const NodeReader& base, const std::string& sweep_path) {
  const std::string reference = base.AsString();
  const fs::path resolved = fs::path(reference).is_absolute()
                                ? fs::path(reference)
                                : fs::path(sweep_path).parent_path() / reference;
  const std::string file = resolved.lexically_normal().string();
  try {
    const YAML::Node root = ConfigDocument::ParseFile(file);
    if (root.IsMap() && root["base"] && root["grid"]) {
      throw base.Error("'" + reference + "' is a sweep; base: names a scenario");
    }
  } catch (const ConfigError& error) {
    if (error.line() > 0 || error.file() != file) throw;
    const std::string shown = file == reference ? "'" + reference + "'" : "'" + reference + "' (" + file + ")";
    throw base.Error("base scenario " + shown + ": " + error.message());
  }
  return file;
}

void HashText(std::uint64_t* hash, const std::string& text) {
  for (const unsigned char c : text) {
    *hash ^= c;
    *hash *= 0x100000001b3ULL;
  }
  *hash ^= 0xff;  // a separator no text contains
  *hash *= 0x100000001b3ULL;
}

// A file the hash covers (the G-code program): unreadable is an error, never an empty hash input.
std::string FileBytes(const std::string& path) {
  std::string text;
  std::string error;
  if (!ReadInputFile(path, &text, &error)) throw ConfigError(path, 0, 0, "", error);
  return text;
}


}  // namespace

bool IsSweepFile(const std::string& path) {
  try {
    const YAML::Node root = ConfigDocument::ParseFile(path);
    return root.IsMap() && root["base"].IsDefined() && root["grid"].IsDefined();
  } catch (const std::exception&) {
    return false;
  }
}

std::string SweepPath(const std::string& path) {
  // The path from the working directory (absolute when the file is outside it), its
  // directory's symbolic links, "." and ".." resolved as the kernel resolves them. The
  // file name itself is kept (a link to a sweep names that link). Anything that cannot be
  // resolved (a missing directory) is left as given, for the reader to report.
  std::error_code ec;
  const fs::path given(path);
  const fs::path name = given.filename();
  if (name.empty() || name == "." || name == "..") return path;
  const fs::path dir = fs::canonical(fs::absolute(given, ec).parent_path(), ec);
  if (ec) return path;
  const fs::path cwd = fs::canonical(fs::current_path(ec), ec);
  if (ec) return (dir / name).string();
  const fs::path relative = dir.lexically_relative(cwd);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  if (!inside) return (dir / name).string();
  return relative == "." ? name.string() : (relative / name).string();
}

Sweep LoadSweep(const std::string& given_path, const std::vector<Override>& sets,
                const SweepLoadOptions& options) {
  // The sweep's identity in what it writes (results.csv's error locations, manifest.json,
  // the base's path) is its file, not the spelling on the command line: shards run as
  // configs/s.yaml, ./configs/../configs/s.yaml and /abs/configs/s.yaml merge into the
  // unsharded bytes. A canonical path (not a content hash) so that messages still point
  // at the file; relative to the working directory so that shards run from the same
  // checkout on different machines agree too (docs/sweeps.md, shards and merge).
  const std::string path = SweepPath(given_path);
  const ConfigDocument document(ConfigDocument::ParseFile(path), path);
  const NodeReader top(document, document.root(), "");
  if (!top.IsMap()) throw top.Error("expected a mapping of sweep keys (" + JoinNames(kSweepKeys, ", ") + ")");
  top.ExpectMap(kSweepKeys);
  for (const char* required : {"base", "grid"}) {
    if (!top.Has(required)) {
      throw top.Error(std::string("a sweep needs base: (a scenario) and grid: (keys and their "
                                  "values); '") + required + "' is missing");
    }
  }
  Sweep sweep;
  sweep.file = path;
  sweep.name = fs::path(path).stem().string();
  top.Read("name", &sweep.name);
  const NodeReader base = *top.Child("base");
  sweep.base = ResolveBase(base, path);
  const NodeReader grid = *top.Child("grid");
  if (!grid.IsMap()) {
    throw grid.Error("expected a mapping of key paths to lists or ranges, e.g. "
                     "machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 201}");
  }
  sweep.axes = ReadGrid(document, grid);
  DrawSamples(&sweep, top, options);
  for (SweepAxis& axis : sweep.axes) {
    for (SweepValues& values : axis.keys) values.KeepTexts();
  }
  sweep.points = CountPoints(sweep.axes, grid);
  if (sweep.points > options.max_points && !options.force) {
    throw grid.Error("the grid has " + WithThousands(sweep.points) + " points, more than the " +
                     WithThousands(options.max_points) +
                     " a sweep runs without --force; pass --force to run it anyway");
  }
  const auto metrics = top.Child("metrics");
  sweep.metrics = metrics ? ReadMetrics(*metrics) : MetricNames();
  if (const auto plots = top.Child("plots")) {
    sweep.plots = ReadPlots(*plots, sweep.metrics, sweep.axes);
  } else {
    sweep.plots = DefaultPlots(sweep.metrics, metrics.has_value(), sweep.axes);
    if (sweep.sampling) sweep.plots = DefaultCdfPlots(sweep.plots, sweep.axes, sweep.sample_axis);
  }
  if (const auto checks = top.Child("checks")) ReadSweepChecks(*checks, &sweep);
  if (const auto level = top.Child("band_threshold")) {
    double value = 0.0;
    top.Read("band_threshold", &value);
    if (!(value > 0.0)) throw level->Error("expected a number > 0 (the level of the robust bands, e.g. 0.05)");
    sweep.band_threshold = value;
  }
  SetCdfLimits(&sweep);

  static std::atomic<std::uint64_t> next_id{1};
  sweep.id = next_id++;
  CheckSetsAvoidGrid(sweep, sets);
  const auto base_scenario = std::make_shared<const Scenario>(LoadScenario(sweep.base, sets));  // must be valid
  sweep.design_modes = FindDesignModes(base_scenario->machine, base_scenario->RunProgram());
  sweep.note = MachineDefaultsNote(sweep, *base_scenario);
  sweep.base_scenario = base_scenario;
  sweep.base_hash = BaseScenarioHash(sweep);  // the files as this load read them
  sweep.base_sets_key = OverridesKey(sets.begin(), sets.end());
  CheckGridAgainstBase(sweep, sets);
  return sweep;
}

std::uint64_t BaseScenarioHash(const Sweep& sweep) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  HashText(&hash, "shapebench sweep 1");
  const YAML::Node base = BuildScenarioTree(sweep.base, {});
  HashText(&hash, YAML::Dump(base));
  if (base.IsMap() && base["program_file"] && base["program_file"].IsScalar()) {
    const fs::path program = fs::path(sweep.base).parent_path() / base["program_file"].Scalar();
    HashText(&hash, FileBytes(program.string()));
  }
  return hash;
}

std::string SweepHash(const Sweep& sweep, const std::vector<Override>& sets) {
  std::uint64_t hash = sweep.base_hash != 0 ? sweep.base_hash : BaseScenarioHash(sweep);
  for (const Override& set : sets) HashText(&hash, set.key_path + "=" + set.value_yaml);
  HashText(&hash, "grid");
  for (const auto& axis : sweep.axes) {
    HashText(&hash, "axis");
    for (const auto& values : axis.keys) {
      HashText(&hash, values.key);
      // A sampled key's values follow from the sampling hashed below: not listed one by
      // one (a sweep of 20,000,000 samples would wait for them before its first point).
      if (values.kind == SweepValues::Kind::kSampled) continue;
      if (values.kept_texts != nullptr) {  // Yaml(i) is Text(i): read without a copy each
        for (const std::string& text : *values.kept_texts) HashText(&hash, text);
        continue;
      }
      for (std::uint64_t i = 0; i < values.size(); ++i) HashText(&hash, values.Yaml(i));
    }
  }
  if (sweep.sampling) {
    // The sampling spec, which makes its values: the same spec, the same values (a resume
    // still checks each kept row's values against the grid).
    HashText(&hash, "sampling");
    HashText(&hash, std::string(DesignName(sweep.sampling->design)) + " seed " +
                        std::to_string(sweep.sampling->seed) + " samples " + std::to_string(sweep.sampling->samples));
    for (const auto& values : sweep.axes[sweep.sample_axis].keys) HashText(&hash, values.distribution->Describe());
  }
  HashText(&hash, "metrics");
  for (const auto& metric : sweep.metrics) HashText(&hash, metric);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string KeyUnit(const std::string& key) {
  static const std::vector<std::pair<std::string, std::string>> kUnits = {
      {"_mm_min", "mm/min"}, {"_m_s2", "m/s²"}, {"_m_s", "m/s"}, {"_hz", "Hz"},
      {"_mm", "mm"},         {"_kg", "kg"},     {"_1_s", "1/s"}, {"_s", "s"},
      {"_m", "m"}};
  for (const auto& [suffix, unit] : kUnits) {
    if (EndsWith(key, suffix)) return unit;
  }
  return "";
}

}  // namespace shapebench::bench
