"""Tests of the Python API beyond the CLI equality: traces, checks, dict sources and
Python values in `set`, pattern, modes, sensitivity, the residual formula, and runs from
several threads. Oracles: the CLI's own files (trace.csv, `check --json`, `modes
--json`, sensitivity.csv) and closed forms (ZVD's impulses, ZV's sensitivity curve)."""

from __future__ import annotations

import csv
import json
import math
import os
import struct
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
import shapebench

from conftest import ROOT, SCENARIOS, run_cli


def bits(value: float) -> bytes:
    return struct.pack("<d", value)


def same_metrics(a: dict, b: dict) -> bool:
    return list(a) == list(b) and all(bits(a[k]) == bits(b[k]) for k in a)


def test_trace_equals_cli_trace_csv(tmp_path):
    """Tests that run(trace=True).trace holds trace.csv's columns, in its order, with its
    numbers bit for bit (trace.csv writes the shortest text that reads back exactly)."""
    done = run_cli("run", "configs/demo.yaml", "--out", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    with open(tmp_path / "out" / "trace.csv", newline="") as file:
        rows = list(csv.reader(file))
    header, rows = rows[0], rows[1:]
    trace = shapebench.load("configs/demo.yaml").run(trace=True).trace
    assert list(trace) == header
    assert len(trace["t_s"]) == len(rows) > 1000
    for c, name in enumerate(header):
        column = trace[name]
        if name == "block":
            assert column.dtype.kind == "i"
            assert column.tolist() == [int(row[c]) for row in rows]
        else:
            assert column.tobytes() == np.array([float(row[c]) for row in rows]).tobytes(), name


def test_trace_is_only_recorded_when_asked_and_metrics_do_not_depend_on_it():
    """Tests that trace is None by default and that the metrics are the same bit for bit
    with and without it."""
    scenario = shapebench.load("configs/scenarios/pocket_corner.yaml")
    plain = scenario.run()
    traced = scenario.run(trace=True)
    assert plain.trace is None
    assert traced.trace is not None
    assert same_metrics(plain.metrics, traced.metrics)


def test_checks_equal_cli_check_json():
    """Tests that Result.checks is `check --json`'s results for the same scenario."""
    path = "configs/scenarios/method1.yaml"
    done = run_cli("check", path, "--json")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)["files"][0]["results"]
    checks = shapebench.load(path).run().checks
    assert checks == expected
    assert len(checks) >= 2 and all(check["passed"] for check in checks)


def test_failed_checks_carry_the_cli_message():
    """Tests that a failing check (method1 unshaped, the README's example) reads as `check`."""
    path = "configs/scenarios/method1.yaml"
    done = run_cli("check", path, "--json", "--set", "controller.pattern.method=none")
    assert done.returncode == 1
    expected = json.loads(done.stdout)["files"][0]["results"]
    checks = shapebench.load(path, set={"controller.pattern.method": "none"}).run().checks
    assert checks == expected
    assert not any(check["passed"] for check in checks)


def test_python_values_in_set_equal_the_cli_yaml_text():
    """Tests that a list of dicts in `set` (a custom shaper's impulses) runs as the same
    YAML text on the CLI's --set, bit for bit."""
    impulses = [{"time_s": 0.0, "amplitude": 0.5}, {"time_s": 0.02, "amplitude": 0.5}]
    done = run_cli("run", "configs/demo.yaml", "--json", "--set", "controller.pattern.method=custom",
                   "--set", "controller.pattern.impulses=[{time_s: 0, amplitude: 0.5}, {time_s: 0.02, amplitude: 0.5}]")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    metrics = shapebench.load("configs/demo.yaml", set={"controller.pattern.method": "custom",
                                                        "controller.pattern.impulses": impulses}).run().metrics
    for name, value in metrics.items():
        if expected[name] is None:
            assert math.isnan(value)
        else:
            assert bits(value) == bits(float(expected[name])), name


