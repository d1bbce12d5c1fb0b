"""Tests that the Python module gives the CLI's numbers to the last bit: every shipped
scenario's metrics against `shapebench run FILE --json`, every shipped sweep's columns
against its results.csv. The oracle is the CLI binary (a separate process)."""

from __future__ import annotations

import csv
import json
import math
import re
import struct

import pytest
import shapebench

from conftest import ROOT, SCENARIOS, SWEEPS, run_cli


def bits(value: float) -> bytes:
    """The IEEE binary64 bytes of a float: equal bits, not merely ==  (0.0 and -0.0 differ)."""
    return struct.pack("<d", value)


def significant_digits(token: str) -> str:
    mantissa = re.split(r"[eE]", token.lstrip("-"))[0].replace(".", "")
    return mantissa.lstrip("0").rstrip("0") or "0"


def cli_json(path) -> tuple[str, dict]:
    done = run_cli("run", path, "--json")
    assert done.returncode == 0, done.stderr
    return done.stdout, json.loads(done.stdout)


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.name)
def test_run_metrics_equal_cli_json_bit_for_bit(path):
    """Tests that Scenario.run().metrics equals `run --json` bit for bit, null as NaN and
    false/true as 0.0/1.0, for every shipped scenario; and that Result.json() is its text."""
    text, expected = cli_json(path)
    # `run` records a trace, so its sampler steps every tick and the attribution
    # (*_source) is there; run(trace=True) is its twin (the metrics are the same either way).
    result = shapebench.load(path).run(trace=True)
    metrics = result.metrics
    # Beside the metrics: residual_modes, integrator_rtol_used, where a stroke alarm
    # fired, stroke_alarm_source, and the attribution (in Result.json()).
    names = [name for name in expected
             if name not in ("residual_modes", "integrator_rtol_used", "stroke_alarm_source",
                             "peak_deflection_source", "max_contour_error_source", "cruise_residual_source",
                             "peak_command_acceleration_source")]
    assert list(metrics) == names
    for name in names:
        value = expected[name]
        if value is None:
            assert math.isnan(metrics[name]), name
        elif isinstance(value, bool):
            assert bits(metrics[name]) == bits(1.0 if value else 0.0), name
        else:
            assert isinstance(metrics[name], float)
            assert bits(metrics[name]) == bits(float(value)), (name, metrics[name], value)
    assert result.residual_modes == expected["residual_modes"]
    rtol = expected["integrator_rtol_used"]
    assert math.isnan(result.integrator_rtol_used) if rtol is None else result.integrator_rtol_used == rtol
    assert result.json() + "\n" == text
    if "stroke_alarm_source" in expected:
        assert json.loads(result.json())["stroke_alarm_source"] == expected["stroke_alarm_source"]


@pytest.mark.parametrize("path", SCENARIOS[:3], ids=lambda p: p.name)
def test_cli_json_numbers_are_shortest_round_trip_texts(path):
    """Tests that the CLI's JSON numbers are the shortest texts that read back as their double
    (so Python's json gets the exact double): each has as many significant digits as
    Python's repr of the double it reads as, never more."""
    text, _ = cli_json(path)
    tokens = re.findall(r"(?<=: )-?[0-9][0-9.eE+-]*(?=,?\n)", text)
    assert len(tokens) > 10
    for token in tokens:
        shortest = repr(float(token))
        assert significant_digits(token) == significant_digits(shortest), (token, shortest)


def read_results_csv(path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="", encoding="utf-8") as file:
        rows = list(csv.reader(file))
    return rows[0], rows[1:]


@pytest.mark.parametrize("path", SWEEPS, ids=lambda p: p.name)
def test_sweep_columns_equal_results_csv(path, tmp_path):
    """Tests that sweep()'s columns equal the CLI's results.csv for every shipped sweep: point,
    the keys' texts, each metric bit for bit (empty as NaN), status and error."""
    done = run_cli("sweep", path, "--jobs", "2", "--out", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    header, rows = read_results_csv(tmp_path / "out" / "results.csv")
    result = shapebench.sweep(path, jobs=2)
    assert ["point", *result.keys, *result.metrics, "status", "error"] == header
    assert list(result.columns) == header
    assert result.points == len(rows)
    for c, name in enumerate(header):
        column = [row[c] for row in rows]
        if name == "point":
            assert result["point"].tolist() == [int(v) for v in column]
        elif name in result.keys:
            assert result.texts[name] == column
        elif name in ("status", "error"):
            assert result[name].tolist() == column
        else:
            values = result[name]
            for p, text in enumerate(column):
                if text == "":
                    assert math.isnan(values[p]), (name, p)
                else:
                    assert bits(float(values[p])) == bits(float(text)), (name, p, values[p], text)
