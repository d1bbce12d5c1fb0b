#include "bench/sweep/sweep_grid_reader.h"

#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "bench/config/input_path.h"
#include "bench/config/key_path.h"

namespace shapebench::bench {
namespace {

constexpr const char* kZip = "zip";

std::pair<int, int> PositionOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return {1, 1};
  return {mark.line + 1, mark.column + 1};
}

// A value in flow style ({gain: 2}, [1, 2]); a quoted scalar stays quoted.
std::string FlowYaml(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter.SetMapFormat(YAML::Flow);
  emitter.SetSeqFormat(YAML::Flow);
  if (node.IsScalar() && node.Tag() == "!") {
    emitter << YAML::DoubleQuoted << node.Scalar();
  } else {
    emitter << node;
  }
  return emitter.c_str();
}

SweepValues ReadRange(const NodeReader& node, const std::string& key) {
  node.ExpectMap({"from", "to", "steps", "spacing"});
  SweepValues values;
  values.key = key;
  values.kind = SweepValues::Kind::kLinear;
  for (const char* required : {"from", "to", "steps"}) {
    if (!node.Has(required)) {
      throw node.Error(std::string("a range needs from, to and steps; '") + required +
                       "' is missing (e.g. {from: 15, to: 35, steps: 201})");
    }
  }
  values.from = node.Child("from")->AsNumber();
  values.to = node.Child("to")->AsNumber();
  const NodeReader steps = *node.Child("steps");
  const long count = steps.AsInteger();
  if (count < 1) throw steps.Error("must be at least 1, got " + std::to_string(count));
  values.steps = static_cast<std::uint64_t>(count);
  if (values.steps == 1 && values.from != values.to) {
    throw steps.Error("steps 1 gives `from` only; make from and to equal, or steps >= 2");
  }
  node.Read<SweepValues::Kind>(
      "spacing", {{"linear", SweepValues::Kind::kLinear}, {"log", SweepValues::Kind::kLog}},
      &values.kind);
  if (values.log()) {
    for (const char* end : {"from", "to"}) {
      const NodeReader child = *node.Child(end);
      if (!(child.AsNumber() > 0.0)) {
        throw child.Error("log spacing needs from > 0 and to > 0, got " + child.node().Scalar());
      }
    }
  }
  return values;
}

// A list [a, b, ...] or a range {from, to, steps[, spacing]} for `key`.
SweepValues ReadValues(const NodeReader& node, const std::string& key) {
  SweepValues values;
  if (IsDistributionNode(node)) {
    values.key = key;
    values.kind = SweepValues::Kind::kSampled;
    values.distribution = ReadDistribution(node);
  } else if (node.node().IsMap()) {
    values = ReadRange(node, key);
  } else if (node.node().IsSequence()) {
    values.key = key;
    values.kind = SweepValues::Kind::kList;
    for (const NodeReader& element : node.Elements()) {
      const YAML::Node& value = element.node();
      const bool plain = value.IsScalar() && value.Tag() != "!";
      values.texts.push_back(value.IsScalar() ? value.Scalar() : FlowYaml(value));
      // A path written in the sweep file is relative to its folder; the override that sets
      // it reads from the current directory (bench/config/input_path.h).
      const bool path = plain && IsPathKey(key) && !value.Scalar().empty();
      values.yamls.push_back(path ? ResolvedFrom(element.document().FileOf(element.path()), value.Scalar())
                                  : plain ? value.Scalar() : FlowYaml(value));
      values.positions.push_back(PositionOf(value));
    }
    if (values.texts.empty()) throw node.Error("expected at least one value");
  } else {
    throw node.Error(
        "expected a list of values [a, b, ...] or a range {from: A, to: B, steps: N}, or a distribution "
        "{normal: {mean: M, sd: S}} (uniform: {from, to}, lognormal: {median, sigma}; truncated: {min, max})");
  }
  std::tie(values.line, values.column) = PositionOf(node.node());
  return values;
}

// The (key node, value) entries of a mapping, in order; duplicate keys are errors.
std::vector<std::pair<YAML::Node, NodeReader>> MapEntries(const ConfigDocument& document,
                                                          const NodeReader& map) {
  if (!map.IsMap()) throw map.Error("expected a mapping");
  std::vector<std::pair<YAML::Node, NodeReader>> entries;
  std::set<std::string> seen;
  for (const auto& entry : map.node()) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
    const std::string path = ChildPath(map.path(), key);
    if (!entry.first.IsScalar()) {
      throw document.ErrorAt(entry.first, map.path(), "expected a plain key, got a complex key");
    }
    if (!seen.insert(key).second) throw document.ErrorAt(entry.first, path, "duplicate key '" + key + "'");
    entries.emplace_back(entry.first, NodeReader(document, entry.second, path));
  }
  return entries;
}

