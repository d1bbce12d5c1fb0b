"""Shared fixtures of the Python module's tests: the repository, the built CLI
(SHAPEBENCH_BINARY, set by ctest) and running it."""

from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENARIOS = sorted((ROOT / "configs" / "scenarios").glob("*.yaml")) + [ROOT / "configs" / "demo.yaml"]
SWEEPS = sorted((ROOT / "configs" / "sweeps").glob("*.yaml"))


def cli_binary() -> str:
    binary = os.environ.get("SHAPEBENCH_BINARY", str(ROOT / "build" / "shapebench"))
    if not os.path.exists(binary):
        pytest.fail(f"the CLI {binary} is not built (ctest sets SHAPEBENCH_BINARY)")
    return binary


def run_cli(*args: str, cwd: pathlib.Path = ROOT) -> subprocess.CompletedProcess:
    """The CLI's exit code, stdout and stderr, run from the repository's top."""
    return subprocess.run([cli_binary(), *map(str, args)], cwd=cwd, capture_output=True, text=True)


@pytest.fixture(autouse=True)
def _at_repository_top(monkeypatch):
    """Every test runs from the repository's top, as the README's commands do."""
    monkeypatch.chdir(ROOT)
