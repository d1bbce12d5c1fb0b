"""Tests that errors raised in Python carry the CLI's location and message: ConfigError's
str() is the CLI's exit-2 line without "error: ", its attributes the parts of that line;
SolverError's str() is the exit-3 line's."""

from __future__ import annotations

import pickle
import re

import pytest
import shapebench

from conftest import ROOT, run_cli

LOCATED = re.compile(r"^(?P<file>.*?):(?P<line>\d+):(?P<column>\d+): (?P<key>[^:]+): (?P<message>.*)$")


def cli_error(*args) -> str:
    """The CLI's error line without "error: " (it must exit 2)."""
    done = run_cli(*args)
    assert done.returncode == 2, (done.returncode, done.stderr)
    line = done.stderr.splitlines()[0]
    assert line.startswith("error: ")
    return line[len("error: "):]


def test_config_error_in_a_file_equals_the_cli_line(tmp_path):
    """Tests that a bad value in a scenario file raises ConfigError whose str() is the CLI's
    exit-2 line minus "error: ", with file, line, column, key path and message as
    attributes (read back from that line)."""
    bad = tmp_path / "bad.yaml"
    text = (ROOT / "configs" / "scenarios" / "method3.yaml").read_text()
    bad.write_text(re.sub(r"k1: [0-9.]+", "k1: 2", text))
    assert "k1: 2" in bad.read_text()
    expected = cli_error("run", bad)
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.load(bad)
    error = raised.value
    assert str(error) == expected
    parts = LOCATED.match(expected)
    assert parts, expected
    assert error.file == parts["file"] == str(bad)
    assert (error.line, error.column) == (int(parts["line"]), int(parts["column"]))
    assert error.key_path == parts["key"] == "controller.pattern.k1"
    assert error.message == parts["message"]
    assert isinstance(error, ValueError) and isinstance(error, shapebench.Error)


def test_config_error_of_a_set_equals_the_cli_line():
    """Tests that the README's bad --set (method 3 with k1 = 2) raises ConfigError at
    --set:2:1 with the CLI's text, set given as a dict of Python values."""
    expected = cli_error("run", "configs/demo.yaml", "--set", "controller.pattern.method=3",
                         "--set", "controller.pattern.k1=2")
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.load("configs/demo.yaml", set={"controller.pattern.method": 3, "controller.pattern.k1": 2})
    assert str(raised.value) == expected
    assert (raised.value.file, raised.value.line, raised.value.column) == ("--set", 2, 1)
    assert raised.value.key_path == "controller.pattern.k1"


@pytest.mark.parametrize("sets", [["controller.pattern.method"], ["=3"], ["controller.pattern.methd=3"]])
def test_malformed_and_unknown_sets_equal_the_cli_line(sets):
    """Tests that a --set without '=', without a key, or naming no key raises the CLI's
    error text (given as "KEY=VALUE" strings, as on the command line)."""
    args = [a for text in sets for a in ("--set", text)]
    expected = cli_error("run", "configs/demo.yaml", *args)
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.load("configs/demo.yaml", set=sets)
    assert str(raised.value) == expected


def test_missing_file_has_no_position():
    """Tests that a file that cannot be read is a ConfigError without position (line 0),
    with the CLI's text."""
    expected = cli_error("run", "configs/no_such.yaml")
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.load("configs/no_such.yaml")
    assert str(raised.value) == expected
    assert (raised.value.line, raised.value.column) == (0, 0)


def test_sweep_error_equals_the_cli_line(tmp_path):
    """Tests that a sweep file's error (a swept key the scenario does not have) is the CLI's."""
    sweep = tmp_path / "bad_sweep.yaml"
    sweep.write_text(f"base: {ROOT / 'configs' / 'demo.yaml'}\ngrid:\n  controller.pattern.nope: [1, 2]\n")
    expected = cli_error("sweep", sweep, "--out", tmp_path / "out")
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.sweep(sweep, jobs=1)
    assert str(raised.value) == expected
    assert raised.value.line == 3


def test_solver_failure_raises_solver_error_with_the_cli_text():
    """Tests that CVODE starved of steps raises SolverError whose str() is the CLI's exit-3
    line minus "error: " ("solver failed: CV_...: ...") and whose flag_name is the flag."""
    starve = {"integrator.method": "cvode", "integrator.max_num_steps": 1, "integrator.rtol": 1e-10}
    args = [a for key, value in starve.items() for a in ("--set", f"{key}={value}")]
    done = run_cli("run", "tests/bench/data/shaped_method1.yaml", *args)
    assert done.returncode == 3, done.stderr
    expected = done.stderr.splitlines()[0][len("error: "):]
    with pytest.raises(shapebench.SolverError) as raised:
        shapebench.load("tests/bench/data/shaped_method1.yaml", set=starve).run()
    assert str(raised.value) == expected
    assert re.match(r"CV_[A-Z_]+$", raised.value.flag_name)
    assert expected == f"solver failed: {raised.value.flag_name}: {raised.value.message}"


def test_dict_source_errors_name_the_dict_without_position():
    """Tests that an error in a scenario given as a dict is reported at "<dict>" with its
    key path and the CLI's message, without a line (a dict has none)."""
    with pytest.raises(shapebench.ConfigError) as raised:
        shapebench.load({"controller": {"pattern": {"method": 3, "k1": 2}}, "move": {"distance_mm": 200}})
    error = raised.value
    assert (error.file, error.line, error.column) == ("<dict>", 0, 0)
    assert error.key_path == "controller.pattern.k1"
    assert str(error) == f"<dict>: controller.pattern.k1: {error.message}"
    assert error.message.startswith("must be in [0.5, 1] for method 3")


def test_errors_survive_pickling():
    """Tests that both errors pickle (multiprocessing hands them between processes)."""
    config = shapebench.ConfigError("a.yaml", 3, 5, "x.y", "bad")
    assert str(config) == "a.yaml:3:5: x.y: bad"
    copy = pickle.loads(pickle.dumps(config))
    assert (str(copy), copy.file, copy.line, copy.column, copy.key_path, copy.message) == (
        str(config), "a.yaml", 3, 5, "x.y", "bad")
    solver = pickle.loads(pickle.dumps(shapebench.SolverError("CV_X", "why")))
    assert (str(solver), solver.flag_name) == ("solver failed: CV_X: why", "CV_X")