SweepValues ReadKeyValues(const ConfigDocument& document, const YAML::Node& key_node,
                          const NodeReader& value) {
  const std::string key = key_node.Scalar();
  if (!ParseKeyPath(key)) {
    throw document.ErrorAt(key_node, value.path(),
                           "not a key path; expected scenario keys joined by '.' with optional "
                           "[INDEX], e.g. machine.modes[0].frequency_hz");
  }
  return ReadValues(value, key);
}

SweepAxis ReadZipGroup(const ConfigDocument& document, const NodeReader& group) {
  SweepAxis axis;
  for (const auto& [key_node, value] : MapEntries(document, group)) {
    axis.keys.push_back(ReadKeyValues(document, key_node, value));
    if (axis.keys.back().kind == SweepValues::Kind::kSampled) {
      throw value.Error("a distribution cannot be in a zip group: every distribution key of the grid "
                        "already moves with the one axis of samples");
    }
    if (axis.keys.back().size() != axis.keys.front().size()) {
      throw value.Error("zip keys move together and need as many values each: '" +
                        axis.keys.front().key + "' has " +
                        std::to_string(axis.keys.front().size()) + ", this one " +
                        std::to_string(axis.keys.back().size()));
    }
  }
  if (axis.keys.empty()) throw group.Error("expected at least one key in a zip group");
  return axis;
}

}  // namespace

std::vector<SweepAxis> ReadGrid(const ConfigDocument& document, const NodeReader& grid) {
  std::vector<SweepAxis> axes;
  for (const auto& [key_node, value] : MapEntries(document, grid)) {
    if (key_node.Scalar() != kZip) {
      axes.push_back(SweepAxis{{ReadKeyValues(document, key_node, value)}});
      continue;
    }
    if (value.node().IsSequence()) {
      for (const NodeReader& group : value.Elements()) axes.push_back(ReadZipGroup(document, group));
      if (value.node().size() == 0) throw value.Error("expected at least one zip group");
    } else if (value.IsMap()) {
      axes.push_back(ReadZipGroup(document, value));
    } else {
      throw value.Error("expected a mapping of keys to lists or ranges of equal length (or a "
                        "list of such mappings)");
    }
  }
  if (axes.empty()) {
    throw grid.Error("expected at least one key, e.g. machine.modes[0].frequency_hz: "
                     "{from: 15, to: 35, steps: 201}");
  }
  // The distribution keys become one axis (of samples) at the place of the first.
  std::vector<SweepAxis> merged;
  std::size_t sample_axis = axes.size();
  for (SweepAxis& axis : axes) {
    if (axis.keys.front().kind != SweepValues::Kind::kSampled) {
      merged.push_back(std::move(axis));
    } else if (sample_axis == axes.size()) {
      sample_axis = merged.size();
      merged.push_back(std::move(axis));
    } else {
      merged[sample_axis].keys.push_back(std::move(axis.keys.front()));
    }
  }
  axes = std::move(merged);
  // A key and a key inside it would overwrite each other.
  std::vector<const SweepValues*> all;
  for (const auto& axis : axes) {
    for (const auto& values : axis.keys) all.push_back(&values);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (IsPathPrefix(all[j]->key, all[i]->key) || IsPathPrefix(all[i]->key, all[j]->key)) {
        throw ConfigError(document.OriginOf("").file, all[i]->line, all[i]->column,
                          ChildPath("grid", all[i]->key),
                          all[i]->key == all[j]->key
                              ? "swept twice (also at line " + std::to_string(all[j]->line) + ")"
                              : "overlaps '" + all[j]->key + "' (line " +
                                    std::to_string(all[j]->line) +
                                    "): a key and a key inside it cannot both be swept");
      }
    }
  }
  return axes;
}

