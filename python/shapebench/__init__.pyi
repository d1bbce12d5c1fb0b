"""Type stubs of the shapebench package (docs/python.md)."""

import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, TypedDict, Union

import numpy as np
import numpy.typing as npt

from ._errors import ConfigError as ConfigError
from ._errors import Error as Error
from ._errors import SolverError as SolverError

__version__: str

PathLike = Union[str, os.PathLike[str]]
Source = Union[PathLike, Mapping[str, Any]]
# {"controller.pattern.k1": 0.6} or ["controller.pattern.k1=0.6"]: the CLI's --set, in order.
Sets = Union[Mapping[str, Any], Iterable[str], None]
FloatArray = npt.NDArray[np.float64]

DICT_SOURCE: str

class ResidualMode(TypedDict):
    frequency_hz: float
    damping_ratio: float
    amplitude_m: float | None

CheckBandResult = TypedDict("CheckBandResult", {
    "key": str, "from": float | None, "to": float | None, "worst_value": float | None,
    "worst_at": float | None, "runs": int, "text": str})

class CheckResult(TypedDict, total=False):
    metric: str
    value: float | None
    bound: str
    passed: bool
    message: str
    band: CheckBandResult

class Scenario:
    """A loaded, validated scenario (shapebench.load). Immutable: load again with other
    `set` values for a variant. Safe to run from several threads at once."""

    @property
    def name(self) -> str:
        """The scenario's name (`name:`, else the file's stem)."""
    @property
    def source_file(self) -> str:
        """The file it was read from."""
    @property
    def sets(self) -> list[str]:
        """The overrides applied, as the CLI's --set texts "KEY=VALUE", in order."""
    def run(self, trace: bool = False) -> Result:
        """Simulates the scenario (the GIL released) and returns its Result. trace=True
        records the trace (every output substep; the metrics are the same bit for bit
        either way)."""
    def yaml(self) -> str:
        """The scenario's YAML as a run reads it: the file, its machine file spliced in,
        the overrides applied."""

class Result:
    """What Scenario.run() gives."""

    @property
    def metrics(self) -> dict[str, float]:
        """Every metric (docs/metrics.md) in table order, SI units, as float: the doubles
        `run --json` prints; NaN where it prints null (not defined for this run);
        stroke_alarm 0.0 or 1.0 where it prints false or true."""
    @property
    def residual_modes(self) -> list[ResidualMode]:
        """`run --json`'s residual_modes: per pole of the plant, ascending frequency."""
    @property
    def integrator_rtol_used(self) -> float:
        """`run --json`'s integrator_rtol_used: the rtol CVODE ran with; NaN where none ran."""
    @property
    def trace(self) -> dict[str, np.ndarray] | None:
        """With run(trace=True): trace.csv's columns as numpy arrays (t_s, ..., block as
        int, planned_feed_mm_min), every sample; else None."""
    @property
    def checks(self) -> list[CheckResult]:
        """The scenario's checks evaluated on this run, as `check --json` gives each.
        Evaluated on first use (a band check runs the scenario over its band)."""
    @property
    def warnings(self) -> list[str]:
        """The warnings the CLI prints on stderr for this run."""
    def json(self) -> str:
        """The text `shapebench run FILE --json` prints (without its final newline)."""

def load(source: Source, set: Sets = None, *, base_dir: PathLike | None = None) -> Scenario:
    """Reads, overrides (in order) and validates a scenario, as `shapebench run` does.
    source: a scenario file, or a dict of a scenario file's content (its relative
    `machine` and `program_file` paths resolve against base_dir, default the current
    directory). Raises ConfigError with the CLI's location and message."""

def run(source: Source | Scenario, set: Sets = None, *, trace: bool = False) -> Result:
    """load(source, set).run(trace=trace)."""

@dataclass(frozen=True)
class SweepResult:
    """The rows of a sweep as results.csv's columns: "point", each swept key (float when
    every value is a number, else str), each kept metric (float, NaN where results.csv is
    empty), "status", "error"; numpy arrays in point order."""

    name: str
    file: str
    points: int
    keys: list[str]
    metrics: list[str]
    columns: dict[str, np.ndarray]
    texts: dict[str, list[str]]
    note: str = ...
    def __getitem__(self, column: str) -> np.ndarray: ...
    @property
    def ok(self) -> npt.NDArray[np.bool_]:
        """True for the points that ran (status "ok")."""

