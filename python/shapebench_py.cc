// shapebench._core: the bench as a Python module (pybind11). The package around it,
// python/shapebench/__init__.py, is the documented API (docs/python.md); this file only
// calls the functions the CLI's commands call (bench/cli/main.cc), so that a run's metrics
// are the CLI's to the last bit:
//   run       LoadScenario, RunScenarioLocated, RunJson (`run --json`)
//   checks    ValidateBandChecks, EvaluateScenarioChecks, CheckReportsJson (`check --json`)
//   sweep     LoadSweep, MakePoint and RunPoint on ForEachSweepPoint (results.csv's rows)
//   pattern   ComputePattern, MachineModeResiduals, MotionTimesWithAndWithoutPattern
//   modes     LoadMachineAxes, AnalyzeMachineModes, ModesJson (`modes --json`)
//   sensitivity  LoadSensitivity, ComputeSensitivity
// The GIL is released while the bench loads, simulates or evaluates: runs from several
// Python threads proceed in parallel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "python/sigint_watch.h"

#include "bench/cli/shapebench_version.h"  // generated in the build tree: cmake/git_version.cmake
#include "bench/config/config_error.h"
#include "bench/run/located_run.h"
#include "bench/config/override.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/output/design_request.h"
#include "bench/output/html_report.h"
#include "bench/output/modes_report.h"
#include "bench/output/pattern_report.h"
#include "bench/output/report.h"
#include "bench/scenario/checks.h"
#include "bench/run/run_scenario.h"
#include "bench/sweep/band_check.h"
#include "bench/sensitivity/sensitivity.h"
#include "bench/sweep/point_loop.h"
#include "bench/sweep/sweep.h"
#include "common/format.h"
#include "common/validation_error.h"
#include "controller/impulse.h"
#include "controller/shaper_registry.h"
#include "model/integrator.h"
#include "model/multi_axis_machine.h"

namespace py = pybind11;

namespace shapebench::python {
namespace {

using bench::Override;

// ---------------------------------------------------------------------------------------
// Conversions

// A JSON value as Python objects: null None, numbers float or int (a double converts
// exactly: both are IEEE binary64), arrays lists, objects dicts in their order.
py::object FromJson(const nlohmann::ordered_json& json) {
  switch (json.type()) {
    case nlohmann::ordered_json::value_t::null: return py::none();
    case nlohmann::ordered_json::value_t::boolean: return py::bool_(json.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer: return py::int_(json.get<std::int64_t>());
    case nlohmann::ordered_json::value_t::number_unsigned: return py::int_(json.get<std::uint64_t>());
    case nlohmann::ordered_json::value_t::number_float: return py::float_(json.get<double>());
    case nlohmann::ordered_json::value_t::string: return py::str(json.get<std::string>());
    case nlohmann::ordered_json::value_t::array: {
      py::list list;
      for (const auto& item : json) list.append(FromJson(item));
      return std::move(list);
    }
    case nlohmann::ordered_json::value_t::object: {
      py::dict dict;
      for (const auto& [key, value] : json.items()) dict[py::str(key)] = FromJson(value);
      return std::move(dict);
    }
    default: return py::none();
  }
}

py::array_t<double> Array(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

template <typename T, typename Get>
py::array_t<T> ArrayOf(std::size_t size, Get get) {
  py::array_t<T> array(static_cast<py::ssize_t>(size));
  T* data = array.mutable_data();
  for (std::size_t i = 0; i < size; ++i) data[i] = get(i);
  return array;
}

std::vector<Override> Overrides(const std::vector<std::string>& sets) { return bench::ParseOverrides(sets); }

// ---------------------------------------------------------------------------------------
// Errors: shapebench.ConfigError and shapebench.SolverError (python/shapebench/_errors.py),
// carrying the texts the CLI prints after "error: ".

void RegisterErrors() {
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const bench::ConfigError& error) {
      const py::object type = py::module_::import("shapebench._errors").attr("ConfigError");
      const py::object value = type(error.file(), error.line(), error.column(), error.key_path(),
                                    error.message(), std::string(error.what()));
      PyErr_SetObject(type.ptr(), value.ptr());
    } catch (const model::SolverError& error) {
      const py::object type = py::module_::import("shapebench._errors").attr("SolverError");
      const py::object value = type(error.flag_name(), std::string(error.what()), bench::SolverFailureText(error));
      PyErr_SetObject(type.ptr(), value.ptr());
    } catch (const controller::DesignError& error) {  // `design` found no pattern (the CLI's exit 3)
      const py::object type = py::module_::import("shapebench._errors").attr("SolverError");
      const py::object value = type("DESIGN", std::string(error.what()));
      PyErr_SetObject(type.ptr(), value.ptr());
    } catch (const ValidationError& error) {  // not located in a file (the CLI's "error: FIELD: ...")
      const py::object type = py::module_::import("shapebench._errors").attr("ConfigError");
      const py::object value = type("", 0, 0, error.field(), error.message(), std::string(error.what()));
      PyErr_SetObject(type.ptr(), value.ptr());
    }
  });
}

// ---------------------------------------------------------------------------------------
// Scenario and Result

struct LoadedScenario {
  std::shared_ptr<const bench::Scenario> scenario;
  std::vector<std::string> sets;  // as given: "KEY=VALUE"
  std::vector<Override> overrides;
};

LoadedScenario Load(const std::string& path, const std::vector<std::string>& sets, bool plan_move) {
  LoadedScenario loaded;
  loaded.sets = sets;
  loaded.overrides = Overrides(sets);
  bench::LoadOptions options;
  options.plan_move = plan_move;
  py::gil_scoped_release release;
  loaded.scenario = std::make_shared<const bench::Scenario>(bench::LoadScenario(path, loaded.overrides, options));
  return loaded;
}

class Result {
 public:
  Result(const LoadedScenario& source, bench::RunResult&& result, bool trace)
      : source_(source), metrics_(result.metrics), json_(bench::RunJson(result)) {
    warnings_ = result.command.warnings;
    warnings_.insert(warnings_.end(), result.warnings.begin(), result.warnings.end());
    if (trace) trace_ = std::move(result.trace);
  }

