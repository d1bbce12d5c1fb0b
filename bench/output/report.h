// What a run leaves behind: the metrics table, metrics JSON, the trace CSV, the
// deflection plot (and two runs' overlaid), and JUnit XML for checks. Files are written
// atomically.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/config/override.h"
#include "bench/scenario/checks.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/metrics.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench {

// One aligned line per metric: name, value in engineering units (common/format.h:
// "7.99855 um", "12.5 ms"), "n/a" for NaN.
void PrintMetricsTable(std::ostream& out, const Metrics& metrics);

// `run`'s table: PrintMetricsTable, then, where CVODE ran, the rtol it ran with
// (`integrator_rtol_used`: the scenario's, or the default tightened by its cross-check).
void PrintRunTable(std::ostream& out, const RunResult& result);

// The unit a table shows for a metric (MetricInfo::shown_unit): "m", "s", or "".
std::string MetricUnit(const std::string& name);

// {"static_displacement_m": ..., ...} in MetricTable() order (ordered_json keeps it);
// NaN -> null, bool metrics as false/true.
nlohmann::ordered_json MetricsJson(const Metrics& metrics);

// `run --json` and run --out's metrics.json: MetricsJson, then "residual_modes", the free
// vibration at motion end per pole of the plant (RunResult::residual_modes), ascending
// frequency: [{"frequency_hz", "damping_ratio", "amplitude_m"}, ...] (the poles the output
// view sees; empty for a machine without states; a real pole: its rate / 2 pi and damping
// ratio 1), then "stroke_alarm_source" (StrokeAlarmJson; only where the alarm fired), then
// "integrator_rtol_used" (RunResult::integrator_rtol_used; null where no CVODE ran).
nlohmann::ordered_json RunJson(const RunResult& result);
// run --json's "peak_deflection_source", "max_contour_error_source" and
// "cruise_residual_source" (after integrator_rtol_used): {time_s, block (0-based, -1 after
// the program), file, line (null without a G-code file), cause: {the same four}}, or null
// where the run has none (bench/run/metric_sources.h; docs/views.md#attribution).
nlohmann::ordered_json SourceJson(const MetricSource& source);
// The three sources under those names, in that order.
std::vector<std::pair<std::string, const MetricSource*>> SourceEntries(const MetricSources& sources);
// Where a stroke alarm fired, as run --json's "stroke_alarm_source" (only where it fired):
// {time_s, block (1-based), line (G-code; null otherwise), axis, position_m, limit_m}.
nlohmann::ordered_json StrokeAlarmJson(const controller::StrokeAlarmSite& site);

// t_s, the scalar view (command_position_m, command_velocity_m_s, command_accel_m_s2,
// deflection_m), per axis command_{x,y,z}_m, actual_{x,y,z}_m, deflection_{x,y,z}_m, then
// block (0-based, -1 after the program) and planned_feed_mm_min; numbers as ExactDouble
// (common/csv.h): the shortest text that reads back exactly.
// A trace of more than `max_rows` samples is decimated (TraceStride): every stride-th
// sample from the first, and a first line "# decimated: 1 in K of N samples kept ..." says
// so. Returns the stride.
std::size_t WriteTraceCsv(const std::string& path, const Trace& trace,
                          long max_rows = RunLimits{}.max_trace_rows);

// trace.csv's columns in order, as its header names them (the Python module's trace keys).
const std::vector<std::string>& TraceColumns();

// The stride that keeps at most `max_rows` (>= 2) of `samples` samples: 1 when they fit,
// else ceil((samples - 1) / (max_rows - 1)): samples 0, stride, 2 stride, ..., which
// reach to within one stride of the last sample.
std::size_t TraceStride(std::size_t samples, long max_rows);

// Deflection in um (y1) and command acceleration in m/s^2 (y2) over time, the static band
// +/- static_displacement dashed; pngcairo 1000x600 via gnuplot. Throws
// std::runtime_error when gnuplot is missing or fails.
// The peak is marked (um and peak_ratio), the residual amplitude labelled after the
// motion's end, which is marked and labelled too; `title` heads the plot (RunPlotTitle).
void WriteDeflectionPlot(const std::string& path_png, const RunResult& result,
                         const Scenario& scenario, const std::string& title);

// The title of a run's plots: the scenario's name, its pattern method and the --set
// options, so two runs of one file tell apart ("demo, method none, --set ..."); each
// option's value is shortened past 24 characters and the options past 160 in all.
std::string RunPlotTitle(const Scenario& scenario, const std::vector<Override>& overrides);

// The deflection is identically zero (a rigid machine, no states): deflection.png would
// be a flat line, so `run --out` writes a note instead.
bool DeflectionIsZero(const RunResult& result);

// The programmed path is a straight line along one axis (every point shares its x or its
// y): path.png would be a line, so `run --out` writes a note instead.
bool PathIsSingleAxisLine(const RunResult& result);

// One run of a deflection overlay: its result (the trace), its scenario (the trace's row
// limit), a short name ("baseline") and its legend entry.
struct OverlaidRun {
  const RunResult* result = nullptr;
  const Scenario* scenario = nullptr;
  std::string name;
  std::string title;
};

// The deflection of several runs over time in one plot (um against s, `compare --out`):
// each run a line in its colour, where its motion ends dotted, its static band dashed
// (once, grey, when the runs share it); the legend in a strip under the plot.
void WriteDeflectionOverlayPlot(const std::string& path_png, const std::vector<OverlaidRun>& runs,
                                const std::string& title);

// The XY path (programmed vs actual tool path), the deviation from the programmed path
// magnified so it shows at the path's scale (the circle-test plot of ISO 230-4); mm.
void WritePathPlot(const std::string& path_png, const RunResult& result,
                   const Scenario& scenario, const std::string& title);

// JUnit XML: one <testsuite> per scenario file, one <testcase> per check; a failed run
// is one <testcase name="run"> with an <error>. A sweep: one <testcase> per point and
// check, named "METRIC @ KEY=VALUE, ...", and "run @ KEY=VALUE, ..." with an <error> for
// a point that failed to run. A band check: "METRIC over KEY in [FROM, TO]", with
// band_key, worst_value, worst_at and runs properties and BandText() as its system-out (and
// its failure's message).
void WriteJUnit(const std::string& path, const std::vector<ScenarioCheckReport>& reports);

// `check --json`: {"files": [{file, name, error (null or the run's), results: [{metric,
// point (a sweep's), value (null: undefined), bound, passed, message, band (a band check:
// key, from, to, worst_value, worst_at, runs, text)}], point_errors: [{point, message}]}]}.
nlohmann::ordered_json CheckReportsJson(const std::vector<ScenarioCheckReport>& reports);

// Escapes text for XML attributes and content; drops what XML 1.0 cannot hold.
std::string XmlEscape(const std::string& text);

}  // namespace shapebench::bench
