"""shapebench: the CNC shaping / structural vibration testbench as a Python module.

The same C++ functions as the `shapebench` CLI, so a run's metrics equal `shapebench run
FILE --json` to the last bit (docs/python.md):

    import shapebench
    scenario = shapebench.load("configs/demo.yaml", set={"controller.pattern.method": "zvd"})
    result = scenario.run()                  # the GIL is released while it simulates
    result.metrics["residual_ratio"]         # floats; NaN where the CLI writes null
    shapebench.sweep("configs/sweeps/natural_period.yaml", jobs=2)["residual_ratio"]

A source is a file path or a dict of the file's content. `set` overrides keys as the CLI's
--set does, in order: {"controller.pattern.k1": 0.6} or ["controller.pattern.k1=0.6"]; a
str value is YAML text as on the command line ("none", "[1, 2]"), any other value is
written as YAML (numbers exactly, lists, dicts). Bad input raises ConfigError (the CLI's
exit 2, same text), a solver failure SolverError (exit 3).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, Union

import numpy as np

from . import _core
from ._core import Result, Scenario
from ._errors import ConfigError, Error, SolverError
from ._yaml import to_yaml

__version__: str = _core.__version__

__all__ = [
    "Band", "ConfigError", "Error", "Modes", "Pattern", "Result", "Scenario", "Sensitivity",
    "SensitivityCurve", "SolverError", "SweepResult", "load", "modes", "pattern",
    "design", "residual_vibration", "run", "sensitivity", "shapers", "sweep",
]

PathLike = Union[str, "os.PathLike[str]"]
Source = Union[PathLike, Mapping[str, Any]]
Sets = Union[Mapping[str, Any], Iterable[str], None]

# A source given as a dict: errors located in it are reported at this name (no position).
DICT_SOURCE = "<dict>"


def _set_texts(sets: Sets) -> list[str]:
    """`set` as the CLI's --set texts "KEY=VALUE", in order."""
    if sets is None:
        return []
    if isinstance(sets, Mapping):
        return [f"{key}={value if isinstance(value, str) else to_yaml(value)}" for key, value in sets.items()]
    if isinstance(sets, str):
        return [sets]
    return [str(text) for text in sets]


# Keys of a file that name other files, relative to it; a dict's are made absolute against
# its base_dir (default: the current directory).
_FILE_KEYS = {"scenario": ("machine", "program_file"), "sweep": ("base",), "machine": (),
              "sensitivity": ()}
# Keys of a machine mapping that name measured or exported data (docs/measured-data.md,
# docs/scenario-reference.md), relative to the file the machine is in.
_MACHINE_FILE_KEYS = ("frf_file", "modal_file")


def _absolute_machine_files(machine: Mapping[str, Any], base: str) -> dict[str, Any]:
    machine = dict(machine)
    for key in _MACHINE_FILE_KEYS:
        value = machine.get(key)
        if isinstance(value, (str, os.PathLike)) and not os.path.isabs(os.fspath(value)):
            machine[key] = os.path.join(base, os.fspath(value))
    return machine


class _DictSource:
    """A dict written as a YAML file in a private temporary directory, kept while in use."""

    def __init__(self, content: Mapping[str, Any], kind: str, base_dir: PathLike | None) -> None:
        self._dir = tempfile.TemporaryDirectory(prefix="shapebench-")
        base = os.path.abspath(os.fspath(base_dir) if base_dir is not None else os.getcwd())
        content = dict(content)
        if kind == "machine":
            content = _absolute_machine_files(content, base)
        elif kind == "scenario" and isinstance(content.get("machine"), Mapping):
            content["machine"] = _absolute_machine_files(content["machine"], base)
        for key in _FILE_KEYS[kind]:
            value = content.get(key)
            if kind == "sweep" and key == "base" and isinstance(value, Mapping):
                self.base = _DictSource(value, "scenario", base)
                content[key] = self.base.path
            elif isinstance(value, (str, os.PathLike)) and not os.path.isabs(os.fspath(value)):
                content[key] = os.path.join(base, os.fspath(value))
        self.path = os.path.join(self._dir.name, f"{kind}.yaml")
        with open(self.path, "w", encoding="utf-8") as out:
            out.write(to_yaml(content) + "\n")

    def shown(self, text: str) -> str:
        """`text` with this file's path (and a position in it) as DICT_SOURCE."""
        text = re.sub(re.escape(self.path) + r"(:\d+:\d+)?", DICT_SOURCE, text)
        base = getattr(self, "base", None)
        return base.shown(text) if base is not None else text