def test_scenario_dict_runs_as_its_file():
    """Tests that a scenario given as a dict (sdof_method1.yaml's content written out by
    hand, its checks left out) gives the file's metrics bit for bit."""
    content = {
        "machine": {"modes": [{"frequency_hz": 25.0, "damping_ratio": 0.0, "gain": 1.0}]},
        "drive": {"type": "kinematic"},
        "controller": {"period_s": 0.001, "feed_mm_min": 30000, "accel_time_s": 0.3,
                       "pattern": {"method": 1, "mode": "both", "frequency_hz": 25.0}},
        "move": {"distance_mm": 213},
        "integrator": {"method": "exact"},
    }
    from_dict = shapebench.load(content)
    assert from_dict.name == "scenario"
    yaml_text = from_dict.yaml()
    assert "frequency_hz" in yaml_text
    expected = shapebench.load("configs/scenarios/sdof_method1.yaml").run().metrics
    if not same_metrics(from_dict.run().metrics, expected):
        pytest.fail("the dict differs from configs/scenarios/sdof_method1.yaml: " + yaml_text)


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.name)
def test_every_shipped_scenario_as_a_dict_runs_as_its_file(path):
    """Tests that each shipped scenario read by PyYAML into a dict (relative machine and
    program files resolved against base_dir) runs bit for bit as the file."""
    yaml = pytest.importorskip("yaml")
    content = yaml.safe_load(path.read_text())
    from_dict = shapebench.load(content, base_dir=path.parent).run().metrics
    assert same_metrics(from_dict, shapebench.load(path).run().metrics)


def test_sweep_dict_with_a_scenario_dict_as_base():
    """Tests that a sweep given as a dict, its base a scenario dict, runs its grid: the
    frequency column numeric, method texts as written, one row per point, every point ok."""
    base = {"machine": {"modes": [{"frequency_hz": 25.0}]},
            "controller": {"feed_mm_min": 30000, "accel_time_s": 0.3, "pattern": {"method": 1, "frequency_hz": 25}},
            "move": {"distance_mm": 200}}
    result = shapebench.sweep({"base": base, "grid": {"controller.pattern.method": ["none", 1],
                                                        "machine.modes[0].frequency_hz": {"from": 20, "to": 30,
                                                                                          "steps": 3}},
                               "metrics": ["peak_ratio"]}, jobs=2)
    assert result.points == 6
    assert result.texts["controller.pattern.method"] == ["none"] * 3 + ["1"] * 3
    assert result["machine.modes[0].frequency_hz"].tolist() == [20.0, 25.0, 30.0] * 2
    assert result.ok.all()
    # Unshaped, a long acceleration step peaks at twice the static deflection; method 1
    # designed for 25 Hz keeps the 25 Hz mode at the static (seed 004 para. 38).
    assert result["peak_ratio"][1] == pytest.approx(2.0, abs=1e-3)
    assert result["peak_ratio"][4] == pytest.approx(1.0, abs=1e-3)