void DrawSamples(Sweep* sweep, const NodeReader& top, const SweepLoadOptions& options) {
  sweep->sampling = ReadSampling(top);
  std::vector<SweepValues*> sampled;
  for (std::size_t a = 0; a < sweep->axes.size(); ++a) {
    for (SweepValues& values : sweep->axes[a].keys) {
      if (values.kind != SweepValues::Kind::kSampled) continue;
      sampled.push_back(&values);
      sweep->sample_axis = a;
    }
  }
  if (sampled.empty()) {
    if (sweep->sampling) {
      throw top.Child("samples")->Error("samples: needs a distribution key in grid:, e.g. "
                                        "machine.modes[0].frequency_hz: {normal: {mean: 25, sd: 0.625}}");
    }
    return;
  }
  if (!sweep->sampling) {
    const SweepValues& first = *sampled.front();
    throw ConfigError(sweep->file, first.line, first.column, ChildPath("grid", first.key),
                      "a distribution needs samples: N at the top of the sweep (and optionally seed: S, "
                      "design: random|latin_hypercube|sobol)");
  }
  // The grid's size before anything runs: a grid larger than asked for is a slip.
  std::uint64_t others = 1;
  for (std::size_t a = 0; a < sweep->axes.size(); ++a) {
    if (a == sweep->sample_axis) continue;
    const std::uint64_t size = sweep->axes[a].size();
    others = others > std::numeric_limits<std::uint64_t>::max() / size ? std::numeric_limits<std::uint64_t>::max()
                                                                         : others * size;
  }
  const std::uint64_t n = sweep->sampling->samples;
  if (!options.force && (n > options.max_points || others > options.max_points / n)) {
    throw top.Child("samples")->Error("the grid has " + std::to_string(n) + " samples" +
                                      (others > 1 ? " times " + std::to_string(others) + " points" : "") +
                                      ", more than the " + std::to_string(options.max_points) +
                                      " points a sweep runs without --force; pass --force to run it anyway");
  }
  try {
    CheckSampleDesign(*sweep->sampling, sampled.size());
  } catch (const std::invalid_argument& error) {
    const auto design = top.Child("design");
    throw (design ? *design : *top.Child("samples")).Error(
        error.what() + std::string("; this sweep has ") + std::to_string(sampled.size()) +
        " distribution keys and " + std::to_string(sweep->sampling->samples) + " samples");
  }
  // Each sample is computed when its point runs (SampleDraw): nothing of size N here.
  for (std::size_t d = 0; d < sampled.size(); ++d) {
    sampled[d]->draw = std::make_shared<const SampleDraw>(*sweep->sampling, d, *sampled[d]->distribution);
  }
}

std::uint64_t CountPoints(const std::vector<SweepAxis>& axes, const NodeReader& grid) {
  std::uint64_t points = 1;
  for (const auto& axis : axes) {
    if (axis.size() > std::numeric_limits<std::uint64_t>::max() / points) {
      throw grid.Error("the grid has more than 2^64 points");
    }
    points *= axis.size();
  }
  return points;
}

}  // namespace shapebench::bench