def _path(source: Source, kind: str, base_dir: PathLike | None) -> tuple[str, _DictSource | None]:
    if isinstance(source, Mapping):
        written = _DictSource(source, kind, base_dir)
        return written.path, written
    return os.fspath(source), None


def _relocated(error: ConfigError, written: _DictSource | None) -> ConfigError:
    """An error in a dict source, at DICT_SOURCE without a position (a dict has no lines)."""
    if written is None:
        return error
    if error.file == written.path or error.file == getattr(getattr(written, "base", None), "path", None):
        return ConfigError(DICT_SOURCE, 0, 0, error.key_path, written.shown(error.message))
    return ConfigError(error.file, error.line, error.column, error.key_path, written.shown(error.message),
                       written.shown(str(error)))


def load(source: Source, set: Sets = None, *, base_dir: PathLike | None = None) -> Scenario:
    """Reads, overrides (in order) and validates a scenario, as `shapebench run` does.

    source: a scenario file, or a dict of a scenario file's content (its relative `machine`
    and `program_file` paths then resolve against base_dir, default the current directory).
    set: overrides as --set, e.g. {"controller.pattern.method": "zvd"}.
    Raises ConfigError with the CLI's location and message.
    """
    path, written = _path(source, "scenario", base_dir)
    try:
        scenario = _core.load(path, _set_texts(set))
    except ConfigError as error:
        raise _relocated(error, written) from None
    scenario._source = written  # the temporary file lives as long as the scenario
    return scenario


_core_run = Scenario.run


def _scenario_run(self: Scenario, trace: bool = False) -> Result:
    try:
        return _core_run(self, trace)
    except ConfigError as error:  # a dict source's errors at DICT_SOURCE
        raise _relocated(error, getattr(self, "_source", None)) from None


_scenario_run.__doc__ = _core_run.__doc__
Scenario.run = _scenario_run  # type: ignore[method-assign]


def run(source: Source | Scenario, set: Sets = None, *, trace: bool = False) -> Result:
    """load(source, set).run(trace=trace); a Scenario is run as it is (set must be None)."""
    if isinstance(source, Scenario):
        if set:
            raise ValueError("run(Scenario, set=...): load the scenario with its set instead")
        return source.run(trace=trace)
    return load(source, set).run(trace=trace)


def _jobs(jobs: int | None) -> int:
    """jobs as the CLI's --jobs takes it: None for every core, else a whole number 1..4096
    (0 was taken for "every core" here while the CLI refuses --jobs 0)."""
    if jobs is None:
        return os.cpu_count() or 1
    if isinstance(jobs, bool) or not isinstance(jobs, int) or not 1 <= jobs <= 4096:
        raise ConfigError("", 0, 0, "jobs", f"must be a whole number in [1, 4096] (got {jobs!r})")
    return jobs


@dataclass(frozen=True)
class SweepResult:
    """The rows of a sweep as results.csv's columns (`shapebench sweep`'s results.csv).

    columns: "point" (int), each swept key (float when every value is a number, else str:
    results.csv's text), each kept metric (float; NaN where results.csv is empty: undefined
    or the point failed), "status" ("ok" or "error") and "error" (the message, "" when ok),
    each a numpy array in point order. texts: each swept key's values as results.csv writes
    them. sweep["residual_ratio"] is columns["residual_ratio"].
    """

    name: str
    file: str
    points: int
    keys: list[str]
    metrics: list[str]
    columns: dict[str, np.ndarray]
    texts: dict[str, list[str]]
    note: str = ""

    def __getitem__(self, column: str) -> np.ndarray:
        return self.columns[column]

    @property
    def ok(self) -> np.ndarray:
        """True for the points that ran (status "ok")."""
        return self.columns["status"] == "ok"


def _number_column(texts: list[str]) -> np.ndarray:
    try:
        return np.array([float(text) for text in texts], dtype=float)
    except ValueError:
        return np.array(texts, dtype=str)