def test_sweep_point_errors_are_rows_not_exceptions(tmp_path):
    """Tests that a point whose value is refused is a row with status error and the CLI's
    message, its metrics NaN, the other points ok."""
    sweep = tmp_path / "s.yaml"
    sweep.write_text(f"base: {ROOT / 'configs' / 'scenarios' / 'method3.yaml'}\n"
                     "grid:\n  controller.pattern.k1: [0.6, 2]\n")
    done = run_cli("sweep", sweep, "--jobs", "1", "--out", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    with open(tmp_path / "out" / "results.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    result = shapebench.sweep(sweep, jobs=1)
    assert result["status"].tolist() == ["ok", "error"]
    assert result["error"].tolist() == [row["error"] for row in rows]
    assert "controller.pattern.k1" in result["error"][1]
    assert math.isnan(result["peak_ratio"][1]) and not math.isnan(result["peak_ratio"][0])


def test_pattern_of_zvd_is_its_closed_form():
    """Tests that pattern() of an undamped ZVD at 25 Hz gives its impulses 1/4, 1/2, 1/4 at
    0, T/2, T (T = 40 ms; to 1e-15 s and 1e-15: the design's own rounding), a profile table
    on the period grid summing to 1, and residuals at the design frequency below 1e-12."""
    p = shapebench.pattern("configs/demo.yaml", set={"controller.pattern.method": "zvd",
                                                     "controller.pattern.frequency_hz": 25})
    assert p.method == "zvd" and p.shapes
    assert np.allclose(p.impulse_time_s, [0.0, 0.02, 0.04], rtol=0, atol=1e-15)
    assert np.allclose(p.impulse_amplitude, [0.25, 0.5, 0.25], rtol=0, atol=1e-15)
    assert p.period_s == 0.001 and p.table_time_s[1] == 0.001
    assert abs(p.table.sum() - 1.0) < 1e-12
    assert p.duration_s == pytest.approx(0.04, abs=1e-15)
    assert p.residuals[0]["frequency_hz"] == 25.0
    assert p.residuals[0]["stepped"] < 1e-12 and p.residuals[0]["profile_table"] < 1e-12
    assert p.residuals[0]["stepped"] == shapebench.residual_vibration(
        {"time_s": p.impulse_time_s, "amplitude": p.impulse_amplitude}, 25.0)
    assert p.machine_modes and p.machine_modes[0]["axis"] in ("x", "y", "z")
    assert p.motion_time_added_s == pytest.approx(0.04, abs=0.0015)  # the shaper's length, on the grid


def test_pattern_table_equals_the_cli_report():
    """Tests that pattern()'s profile table is the one `shapebench pattern` lists (%.9g: to
    half a unit of the 9th digit, 5e-9 relative)."""
    done = run_cli("pattern", "configs/scenarios/um_zv.yaml")
    assert done.returncode == 0, done.stderr
    p = shapebench.pattern("configs/scenarios/um_zv.yaml")
    listed = 0
    lines = done.stdout.split("profile table on the")[1].split("\n\n")[0].splitlines()[2:]
    for line in lines:
        fields = line.split()
        if len(fields) == 3 and fields[0].isdigit():
            n, alpha = int(fields[0]), float(fields[2])
            assert abs(p.table[n] - alpha) <= 5e-9 * abs(alpha), (n, p.table[n], alpha)
            listed += 1
    assert listed >= 3


def test_modes_equal_cli_modes_json():
    """Tests that modes() of the moving-column machine is `modes --json`'s object, its
    arrays that object's columns."""
    path = "configs/machines/moving_column.yaml"
    done = run_cli("modes", path, "--json")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    m = shapebench.modes(path)
    assert m.json == expected
    assert m.frequency_hz.tolist() == [row["frequency_hz"] for row in expected["modes"]]
    assert m.axis.tolist() == [row["axis"] for row in expected["modes"]]
    assert m.static_deflection_per_accel_s2 == expected["static_deflection_per_accel_s2"]


def test_design_equals_cli_design_json():
    """Tests that design() of the gantry (18 and 55 Hz, +/-10%, 5%) is `design --json`'s
    object, its coefficients a numpy array of the same doubles summing to 1, and that the
    impulses form gives them one per grid point too."""
    path = "configs/scenarios/gantry_zvd.yaml"
    done = run_cli("design", path, "--json", "--no-registry")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    d = shapebench.design(path, registry=False)
    assert isinstance(d["coefficients"], np.ndarray)
    assert [bits(x) for x in d["coefficients"]] == [bits(x) for x in expected["coefficients"]]
    assert d["duration_s"] == expected["duration_s"]
    assert d["bands"] == expected["bands"]
    assert d["coefficients"].sum() == pytest.approx(1.0, abs=1e-12)
    impulses = shapebench.design(path, band={0: (17.0, 19.0)}, form="impulses", grid_s=0.0005, registry=False)
    assert len(impulses["bands"]) == 1
    assert len(impulses["coefficients"]) == round(impulses["duration_s"] / 0.0005) + 1
    assert impulses["coefficients"].sum() == pytest.approx(1.0, abs=1e-12)


def test_design_errors_are_the_clis():
    """Tests that a bad band is a ConfigError naming --band, and a specification no pattern
    meets a SolverError with flag DESIGN."""
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.design("configs/scenarios/gantry_zvd.yaml", band={5: (1.0, 2.0)})
    assert "--band" in str(raised.value)
    with pytest.raises(shapebench.SolverError) as solver:
        shapebench.design("configs/scenarios/gantry_zvd.yaml", band={0: (15.0, 25.0)}, tolerance=0.0, margin=0.5,
                          registry=False)
    assert solver.value.flag_name == "DESIGN"


def test_modes_of_a_scenario_take_its_overrides():
    """Tests that modes(Scenario) reads the scenario's machine with its set: a 30 Hz mode."""
    scenario = shapebench.load("configs/scenarios/sdof_method1.yaml", set={"machine.modes[0].frequency_hz": 30})
    assert shapebench.modes(scenario).frequency_hz.tolist() == pytest.approx([30.0], rel=1e-12)


def test_sensitivity_of_zv_is_its_closed_form():
    """Tests that ZV's undamped curve is 100 |cos(pi r / 2)| % (to 1e-10 %, rounding)."""
    s = shapebench.sensitivity({"shapers": [{"method": "zv", "frequency_hz": 25}],
                                "ratio": {"from": 0.5, "to": 1.5, "steps": 101}})
    assert len(s.curves) == 1 and len(s.ratio) == 101
    expected = 100 * np.abs(np.cos(np.pi * s.ratio / 2))
    assert np.max(np.abs(s.curves[0].residual_percent - expected)) < 1e-10
    # The 5% band: |cos(pi r / 2)| <= 0.05 around r = 1, width 4 asin(0.05) / pi.
    assert s.curves[0].band_5.width == pytest.approx(4 * math.asin(0.05) / math.pi, abs=1e-9)


def test_sensitivity_equals_cli_csv(tmp_path):
    """Tests that the shipped sensitivity file's curves equal the CLI's sensitivity.csv
    (written %.10g: to 1e-9 relative, or 1e-12 % absolute near zero)."""
    path = "configs/sensitivity/shapers.yaml"
    done = run_cli("sensitivity", path, "--out", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    with open(tmp_path / "out" / "sensitivity.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    s = shapebench.sensitivity(path)
    assert [c.name for c in s.curves] == list(rows[0])[1:]
    for curve in s.curves:
        csv_values = np.array([float(row[curve.name]) for row in rows])
        assert np.all(np.abs(curve.residual_percent - csv_values) <= 1e-9 * np.abs(csv_values) + 1e-12), curve.name


def test_residual_vibration_of_simple_sequences():
    """Tests residual_vibration against closed forms: one impulse leaves all (1), ZV's two
    halves half a period apart leave nothing at the design frequency and |cos(pi r/2)| off it."""
    assert shapebench.residual_vibration([(0.0, 1.0)], 25.0) == pytest.approx(1.0, abs=1e-15)
    zv = [(0.0, 0.5), (0.02, 0.5)]
    assert shapebench.residual_vibration(zv, 25.0) < 1e-15
    assert shapebench.residual_vibration(zv, 30.0) == pytest.approx(abs(math.cos(math.pi * 1.2 / 2)), abs=1e-14)
    with pytest.raises(ValueError):
        shapebench.residual_vibration({"time_s": [0.0], "amplitude": [0.5, 0.5]}, 25.0)


ZV = [(0.0, 0.5), (0.02, 0.5)]


@pytest.mark.parametrize("impulses, frequency_hz, damping_ratio, key", [
    (ZV, float("nan"), 0.0, "frequency_hz"),
    (ZV, -30.0, 0.0, "frequency_hz"),
    (ZV, 25.0, -1.0, "damping_ratio"),
    (ZV, 25.0, 5.0, "damping_ratio"),
    ([(0.0, 0.5), (0.02, -0.5)], 25.0, 0.0, "impulses"),
    ([(0.5, 0.0), (0.5, 0.02)], 25.0, 0.0, "impulses[1].time_s"),
    ([(-0.01, 1.0)], 25.0, 0.0, "impulses[0].time_s"),
    ([], 25.0, 0.0, "impulses"),
    ([{"time_s": 0.0}], 25.0, 0.0, "impulses[0]"),
    ([(0.0, "a")], 25.0, 0.0, "impulses[0].amplitude"),
    ([(0.0, 0.5, 1.0)], 25.0, 0.0, "impulses[0]"),
])
def test_residual_vibration_refuses_what_the_loader_refuses(impulses, frequency_hz, damping_ratio, key):
    """Tests that residual_vibration raises ConfigError naming the argument, as the loader
    refuses a mode and a custom pattern: NaN or negative frequency (was nan, and -30 Hz
    differed from +30 Hz), damping -1 or 5 (145.69 and nan), amplitudes summing to 0 (inf),
    ZV's pairs swapped to (amplitude, time_s) (times not ascending), a negative time, no
    impulse, a mapping or tuple that is not one impulse, a non-number."""
    with pytest.raises(shapebench.ConfigError) as error:
        shapebench.residual_vibration(impulses, frequency_hz, damping_ratio)
    assert error.value.key_path == key, str(error.value)


def test_residual_vibration_takes_the_custom_patterns_form():
    """Tests that {time_s, amplitude} mappings, as a custom pattern lists its impulses, give
    the pairs' residual bit for bit, and that the loader refuses the swapped ZV pairs at the
    same impulse as residual_vibration does."""
    mappings = [{"time_s": t, "amplitude": a} for t, a in ZV]
    for frequency_hz in (20.0, 25.0, 31.0):
        assert shapebench.residual_vibration(mappings, frequency_hz, 0.05) == \
            shapebench.residual_vibration(ZV, frequency_hz, 0.05)
    swapped = [{"time_s": a, "amplitude": t} for t, a in ZV]
    scenario = {"machine": {"modes": [{"frequency_hz": 25.0}]},
                "controller": {"pattern": {"method": "custom", "impulses": swapped}},
                "move": {"distance_mm": 100}}
    with pytest.raises(shapebench.ConfigError) as loaded:
        shapebench.load(scenario)
    assert loaded.value.key_path.endswith("impulses[1].time_s"), str(loaded.value)


@pytest.mark.parametrize("jobs", [0, -1, 4097, 1.5, True])
def test_sweep_refuses_the_jobs_the_cli_refuses(jobs):
    """Tests that sweep(jobs=...) takes what --jobs takes (1..4096, or None for every core):
    jobs=0 ran on every core while the CLI refuses --jobs 0 (issue 32 item 16)."""
    with pytest.raises(shapebench.ConfigError) as error:
        shapebench.sweep(ROOT / "configs" / "sweeps" / "natural_period.yaml", jobs=jobs)
    assert error.value.key_path == "jobs", str(error.value)


def test_runs_from_several_threads_equal_serial_runs():
    """Tests that four threads running scenarios at once get the serial runs' metrics bit
    for bit (a scenario is shared by the threads that run it)."""
    scenarios = [shapebench.load(p) for p in SCENARIOS[:4]] * 2
    serial = [s.run().metrics for s in scenarios]
    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda s: s.run().metrics, scenarios))
    assert all(same_metrics(a, b) for a, b in zip(serial, parallel))


def test_the_gil_is_released_while_a_sweep_runs():
    """Tests that Python code keeps running while a sweep simulates in another thread: the
    main thread gets at least 20 turns of a 1 ms sleep meanwhile (none if the sweep held the
    GIL: a blocked interpreter runs no other thread). Not a timing comparison."""
    done = threading.Event()

    def work():
        shapebench.sweep("configs/sweeps/natural_period.yaml", jobs=1)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    turns = 0
    while not done.is_set():
        time.sleep(0.001)
        turns += 1
    thread.join()
    assert turns >= 20


def test_shapers_and_version():
    """Tests that shapers() lists the registry (custom among them) and __version__ is set."""
    keys = [s["key"] for s in shapebench.shapers()]
    assert {"none", "1", "zv", "zvd", "ei", "custom"} <= set(keys)
    assert shapebench.__version__


def test_set_numbers_reach_the_bench_exactly():
    """Tests that a float in `set` (numpy's too) reaches the bench as the same double: the
    design frequency 0.1 + 0.2 + 25 comes back as pattern_frequency_hz bit for bit."""
    frequency = 0.1 + 0.2 + 25.0  # 25.3 plus an ulp: no short decimal text
    for value in (frequency, np.float64(frequency)):
        metrics = shapebench.load("configs/scenarios/sdof_method1.yaml",
                                  set={"controller.pattern.frequency_hz": value}).run().metrics
        assert bits(metrics["pattern_frequency_hz"]) == bits(frequency)


def test_ctrl_c_stops_a_sweep_between_points():
    """Tests that SIGINT during a 100,000-point sweep raises KeyboardInterrupt in the
    calling thread (the sweep would otherwise run to its end and say so)."""
    script = """
import os, signal, threading, time, shapebench
signal.signal(signal.SIGINT, signal.default_int_handler)
threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
try:
    shapebench.sweep({"base": "configs/scenarios/sdof_method1.yaml", "metrics": ["peak_ratio"],
                      "grid": {"machine.modes[0].frequency_hz": {"from": 15, "to": 35, "steps": 100000}}}, jobs=2)
    print("finished")
except KeyboardInterrupt:
    print("interrupted")
"""
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(shapebench.__file__))))
    done = subprocess.run([sys.executable, "-c", script], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.stdout.strip() == "interrupted", (done.stdout, done.stderr)


def test_ctrl_c_stops_a_sweep_on_a_worker_thread():
    """Tests that SIGINT stops a 1,000,000-point sweep running on a thread other than the
    main one, with KeyboardInterrupt in that thread (Python looks at signals on its main
    thread only: the sweep ran to its end, issue 32 item 16). SIGINT is sent until the
    thread ends, so one arrives while the sweep runs; the main thread's handler only counts."""
    script = """
import os, signal, threading, shapebench
signal.signal(signal.SIGINT, lambda *args: None)
outcome = []
def work():
    try:
        shapebench.sweep({"base": "configs/scenarios/sdof_method1.yaml", "metrics": ["peak_ratio"],
                          "grid": {"machine.modes[0].frequency_hz": {"from": 15, "to": 35, "steps": 1000000}}},
                         jobs=1)
        outcome.append("finished")
    except KeyboardInterrupt:
        outcome.append("interrupted")
worker = threading.Thread(target=work)
worker.start()
while worker.is_alive():
    os.kill(os.getpid(), signal.SIGINT)
    worker.join(0.05)
print(outcome[0])
"""
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(shapebench.__file__))))
    done = subprocess.run([sys.executable, "-c", script], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.stdout.strip() == "interrupted", (done.stdout, done.stderr)


def test_stubs_and_docstrings_cover_the_api():
    """Tests that the package ships its stubs and py.typed beside the module, that the stub
    declares every public name and every public member of Scenario and Result, and that each
    of them has a docstring (what an editor completes and shows)."""
    import ast
    package = os.path.dirname(os.path.abspath(shapebench.__file__))
    for name in ("__init__.pyi", "_errors.pyi", "py.typed"):
        assert os.path.exists(os.path.join(package, name)), name
    stub = ast.parse(open(os.path.join(package, "__init__.pyi")).read())
    declared = set()
    members: dict[str, set] = {}
    for node in stub.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            declared.add(node.name)
            if isinstance(node, ast.ClassDef):
                members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)} | {
                    n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        elif isinstance(node, ast.ImportFrom):
            declared.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.Assign):
            declared.update(t.id for t in node.targets if isinstance(t, ast.Name))
    assert set(shapebench.__all__) <= declared
    for cls in (shapebench.Scenario, shapebench.Result):
        public = {name for name in dir(cls) if not name.startswith("_")}
        assert public <= members[cls.__name__], public - members[cls.__name__]
        for name in public:
            assert getattr(cls, name).__doc__, f"{cls.__name__}.{name}"
    for name in shapebench.__all__:
        assert getattr(shapebench, name).__doc__, name
