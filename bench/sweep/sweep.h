// A sweep file (docs/sweeps.md): a base scenario and a grid of values over any
// of its keys, the metrics to keep, the plots to draw and checks for every point.
//
//   name: natural_period                 # optional; default: the file's stem
//   base: ../scenarios/sdof_method1.yaml # the scenario, relative to the sweep file
//   grid:                                # dotted key paths as in --set, any scenario key
//     machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 201}   # linear range
//     controller.feed_mm_min: {from: 1000, to: 30000, steps: 5, spacing: log}
//     controller.pattern.method: [none, 1, 3]                         # a list of YAML values
//     zip:                               # keys that move together (equal lengths): one axis
//       controller.feed_mm_min: [6000, 12000]
//       controller.accel_time_s: [0.1, 0.2]
//     # several zip groups: zip: [{a: [..], b: [..]}, {c: [..], d: [..]}]
//     machine.modes[0].damping_ratio: {normal: {mean: 0.03, sd: 0.003}}  # a distribution:
//   samples: 500                         # with samples:, seed:, design: (bench/sweep/sampling.h)
//   metrics: [peak_ratio, residual_ratio] # results.csv columns (default: every metric)
//   plots:                                 # PNGs next to results.csv
//     - {metric: residual_ratio, x: machine.modes[0].frequency_hz, series: controller.pattern.method}
//     - {metric: peak_ratio, heatmap: [machine.modes[0].frequency_hz, controller.feed_mm_min], log: true}
//   checks: {residual_ratio: {max: 0.05}}  # `check` applies them to every point
//
// The grid is the Cartesian product of its axes in the order written, the LAST axis
// varying fastest (like nested loops written top to bottom); a zip group is one axis at
// the place of its `zip:` key. Point p (0-based) has the mixed-radix digits of p. A range
// has `steps` values from `from` to `to` inclusive (steps 1: `from` only, which must then
// equal `to`), evenly spaced or, with `spacing: log`, evenly in log (from, to > 0); each
// value is written (results.csv, the override) in at most 15 significant digits, so float
// noise does not show ("15.3", not "15.300000000000001"; `from` and `to` as written), and
// the point runs with exactly the value shown. A list value is used as written (its YAML
// scalar text; a mapping or list value in flow style).
// Each point is the base scenario with the point's values applied as --set overrides
// (keys inside a machine file referenced by `machine:` included), then the command
// line's --set options; a --set may not touch a swept key. Pattern values left to the
// machine (no frequency_hz, `machine`) come from the base scenario's machine, not the
// point's (Sweep::design_modes).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/config/config_error.h"
#include "bench/scenario/metrics.h"
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
  // kSampled (bench/sweep/sampling.h): the distribution and its samples, drawn once per load.
  std::optional<Distribution> distribution;
  std::shared_ptr<const std::vector<double>> samples;

  std::uint64_t size() const;
  std::string Text(std::uint64_t i) const;
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

struct SweepLoadOptions {
  // A grid larger than this is refused (exit 2) unless `force`.
  std::uint64_t max_points = 2'000'000;
  bool force = false;
};

// True when the file is a YAML mapping with both `base:` and `grid:` (a sweep, not a
// scenario). False for anything unreadable (the scenario loader then reports it).
bool IsSweepFile(const std::string& path);

// `path` as a sweep names itself in messages and files: relative to the working
// directory when the file is inside it, else absolute; "./a/../a/s.yaml", "a/s.yaml" and
// "/cwd/a/s.yaml" all give "a/s.yaml" (symbolic links in its directory resolved).
std::string SweepPath(const std::string& path);

// Reads and checks a sweep file (named by SweepPath(path) in its errors and results): every error is a ConfigError at FILE:LINE:COL with its
// key path. Also loads the base scenario with `sets` (errors located there), applies
// point 0's values to the base (a swept key that does not fit the scenario, or is not a
// scenario key, is an error of the sweep file), and refuses --set options on swept keys.
Sweep LoadSweep(const std::string& path, const std::vector<Override>& sets,
                const SweepLoadOptions& options = {});

// What running one point gave.
struct PointOutcome {
  enum class Status { kOk, kBadInput, kSolverFailed, kFailed };
  std::uint64_t index = 0;
  Status status = Status::kOk;
  Metrics metrics;
  std::string error;  // "FILE:LINE:COL: key: message", "solver failed: FLAG: ..."
  bool ok() const { return status == Status::kOk; }
};

// Loads and runs one point; throws only std::bad_alloc (out of memory says nothing of the
// point: a row "error" would be kept by a resumed sweep, so the sweep stops instead). An error caused by one of the point's values
// is located at that value in the sweep file; one caused by a --set reads --set:N:1.
PointOutcome RunPoint(const Sweep& sweep, const std::vector<Override>& sets, std::uint64_t index);
// The same for the point MakePoint(sweep, point.index, sets) made.
PointOutcome RunPoint(const Sweep& sweep, const SweepPoint& point);

std::uint64_t BaseScenarioHash(const Sweep& sweep);

// A hash (16 hex digits) of everything results.csv depends on: the base scenario as read
// (machine and program files included), the expanded grid, the --set options and the
// kept metrics. Shards and resumed runs must agree on it.
std::string SweepHash(const Sweep& sweep, const std::vector<Override>& sets);

// Unit suffix of a key or metric name for axis labels: _hz Hz, _s s, _mm mm, _mm_min
// mm/min, _m m, _kg kg, _m_s m/s, _m_s2 m/s^2; "" when none.
std::string KeyUnit(const std::string& key);

}  // namespace shapebench::bench
