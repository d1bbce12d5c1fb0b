"""Tests that the MAT files shapebench writes read back in scipy.io.loadmat as the CSV files
beside them: run --out's trace.mat against trace.csv, a sweep's results.mat against
results.csv (docs/views.md#matlab-files)."""

from __future__ import annotations

import csv
import math

import numpy as np
import scipy.io

from conftest import ROOT, run_cli


def read_csv(path):
    with open(path, newline="") as f:
        rows = [row for row in csv.reader(f) if not row[0].startswith("#")]
    return rows[0], rows[1:]


def as_number(text: str) -> float:
    return math.nan if text == "" else float(text)


def test_trace_mat_equals_trace_csv(tmp_path):
    """Tests that trace.mat holds every trace.csv column as an N x 1 double of the same name
    whose values equal the CSV's bit for bit (the CSV's shortest round-trip text), for the
    demo and for a decimated trace (limits.max_trace_rows)."""
    for name, sets in (("demo", []), ("decimated", ["--set", "limits.max_trace_rows=1000"])):
        out = tmp_path / name
        done = run_cli("run", ROOT / "configs" / "demo.yaml", "--out", out, *sets)
        assert done.returncode == 0, done.stderr
        assert f"wrote {out}/trace.mat" in done.stdout
        header, rows = read_csv(out / "trace.csv")
        mat = scipy.io.loadmat(out / "trace.mat")
        assert scipy.io.whosmat(out / "trace.mat")[0][2] == "double"
        assert sorted(k for k in mat if not k.startswith("__")) == sorted(header)
        for c, column in enumerate(header):
            expected = np.array([as_number(row[c]) for row in rows])
            got = mat[column]
            assert got.shape == (len(rows), 1), column
            np.testing.assert_array_equal(got[:, 0], expected, err_msg=column)
        if name == "decimated":
            assert len(rows) <= 1000


def test_results_mat_equals_results_csv(tmp_path):
    """Tests that a sweep's results.mat holds each results.csv column under its MATLAB name
    (numbers as N x 1 doubles equal to the CSV's, empty fields NaN; text as N x 1 cells of
    the same strings) and `columns`, the header as written."""
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text(
        f"base: {ROOT}/configs/scenarios/sdof_method1.yaml\n"
        "grid:\n"
        "  controller.pattern.method: [none, \"1\", zvd]\n"
        "  machine.modes[0].frequency_hz: {from: 20, to: 30, steps: 3}\n"
        "metrics: [peak_ratio, residual_ratio, motion_time_s]\n")
    out = tmp_path / "out"
    done = run_cli("sweep", sweep, "--out", out)
    assert done.returncode == 0, done.stderr
    assert f"{out}/results.mat" in done.stdout
    header, rows = read_csv(out / "results.csv")
    mat = scipy.io.loadmat(out / "results.mat")
    assert [str(cell[0]) for cell in mat["columns"][:, 0]] == header
    names = {
        "point": "point", "controller.pattern.method": "controller_pattern_method",
        "machine.modes[0].frequency_hz": "machine_modes_0_frequency_hz", "peak_ratio": "peak_ratio",
        "residual_ratio": "residual_ratio", "motion_time_s": "motion_time_s", "status": "status", "error": "error"}
    assert set(header) == set(names)
    for c, column in enumerate(header):
        got = mat[names[column]]
        assert got.shape == (len(rows), 1), column
        texts = [row[c] for row in rows]
        if got.dtype == object:
            assert [cell[0] if cell.size else "" for cell in got[:, 0]] == texts, column
        else:
            np.testing.assert_array_equal(got[:, 0], np.array([as_number(t) for t in texts]), err_msg=column)
    assert mat["controller_pattern_method"].dtype == object  # none, 1, zvd: text
    assert mat["peak_ratio"].dtype == np.float64