def sweep(source: Source, *, jobs: int | None = None, set: Sets = None, force: bool = False,
          base_dir: PathLike | None = None) -> SweepResult:
    """Runs every point of a sweep file (docs/sweeps.md) on `jobs` threads (default: every
    core) and returns its columns; nothing is written. The same points and values as
    `shapebench sweep` (RunPoint), so each column equals results.csv's.

    source: a sweep file, or a dict of one (its `base` a path, relative to base_dir, or a
    scenario dict). force: run a grid of more than 2,000,000 points. Ctrl-C stops it.
    """
    path, written = _path(source, "sweep", base_dir)
    try:
        raw = _core.sweep(path, _set_texts(set), _jobs(jobs), force)
    except ConfigError as error:
        raise _relocated(error, written) from None
    raw_columns = raw["columns"]
    columns: dict[str, np.ndarray] = {}
    texts: dict[str, list[str]] = {}
    for name, values in raw_columns.items():
        if name in raw["keys"]:
            texts[name] = list(values)
            columns[name] = _number_column(values)
        elif name in ("status", "error"):
            shown = [written.shown(v) for v in values] if written is not None else values
            columns[name] = np.array(shown, dtype=str)
        else:
            columns[name] = values
    return SweepResult(name=raw["name"], file=DICT_SOURCE if written else raw["file"], points=raw["points"],
                       keys=list(raw["keys"]), metrics=list(raw["metrics"]), columns=columns, texts=texts,
                       note=written.shown(raw["note"]) if written else raw["note"])


@dataclass(frozen=True)
class Pattern:
    """What `shapebench pattern` shows, as numbers.

    impulse_time_s, impulse_amplitude: the jerk impulses at the start of a shaped phase
    (continuous time, per unit acceleration; method none: the unshaped step 0 s, 1).
    table: the profile table the controller builds from them, alpha_n at table_time_s =
    n * period_s. residuals: at each design frequency {frequency_hz, damping_ratio,
    stepped, profile_table, rounded} (fractions of an unshaped step's residual).
    machine_modes: at each mode of the scenario's machine {axis, mode, frequency_hz,
    damping_ratio, participation, stepped, profile_table}. duration_s: the last impulse's
    time. motion_time_*: the scenario's move with and without the pattern (NaN and
    motion_time_note when it cannot be planned; NaN when the pattern does not shape).
    """

    method: str
    realization: str
    shapes: bool
    design_frequencies_hz: np.ndarray
    impulse_time_s: np.ndarray
    impulse_amplitude: np.ndarray
    period_s: float
    table: np.ndarray
    table_time_s: np.ndarray
    residuals: list[dict[str, float]]
    machine_modes: list[dict[str, Any]]
    duration_s: float
    table_duration_s: float
    motion_time_shaped_s: float
    motion_time_unshaped_s: float
    motion_time_note: str

    @property
    def motion_time_added_s(self) -> float:
        return self.motion_time_shaped_s - self.motion_time_unshaped_s


def pattern(source: Source | Scenario, set: Sets = None, *, base_dir: PathLike | None = None) -> Pattern:
    """The scenario's shaping pattern (`shapebench pattern`): impulses, profile table and the
    residual vibration they leave. A path or dict is loaded as `pattern` loads it: whatever
    the move (a move too short for its pattern is no error here)."""
    if isinstance(source, Scenario):
        if set:
            raise ValueError("pattern(Scenario, set=...): load the scenario with its set instead")
        scenario = source
    else:
        path, written = _path(source, "scenario", base_dir)
        try:
            scenario = _core.load(path, _set_texts(set), plan_move=False)
        except ConfigError as error:
            raise _relocated(error, written) from None
        scenario._source = written
    raw = _core.pattern(scenario)
    table = raw["table"]
    return Pattern(method=raw["method"], realization=raw["realization"], shapes=raw["shapes"],
                   design_frequencies_hz=raw["design_frequencies_hz"],
                   impulse_time_s=raw["impulses"]["time_s"], impulse_amplitude=raw["impulses"]["amplitude"],
                   period_s=raw["period_s"], table=table,
                   table_time_s=np.arange(len(table), dtype=float) * raw["period_s"],
                   residuals=raw["residuals"], machine_modes=raw["machine_modes"], duration_s=raw["duration_s"],
                   table_duration_s=(len(table) - 1) * raw["period_s"],
                   motion_time_shaped_s=raw["motion_time_shaped_s"],
                   motion_time_unshaped_s=raw["motion_time_unshaped_s"], motion_time_note=raw["motion_time_note"])


@dataclass(frozen=True)
class Modes:
    """The machine's modes (`shapebench modes`): one entry per mode, by axis then ascending
    frequency, as numpy arrays; the driven axis' static deflection per m/s^2 and every
    modelled axis'. json: `modes --json`'s object."""

    axis: np.ndarray
    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    participation: np.ndarray
    static_deflection_per_accel_s2: float
    static_deflection_per_accel_s2_by_axis: dict[str, float]
    json: dict[str, Any] = field(repr=False)