  // The metrics of RunJson (`run --json`) in its order: null (undefined) as NaN, the bool
  // metric (stroke_alarm) as 0.0 or 1.0; every other value is the double RunJson holds.
  py::dict Metrics() const {
    py::dict metrics;
    for (const bench::MetricInfo& info : bench::MetricTable()) {
      const nlohmann::ordered_json& value = json_.at(std::string(info.name));
      const double number = value.is_null() ? NAN : value.is_boolean() ? (value.get<bool>() ? 1.0 : 0.0)
                                                                        : value.get<double>();
      metrics[py::str(std::string(info.name))] = py::float_(number);
    }
    // A nonlinear plant's own metrics (dead_band_m, quadrant_glitch_m): present exactly
    // where RunJson has them (absent from a linear run's, as in `run --json`).
    for (const bench::MetricInfo& info : bench::NonlinearMetricTable()) {
      const std::string name(info.name);
      if (json_.contains(name)) metrics[py::str(name)] = py::float_(json_.at(name).get<double>());
    }
    return metrics;
  }

  py::list ResidualModes() const { return FromJson(json_.at("residual_modes")); }
  double RtolUsed() const {
    const nlohmann::ordered_json& value = json_.at("integrator_rtol_used");
    return value.is_null() ? NAN : value.get<double>();
  }

  std::string Json() const { return json_.dump(2); }

  py::object Trace() const {
    if (!trace_) return py::none();
    const bench::Trace& t = *trace_;
    const std::size_t n = t.time_s.size();
    const std::vector<std::string>& names = bench::TraceColumns();
    py::dict trace;
    std::size_t column = 0;
    for (const std::vector<double>* values : {&t.time_s, &t.command_position_m, &t.command_velocity_m_s,
                                              &t.command_accel_m_s2, &t.deflection_m}) {
      trace[py::str(names[column++])] = Array(*values);
    }
    for (const std::vector<Eigen::Vector3d>* values : {&t.command_m, &t.actual_m, &t.deflection_axes_m}) {
      for (int axis = 0; axis < 3; ++axis) {
        trace[py::str(names[column++])] = ArrayOf<double>(n, [&](std::size_t i) { return (*values)[i][axis]; });
      }
    }
    trace[py::str(names[column++])] = ArrayOf<int>(n, [&](std::size_t i) { return t.block[i]; });
    trace[py::str(names[column++])] = Array(t.planned_feed_mm_min);
    return std::move(trace);
  }

