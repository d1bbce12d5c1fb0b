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
#include "bench/sweep/sweep_definition.h"
#include "bench/sweep/sweep_point_run.h"

namespace shapebench::bench {

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

std::uint64_t BaseScenarioHash(const Sweep& sweep);

// A hash (16 hex digits) of everything results.csv depends on: the base scenario as read
// (machine and program files included), the expanded grid, the --set options and the
// kept metrics. Shards and resumed runs must agree on it.
std::string SweepHash(const Sweep& sweep, const std::vector<Override>& sets);

// Unit suffix of a key or metric name for axis labels: _hz Hz, _s s, _mm mm, _mm_min
// mm/min, _m m, _kg kg, _m_s m/s, _m_s2 m/s^2; "" when none.
std::string KeyUnit(const std::string& key);

}  // namespace shapebench::bench