def modes(machine: Source | Scenario, set: Sets = None, *, base_dir: PathLike | None = None) -> Modes:
    """The modes of a machine file, of a scenario's machine (a scenario file or a Scenario,
    with its overrides), or of a dict of a machine file's content."""
    sets = _set_texts(set)
    written = None
    if isinstance(machine, Scenario):
        path, sets = machine.source_file, list(machine.sets) + sets
    else:
        path, written = _path(machine, "machine", base_dir)
    try:
        raw = _core.modes(path, sets)
    except ConfigError as error:
        raise _relocated(error, written) from None
    rows = raw["modes"]
    return Modes(axis=np.array([m["axis"] for m in rows], dtype=str),
                 frequency_hz=np.array([m["frequency_hz"] for m in rows], dtype=float),
                 damping_ratio=np.array([m["damping_ratio"] for m in rows], dtype=float),
                 participation=np.array([m["participation"] for m in rows], dtype=float),
                 static_deflection_per_accel_s2=raw["static_deflection_per_accel_s2"],
                 static_deflection_per_accel_s2_by_axis=raw["static_deflection_per_accel_s2_by_axis"], json=raw)


@dataclass(frozen=True)
class Band:
    """The interval of plant frequency / design frequency around 1 where the residual stays
    at or below a level (bench/sensitivity/sensitivity.h); low and high NaN when none."""

    found: bool
    low: float
    high: float
    width: float
    open_low: bool
    open_high: bool


@dataclass(frozen=True)
class SensitivityCurve:
    """One curve: a shaper at one plant damping ratio (realized: its profile table on
    period_s), residual_percent at Sensitivity.ratio, V(1), the 5% band and the level's."""

    name: str
    label: str
    method: str
    damping_ratio: float
    realized: bool
    residual_percent: np.ndarray
    at_design_percent: float
    band_5: Band
    band_level: Band
    impulse_time_s: np.ndarray
    impulse_amplitude: np.ndarray


@dataclass(frozen=True)
class Sensitivity:
    """`shapebench sensitivity`: each shaper's residual vibration against plant frequency /
    design frequency, in percent of an unshaped step's."""

    ratio: np.ndarray
    level: float
    period_s: float | None
    curves: list[SensitivityCurve]


def sensitivity(source: Source, set: Sets = None) -> Sensitivity:
    """Sensitivity curves of a sensitivity file (docs/sweeps.md), or of a dict of one, e.g.
    {"shapers": [{"method": "zvd", "frequency_hz": 25}], "ratio": {"from": 0.5, "to": 1.5,
    "steps": 101}}."""
    path, written = _path(source, "sensitivity", None)
    try:
        raw = _core.sensitivity(path, _set_texts(set))
    except ConfigError as error:
        raise _relocated(error, written) from None
    curves = [SensitivityCurve(name=c["name"], label=c["label"], method=c["method"], damping_ratio=c["damping_ratio"],
                               realized=c["realized"], residual_percent=c["residual_percent"],
                               at_design_percent=c["at_design_percent"], band_5=Band(**c["band_5"]),
                               band_level=Band(**c["band_level"]), impulse_time_s=c["impulses"]["time_s"],
                               impulse_amplitude=c["impulses"]["amplitude"])
              for c in raw["curves"]]
    return Sensitivity(ratio=raw["ratio"], level=raw["level"], period_s=raw["period_s"], curves=curves)


def _ranges(ranges: Mapping[int, tuple[float, float]] | None) -> list[str]:
    return [f"{int(mode)}={float(lo)!r}:{float(hi)!r}" for mode, (lo, hi) in (ranges or {}).items()]