  // `check --json`'s results of this run (evaluated once, on first use: a band check runs
  // the scenario over its band).
  py::list Checks() {
    if (!checks_) {
      nlohmann::ordered_json json;
      {
        py::gil_scoped_release release;
        bench::ValidateBandChecks(*source_.scenario, source_.overrides);
        bench::ScenarioCheckReport report;
        report.file = source_.scenario->source_file;
        report.name = source_.scenario->name;
        report.results = bench::EvaluateScenarioChecks(*source_.scenario, source_.overrides, metrics_);
        json = bench::CheckReportsJson({report});
      }
      checks_ = FromJson(json.at("files").at(0).at("results"));
    }
    return *checks_;
  }

  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  LoadedScenario source_;
  bench::Metrics metrics_;
  nlohmann::ordered_json json_;
  std::optional<bench::Trace> trace_;
  std::vector<std::string> warnings_;
  std::optional<py::list> checks_;
};

Result Run(const LoadedScenario& source, bool trace) {
  bench::RunOptions options;
  options.record_trace = trace;
  std::optional<bench::RunResult> result;
  {
    py::gil_scoped_release release;
    result = bench::RunScenarioLocated(*source.scenario, source.overrides, options);
  }
  return Result(source, std::move(*result), trace);
}

// ---------------------------------------------------------------------------------------
// Sweep: the columns of results.csv

// Every point of the sweep on `jobs` threads, in point order. Ctrl-C stops it between
// points: on Python's main thread a pending signal, looked at every 100 ms; on another
// thread a SIGINT counted since it began (python/sigint_watch.h), looked at before each
// point. Either raises KeyboardInterrupt in the thread that called.
py::dict Sweep(const std::string& path, const std::vector<std::string>& sets, int jobs, bool force) {
  const std::vector<Override> overrides = Overrides(sets);
  bench::SweepLoadOptions load;
  load.force = force;
  std::optional<bench::Sweep> loaded;
  {
    py::gil_scoped_release release;
    loaded = bench::LoadSweep(path, overrides, load);
  }
  const bench::Sweep& sweep = *loaded;
  const std::vector<std::string> keys = sweep.Keys();
  std::vector<const bench::MetricInfo*> metrics;
  for (const std::string& name : sweep.metrics) {
    if (const bench::MetricInfo* info = bench::FindMetric(name)) metrics.push_back(info);
  }
  const std::size_t points = sweep.points;
  std::vector<std::vector<std::string>> texts(keys.size());
  std::vector<std::vector<double>> values(metrics.size());
  std::vector<std::string> status;
  std::vector<std::string> errors;
  std::atomic<bool> interrupted{false};
  auto last_look = std::chrono::steady_clock::now();
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  std::optional<SigintWatch> watch;
  if (!main_thread) watch.emplace();
  using Row = std::pair<std::vector<std::string>, bench::PointOutcome>;
  {
    py::gil_scoped_release release;
    bench::ForEachSweepPoint<Row>(
        0, points, jobs,
        [&](std::uint64_t p) {
          return Row{bench::MakePoint(sweep, p, overrides).texts, bench::RunPoint(sweep, overrides, p)};
        },
        [&](std::uint64_t, Row&& row) {
          for (std::size_t k = 0; k < keys.size(); ++k) texts[k].push_back(std::move(row.first[k]));
          const bench::PointOutcome& outcome = row.second;
          for (std::size_t m = 0; m < metrics.size(); ++m) {
            values[m].push_back(outcome.ok() ? outcome.metrics.*metrics[m]->field : NAN);
          }
          status.push_back(outcome.ok() ? "ok" : "error");
          errors.push_back(outcome.error);
          if (main_thread && std::chrono::steady_clock::now() - last_look > std::chrono::milliseconds(100)) {
            last_look = std::chrono::steady_clock::now();
            py::gil_scoped_acquire acquire;
            if (PyErr_CheckSignals() != 0) interrupted = true;
          }
        },
        [&] {
          if (watch && watch->Fired()) interrupted = true;
          return interrupted.load();
        });
  }
  if (interrupted && !main_thread) PyErr_SetNone(PyExc_KeyboardInterrupt);
  if (interrupted) throw py::error_already_set();
  py::dict columns;
  columns["point"] = ArrayOf<std::int64_t>(status.size(), [](std::size_t i) { return static_cast<std::int64_t>(i); });
  for (std::size_t k = 0; k < keys.size(); ++k) columns[py::str(keys[k])] = texts[k];
  for (std::size_t m = 0; m < metrics.size(); ++m) {
    columns[py::str(std::string(metrics[m]->name))] = Array(values[m]);
  }
  columns["status"] = status;
  columns["error"] = errors;
  py::dict result;
  result["name"] = sweep.name;
  result["file"] = sweep.file;
  result["base"] = sweep.base;
  result["points"] = points;
  result["keys"] = keys;
  result["metrics"] = sweep.metrics;
  result["note"] = sweep.note;
  result["columns"] = columns;
  return result;
}

// ---------------------------------------------------------------------------------------
// Pattern, modes, sensitivity

py::dict Impulses(const std::vector<controller::Impulse>& impulses) {
  py::dict dict;
  dict["time_s"] = ArrayOf<double>(impulses.size(), [&](std::size_t i) { return impulses[i].time_s; });
  dict["amplitude"] = ArrayOf<double>(impulses.size(), [&](std::size_t i) { return impulses[i].amplitude; });
  return dict;
}

py::dict Pattern(const LoadedScenario& source) {
  const bench::Scenario& scenario = *source.scenario;
  std::optional<bench::PatternData> data;
  std::vector<bench::ModeResidual> modes;
  bench::PatternMotionTimes times;
  {
    py::gil_scoped_release release;
    data = bench::ComputePattern(scenario.controller);
    modes = bench::MachineModeResiduals(scenario);
    if (data->shapes) times = bench::MotionTimesWithAndWithoutPattern(scenario);
  }
  const controller::PatternConfig& config = scenario.controller.pattern;
  py::dict result;
  result["method"] = config.method;
  result["realization"] =
      config.realization == controller::PatternRealization::kProfileTable ? "profile_table" : "stepped";
  result["shapes"] = data->shapes;
  result["design_frequencies_hz"] = Array(data->design_frequencies_hz);
  result["impulses"] = Impulses(data->impulses);
  result["period_s"] = data->period_s;
  result["table"] = Array(data->table);
  py::list residuals;
  for (const bench::PatternResidual& r : data->residuals) {
    residuals.append(py::dict(py::arg("frequency_hz") = r.frequency_hz, py::arg("damping_ratio") = r.damping_ratio,
                              py::arg("stepped") = r.stepped, py::arg("profile_table") = r.profile_table,
                              py::arg("rounded") = r.rounded));
  }
  result["residuals"] = residuals;
  py::list mode_list;
  for (const bench::ModeResidual& m : modes) {
    mode_list.append(py::dict(py::arg("axis") = model::AxisName(m.axis), py::arg("mode") = m.mode,
                              py::arg("frequency_hz") = m.frequency_hz, py::arg("damping_ratio") = m.damping_ratio,
                              py::arg("participation") = m.participation, py::arg("stepped") = m.stepped,
                              py::arg("profile_table") = m.profile_table));
  }
  result["machine_modes"] = mode_list;
  result["duration_s"] = controller::ShaperDuration(data->impulses);
  result["motion_time_shaped_s"] = times.shaped_s;
  result["motion_time_unshaped_s"] = times.unshaped_s;
  result["motion_time_note"] = times.why_not;
  return result;
}

py::object Modes(const std::string& path, const std::vector<std::string>& sets) {
  const std::vector<Override> overrides = Overrides(sets);
  nlohmann::ordered_json json;
  {
    py::gil_scoped_release release;
    const model::MultiAxisMachineConfig machine = bench::LoadMachineAxes(path, overrides);
    json = bench::ModesJson(model::AnalyzeMachineModes(machine), machine.driven_axis);
  }
  return FromJson(json);
}

py::dict Band(const bench::Band& band) {
  py::dict dict;
  dict["found"] = band.found;
  dict["low"] = band.found ? band.low : NAN;
  dict["high"] = band.found ? band.high : NAN;
  dict["width"] = band.width();
  dict["open_low"] = band.open_low;
  dict["open_high"] = band.open_high;
  return dict;
}

py::dict Sensitivity(const std::string& path, const std::vector<std::string>& sets) {
  const std::vector<Override> overrides = Overrides(sets);
  std::optional<bench::SensitivityResult> result;
  std::optional<bench::SensitivitySpec> spec;
  {
    py::gil_scoped_release release;
    spec = bench::LoadSensitivity(path, overrides);
    result = bench::ComputeSensitivity(*spec);
  }
  py::list curves;
  for (const bench::SensitivityCurve& curve : result->curves) {
    py::dict c;
    c["name"] = bench::CurveName(curve, *result);
    c["label"] = curve.label;
    c["shaper"] = curve.shaper;
    c["method"] = spec->shapers[curve.shaper].pattern.method;
    c["damping_ratio"] = curve.damping_ratio;
    c["realized"] = curve.realized;
    c["residual_percent"] = Array(curve.residual_percent);
    c["at_design_percent"] = curve.at_design_percent;
    c["band_5"] = Band(curve.band_5);
    c["band_level"] = Band(curve.band_level);
    c["impulses"] = Impulses(controller::ShaperImpulses(spec->shapers[curve.shaper].pattern));
    curves.append(c);
  }
  py::dict dict;
  dict["ratio"] = Array(result->ratio);
  dict["level"] = result->level;
  dict["period_s"] = result->period_s ? py::object(py::float_(*result->period_s)) : py::object(py::none());
  dict["curves"] = curves;
  return dict;
}

// residual_vibration's arguments, refused as the loader refuses a mode (frequency finite and
// > 0, damping in [0, 1)) and a custom pattern's impulses (times finite, >= 0 and strictly
// ascending, amplitudes finite), except that the amplitudes need only a positive sum (the
// residual is a fraction of the step they make): ValidationError, Python's ConfigError.
void ValidateResidualArguments(const std::vector<controller::Impulse>& impulses, double frequency_hz,
                               double damping_ratio) {
  if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
    throw ValidationError("frequency_hz", "must be finite and > 0" + FormatGot(frequency_hz));
  }
  if (!(damping_ratio >= 0.0 && damping_ratio < 1.0)) {
    throw ValidationError("damping_ratio", "must be in [0, 1) (underdamped)" + FormatGot(damping_ratio));
  }
  if (impulses.empty()) throw ValidationError("impulses", "must list at least one (time_s, amplitude) impulse");
  double total = 0.0;
  for (std::size_t i = 0; i < impulses.size(); ++i) {
    const std::string at = "impulses[" + std::to_string(i) + "]";
    if (!std::isfinite(impulses[i].amplitude)) {
      throw ValidationError(at + ".amplitude", "must be finite" + FormatGot(impulses[i].amplitude));
    }
    if (!(std::isfinite(impulses[i].time_s) && impulses[i].time_s >= 0.0)) {
      throw ValidationError(at + ".time_s", "must be finite and >= 0 s" + FormatGot(impulses[i].time_s));
    }
    if (i > 0 && !(impulses[i].time_s > impulses[i - 1].time_s)) {
      throw ValidationError(at + ".time_s", "must be after the previous impulse's (" +
                                                FormatNumber(impulses[i - 1].time_s) +
                                                " s): times strictly ascending" + FormatGot(impulses[i].time_s));
    }
    total += impulses[i].amplitude;
  }
  if (!(total > 0.0)) {
    throw ValidationError("impulses", "the amplitudes must have a positive sum (the residual is a fraction of "
                                      "the step they make)" + FormatGot(total));
  }
}

