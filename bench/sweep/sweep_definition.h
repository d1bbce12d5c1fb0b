// What a sweep file defines, once read (bench/sweep/sweep.h reads it): each swept key's
// values, the axes, the plots, the Sweep, and its points (MakePoint). Also how a point's
// errors are located in the sweep file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/config/config_error.h"
#include "bench/config/override.h"
#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/scenario.h"
#include "bench/sweep/sampling.h"

namespace shapebench::bench {

// The values of one swept key.
struct SweepValues {
  enum class Kind { kList, kLinear, kLog, kSampled };

  std::string key;  // the dotted key path as written
  Kind kind = Kind::kList;
  int line = 0;     // where the values are written in the sweep file (1-based)
  int column = 0;
  // kList: each value's text as written (results.csv), as YAML (the override), position.
  std::vector<std::string> texts;
  std::vector<std::string> yamls;
  std::vector<std::pair<int, int>> positions;
  // kLinear, kLog.
  double from = 0.0;
  double to = 0.0;
  std::uint64_t steps = 0;
  // kSampled (bench/sweep/sampling.h): the distribution and its samples, each computed
  // when a point asks (no list of them is held).
  std::optional<Distribution> distribution;
  std::shared_ptr<const SampleDraw> draw;
  // kLinear, kLog of at most kKeptTexts values: every value's text, made once when the
  // sweep is loaded (KeepTexts). The manifest's hash and each point read it (each made it
  // before: a 15-digit text costs about as much as a point's row of metrics).
  std::shared_ptr<const std::vector<std::string>> kept_texts;
  static constexpr std::uint64_t kKeptTexts = 100'000;

  std::uint64_t size() const;
  std::string Text(std::uint64_t i) const;
  // Text(i) into *text (its capacity kept: no allocation a point).
  void AssignText(std::uint64_t i, std::string* text) const;
  void KeepTexts();
  std::string Yaml(std::uint64_t i) const;
  std::pair<int, int> Position(std::uint64_t i) const;
  bool log() const { return kind == Kind::kLog; }
};

// One axis of the grid: one key, or the keys of a zip group (equal lengths).
struct SweepAxis {
  std::vector<SweepValues> keys;
  std::uint64_t size() const { return keys.front().size(); }
};

// A plot of the sweep: `metric` against `x`, one line per value of `series` (optional);
// or a heat map of `metric` over `heatmap_x` and `heatmap_y`.
struct SweepPlot {
  std::string metric;
  std::string x;
  std::string series;
  std::string heatmap_x;
  std::string heatmap_y;
  // `log:` the metric's axis (a heat map's colour scale) in log: true, false, or unset:
  // then log for a ratio metric whose positive values span more than two decades
  // (LogMetricAxis, bench/sweep/sweep_plot.h).
  std::optional<bool> log;
  // A sampled sweep's empirical CDF of `metric` over its samples (`x` is a key of the axis
  // of samples), one curve per value of `series`, with the checks' bounds on it as
  // vertical lines (`limits`).
  bool cdf = false;
  std::vector<double> limits = {};
  bool heatmap() const { return !heatmap_x.empty(); }
};

struct Sweep {
  std::string file;  // SweepPath of the path given (the same for every spelling of it)
  std::string name;  // `name:` or the file's stem
  std::string base;  // the base scenario's path (resolved against the sweep file)
  std::vector<SweepAxis> axes;       // in file order; the last varies fastest
  // samples:, seed:, design: of a sweep with distribution keys, which all move with the
  // axis `sample_axis` (bench/sweep/sampling.h); nullopt for a plain grid.
  std::optional<SweepSampling> sampling;
  std::size_t sample_axis = 0;
  std::vector<std::string> metrics;  // kept in results.csv, in the order written
  std::vector<SweepPlot> plots;
  std::vector<Check> checks;
  std::vector<SampleGate> gates;  // a sampled sweep's quantile and yield gates
  // `band_threshold:`: the level of the robust bands of ratio metrics without a max check
  // (bench/sweep/robust_band.h); nullopt: their 5% level.
  std::optional<double> band_threshold;
  std::uint64_t points = 0;
  std::uint64_t id = 0;  // unique to this load of the sweep (RunPoint's shared commands)
  // The base scenario's participating modes (pattern_defaults.h): every point's pattern
  // values left to the machine are taken from them, not from the point's own machine, so
  // a sweep of the plant (the natural-period sweep) keeps the pattern fixed. nullopt (a
  // Sweep built by hand): each point's own.
  std::optional<DesignModes> design_modes;
  // Said once on stderr by the commands that run the sweep: the pattern is left to the
  // machine while swept keys change the machine (empty when not).
  std::string note;
  // The base scenario as LoadSweep loaded it with its --set options (base_sets_key: each
  // "key=value\n"): the structure-only points of every thread start from it and set their
  // numbers (structure_numbers.h) instead of loading it again. Null: loaded per thread.
  std::shared_ptr<const Scenario> base_scenario;
  std::string base_sets_key;
  // SweepHash's state after the base scenario's files (BaseScenarioHash), hashed when
  // LoadSweep read them; 0: hashed when asked.
  std::uint64_t base_hash = 0;

  // Every swept key in column order (axes in order, a zip group's keys as written).
  std::vector<std::string> Keys() const;
  // The value index on each axis of point p.
  std::vector<std::uint64_t> AxisIndices(std::uint64_t point) const;
};

// One point: its values and the overrides that make its scenario.
struct SweepPoint {
  std::uint64_t index = 0;
  std::vector<std::string> keys;    // Sweep::Keys()
  std::vector<std::string> texts;   // each key's value as results.csv shows it
  std::vector<Override> overrides;  // the point's values (in key order), then the --set ones
  // "machine.modes[0].frequency_hz=21.5, controller.pattern.method=1"
  std::string Label() const;
};

SweepPoint MakePoint(const Sweep& sweep, std::uint64_t index, const std::vector<Override>& sets);
// The same into *point, its strings' and vectors' capacity reused (a sweep's thread keeps one).
void MakePointInto(const Sweep& sweep, std::uint64_t index, const std::vector<Override>& sets, SweepPoint* point);

struct SweepLoadOptions {
  // A grid larger than this is refused (exit 2) unless `force`.
  std::uint64_t max_points = 2'000'000;
  bool force = false;
};

// The --set options a scenario was loaded with, as a key: "key=value\n" each.
std::string OverridesKey(std::vector<Override>::const_iterator first,
                         std::vector<Override>::const_iterator last);

// A ConfigError from loading a point: the grid's overrides are located in the sweep file,
// the command line's keep their own --set numbering.
ConfigError RelocatePointError(const Sweep& sweep, const SweepPoint& point, const ConfigError& error);

// Whether the error is at one of the point's grid overrides (not a --set one).
bool IsGridOverrideError(const SweepPoint& point, const ConfigError& error);

}  // namespace shapebench::bench