def design(source: Source | Scenario, set: Sets = None, *, band: Mapping[int, tuple[float, float]] | None = None,
           damping: Mapping[int, tuple[float, float]] | None = None, tolerance: float = 0.05,
           derivatives: int = 0, form: str = "profile_table", grid_s: float | None = None,
           margin: float | None = None, registry: bool = True, validate: bool = False,
           base_dir: PathLike | None = None) -> dict[str, Any]:
    """The shortest pattern whose residual vibration stays within `tolerance` over a band
    around each participating mode of the scenario's machine (`shapebench design`,
    docs/design.md): its JSON as a dict, "coefficients" a numpy array (for form "impulses"
    too: one per grid point, the first at t = 0). `band` and `damping` map a mode's index
    to (low, high) as --band and --damping. SolverError (flag DESIGN) when no pattern meets it."""
    sets = _set_texts(set)
    written = None
    if isinstance(source, Scenario):
        path, sets = source.source_file, list(source.sets) + sets
    else:
        path, written = _path(source, "scenario", base_dir)
    try:
        raw = _core.design(path, sets, _ranges(band), _ranges(damping), float(tolerance), int(derivatives), form,
                           None if grid_s is None else float(grid_s), None if margin is None else float(margin),
                           bool(registry), bool(validate))
    except ConfigError as error:
        raise _relocated(error, written) from None
    if "coefficients" not in raw:
        coefficients = np.zeros(int(round(raw["duration_s"] / raw["grid_s"])) + 1)
        for impulse in raw["impulses"]:
            coefficients[int(round(impulse["time_s"] / raw["grid_s"]))] = impulse["amplitude"]
        raw["coefficients"] = coefficients
    raw["coefficients"] = np.asarray(raw["coefficients"], dtype=float)
    return raw


def residual_vibration(impulses: Iterable[tuple[float, float]] | Mapping[str, Any], frequency_hz: float,
                       damping_ratio: float = 0.0) -> float:
    """The residual vibration an impulse sequence leaves in a mode of frequency_hz and
    damping_ratio, as a fraction of an unshaped step's (controller/impulse.h: the function
    the bench's pattern report and sensitivity curves use). impulses: (time_s, amplitude)
    pairs, {"time_s": ..., "amplitude": ...} mappings as a `custom` pattern lists them, or
    {"time_s": [...], "amplitude": [...]}. Validated as the loader validates a mode and a
    `custom` pattern (times >= 0 and strictly ascending, amplitudes with a positive sum;
    frequency finite and > 0, damping in [0, 1)): else ConfigError."""
    times, amplitudes = _impulse_lists(impulses)
    return _core.residual_vibration(times, amplitudes, float(frequency_hz), float(damping_ratio))


def _impulse_lists(impulses: Any) -> tuple[list[float], list[float]]:
    """residual_vibration's impulses as (times, amplitudes); ConfigError naming the impulse
    that has no number where one belongs."""
    def number(value: Any, key: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConfigError("", 0, 0, key, f"must be a number (got {value!r})")
        return float(value)

    if isinstance(impulses, Mapping) and not ({"time_s", "amplitude"} - set(impulses)) and \
            not isinstance(impulses["time_s"], (int, float)):
        times, amplitudes = list(impulses["time_s"]), list(impulses["amplitude"])
        if len(times) != len(amplitudes):
            raise ConfigError("", 0, 0, "impulses",
                              f"time_s and amplitude differ in length ({len(times)} and {len(amplitudes)})")
        return ([number(t, f"impulses.time_s[{i}]") for i, t in enumerate(times)],
                [number(a, f"impulses.amplitude[{i}]") for i, a in enumerate(amplitudes)])
    if isinstance(impulses, (Mapping, str, bytes)):
        raise ConfigError("", 0, 0, "impulses", "must be (time_s, amplitude) pairs, {time_s, amplitude} mappings, "
                          "or {time_s: [...], amplitude: [...]}")
    times, amplitudes = [], []
    for i, impulse in enumerate(impulses):
        at = f"impulses[{i}]"
        if isinstance(impulse, Mapping):
            missing = sorted({"time_s", "amplitude"} - set(impulse))
            extra = sorted(set(impulse) - {"time_s", "amplitude"})
            if missing or extra:
                raise ConfigError("", 0, 0, at, f"needs exactly time_s and amplitude (missing {missing}, unknown {extra})")
            time_s, amplitude = impulse["time_s"], impulse["amplitude"]
        else:
            pair = tuple(impulse) if not isinstance(impulse, (str, bytes)) else ()
            if len(pair) != 2:
                raise ConfigError("", 0, 0, at, f"must be a (time_s, amplitude) pair (got {impulse!r})")
            time_s, amplitude = pair
        times.append(number(time_s, at + ".time_s"))
        amplitudes.append(number(amplitude, at + ".amplitude"))
    return times, amplitudes


def shapers() -> list[dict[str, str]]:
    """Every value of controller.pattern.method: {key, name, description} (docs/shapers.md)."""
    return _core.shapers()