std::vector<controller::Impulse> ToImpulses(const std::vector<double>& times_s, const std::vector<double>& amplitudes) {
  if (times_s.size() != amplitudes.size()) {
    throw py::value_error("times_s and amplitudes differ in length (" + std::to_string(times_s.size()) + " and " +
                          std::to_string(amplitudes.size()) + ")");
  }
  std::vector<controller::Impulse> impulses;
  for (std::size_t i = 0; i < times_s.size(); ++i) impulses.push_back({times_s[i], amplitudes[i]});
  return impulses;
}

// ---------------------------------------------------------------------------------------
// The module

void DefineScenario(py::module_& m) {
  py::class_<LoadedScenario>(m, "Scenario", py::dynamic_attr(),
                             "A loaded, validated scenario (shapebench.load). Immutable: load again with other\n"
                             "`set` values for a variant. Safe to run from several threads at once.")
      .def_property_readonly("name", [](const LoadedScenario& s) { return s.scenario->name; },
                             "The scenario's name (`name:`, else the file's stem).")
      .def_property_readonly("source_file", [](const LoadedScenario& s) { return s.scenario->source_file; },
                             "The file it was read from.")
      .def_property_readonly("sets", [](const LoadedScenario& s) { return s.sets; },
                             "The overrides applied, as the CLI's --set texts \"KEY=VALUE\", in order.")
      .def("run", &Run, py::arg("trace") = false,
           "Simulates the scenario (the GIL released) and returns its Result. trace=True records\n"
           "the trace (every output substep; the metrics are the same bit for bit either way).")
      .def(
          "yaml",
          [](const LoadedScenario& s) { return bench::EffectiveScenarioYaml(s.scenario->source_file, s.overrides); },
          "The scenario's YAML as a run reads it: the file, its machine file spliced in, the\n"
          "overrides applied.");
}