def sweep(source: Source, *, jobs: int | None = None, set: Sets = None, force: bool = False,
          base_dir: PathLike | None = None) -> SweepResult:
    """Runs every point of a sweep file on `jobs` threads (default: every core) and returns
    its columns (each equal to results.csv's); nothing is written. Ctrl-C stops it."""

class PatternResidual(TypedDict):
    frequency_hz: float
    damping_ratio: float
    stepped: float
    profile_table: float
    rounded: float

class ModeResidual(TypedDict):
    axis: str
    mode: int
    frequency_hz: float
    damping_ratio: float
    participation: float
    stepped: float
    profile_table: float

@dataclass(frozen=True)
class Pattern:
    """What `shapebench pattern` shows, as numbers: the impulses, the profile table
    (alpha_n at n * period_s), the residuals at the design frequencies and at the
    machine's modes, the duration and the motion time with and without the pattern."""

    method: str
    realization: str
    shapes: bool
    design_frequencies_hz: FloatArray
    impulse_time_s: FloatArray
    impulse_amplitude: FloatArray
    period_s: float
    table: FloatArray
    table_time_s: FloatArray
    residuals: list[PatternResidual]
    machine_modes: list[ModeResidual]
    duration_s: float
    table_duration_s: float
    motion_time_shaped_s: float
    motion_time_unshaped_s: float
    motion_time_note: str
    @property
    def motion_time_added_s(self) -> float: ...

def pattern(source: Source | Scenario, set: Sets = None, *, base_dir: PathLike | None = None) -> Pattern:
    """The scenario's shaping pattern (`shapebench pattern`)."""

@dataclass(frozen=True)
class Modes:
    """The machine's modes (`shapebench modes`), one entry per mode, by axis then frequency."""

    axis: np.ndarray
    frequency_hz: FloatArray
    damping_ratio: FloatArray
    participation: FloatArray
    static_deflection_per_accel_s2: float
    static_deflection_per_accel_s2_by_axis: dict[str, float]
    json: dict[str, Any]

def modes(machine: Source | Scenario, set: Sets = None, *, base_dir: PathLike | None = None) -> Modes:
    """The modes of a machine file, a scenario's machine, or a dict of a machine file."""

@dataclass(frozen=True)
class Band:
    found: bool
    low: float
    high: float
    width: float
    open_low: bool
    open_high: bool

@dataclass(frozen=True)
class SensitivityCurve:
    name: str
    label: str
    method: str
    damping_ratio: float
    realized: bool
    residual_percent: FloatArray
    at_design_percent: float
    band_5: Band
    band_level: Band
    impulse_time_s: FloatArray
    impulse_amplitude: FloatArray

@dataclass(frozen=True)
class Sensitivity:
    ratio: FloatArray
    level: float
    period_s: float | None
    curves: list[SensitivityCurve]

def sensitivity(source: Source, set: Sets = None) -> Sensitivity:
    """Sensitivity curves of a sensitivity file or a dict of one (`shapebench sensitivity`)."""

def design(source: Source | Scenario, set: Sets = None, *, band: Mapping[int, tuple[float, float]] | None = None,
           damping: Mapping[int, tuple[float, float]] | None = None, tolerance: float = 0.05,
           derivatives: int = 0, form: str = "profile_table", grid_s: float | None = None,
           margin: float | None = None, registry: bool = True, validate: bool = False,
           base_dir: PathLike | None = None) -> dict[str, Any]:
    """The shortest pattern within `tolerance` over each mode's band (`shapebench design`):
    its JSON as a dict, "coefficients" a numpy array."""

def residual_vibration(impulses: Iterable[tuple[float, float]] | Mapping[str, Any], frequency_hz: float,
                       damping_ratio: float = 0.0) -> float:
    """The residual vibration an impulse sequence leaves in a mode, as a fraction of an
    unshaped step's (controller/impulse.h)."""

class ShaperInfo(TypedDict):
    key: str
    name: str
    description: str

def shapers() -> list[ShaperInfo]:
    """Every value of controller.pattern.method (docs/shapers.md)."""