void DefineResult(py::module_& m) {
  py::class_<Result>(m, "Result", "What Scenario.run() gives.")
      .def_property_readonly("metrics", &Result::Metrics,
                             "Every metric (docs/metrics.md) in table order, SI units, as float: the doubles\n"
                             "`run --json` prints; NaN where it prints null (not defined for this run);\n"
                             "stroke_alarm 0.0 or 1.0 where it prints false or true.")
      .def_property_readonly("residual_modes", &Result::ResidualModes,
                             "`run --json`'s residual_modes: per pole of the plant, ascending frequency,\n"
                             "{frequency_hz, damping_ratio, amplitude_m} (amplitude_m None: undefined).")
      .def_property_readonly("integrator_rtol_used", &Result::RtolUsed,
                             "`run --json`'s integrator_rtol_used: the rtol CVODE ran with (the scenario's, or\n"
                             "the default tightened by its cross-check); NaN where no CVODE ran.")
      .def_property_readonly("trace", &Result::Trace,
                             "With run(trace=True): trace.csv's columns as numpy arrays (t_s, ...,\n"
                             "block as int, planned_feed_mm_min), every sample; else None.")
      .def_property_readonly("checks", &Result::Checks,
                             "The scenario's checks evaluated on this run, as `check --json` gives each:\n"
                             "{metric, value (None: undefined), bound, passed, message, band (a band check)}.\n"
                             "Evaluated on first use (a band check runs the scenario over its band).")
      .def_property_readonly("warnings", &Result::warnings,
                             "The warnings the CLI prints on stderr for this run (controller, cross-check).")
      .def("json", &Result::Json,
           "The text `shapebench run FILE --json` prints (without its final newline).");
}

}  // namespace
}  // namespace shapebench::python

PYBIND11_MODULE(_core, m) {
  using namespace shapebench;
  using namespace shapebench::python;
  m.doc() = "The compiled core of the shapebench package; use the package (import shapebench).";
  m.attr("__version__") = std::string(SHAPEBENCH_VERSION);
  RegisterErrors();
  DefineResult(m);  // before Scenario: its run() signature names Result
  DefineScenario(m);
  m.def("load", &Load, py::arg("path"), py::arg("sets"), py::arg("plan_move") = true);
  m.def("sweep", &python::Sweep, py::arg("path"), py::arg("sets"), py::arg("jobs"), py::arg("force"));
  m.def("pattern", &python::Pattern, py::arg("scenario"));
  m.def("modes", &python::Modes, py::arg("path"), py::arg("sets"));
  m.def("sensitivity", &python::Sensitivity, py::arg("path"), py::arg("sets"));
  // `shapebench design`'s JSON (bench/output/design_report.h).
  m.def(
      "design",
      [](const std::string& path, const std::vector<std::string>& sets, const std::vector<std::string>& bands,
         const std::vector<std::string>& dampings, double tolerance, int derivatives, const std::string& form,
         std::optional<double> grid_s, std::optional<double> margin, bool registry, bool validate) {
        bench::DesignRequest request{path, sets,   bands,  dampings, tolerance, derivatives,
                                     form, grid_s, margin, registry, validate};
        nlohmann::ordered_json json;
        {
          py::gil_scoped_release release;
          json = bench::DesignJson(bench::ComputeDesign(request));
        }
        return FromJson(json);
      },
      py::arg("path"), py::arg("sets"), py::arg("bands"), py::arg("dampings"), py::arg("tolerance"),
      py::arg("derivatives"), py::arg("form"), py::arg("grid_s"), py::arg("margin"), py::arg("registry"),
      py::arg("validate"));
  m.def(
      "residual_vibration",
      [](const std::vector<double>& times_s, const std::vector<double>& amplitudes, double frequency_hz,
         double damping_ratio) {
        const std::vector<controller::Impulse> impulses = ToImpulses(times_s, amplitudes);
        ValidateResidualArguments(impulses, frequency_hz, damping_ratio);
        return controller::ResidualVibration(impulses, frequency_hz, damping_ratio);
      },
      py::arg("times_s"), py::arg("amplitudes"), py::arg("frequency_hz"), py::arg("damping_ratio") = 0.0);
  m.def("shapers", [] {
    py::list list;
    for (const controller::ShaperEntry* entry : controller::Shapers()) {
      list.append(py::dict(py::arg("key") = entry->key, py::arg("name") = entry->name,
                           py::arg("description") = entry->description));
    }
    return list;
  });
  m.def("config_error_text", [](const std::string& file, int line, int column, const std::string& key_path,
                                const std::string& message) {
    return std::string(bench::ConfigError(file, line, column, key_path, message).what());
  });
}
