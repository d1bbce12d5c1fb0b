"""Tests that examples/notebook.md, the README's tour from Python, runs and prints what it
says: its ```python blocks run in order in one namespace, each one's output equal to the
```text block that follows it."""

from __future__ import annotations

import contextlib
import io
import re

from conftest import ROOT


def blocks() -> list[tuple[str, str | None]]:
    text = (ROOT / "examples" / "notebook.md").read_text()
    found = re.findall(r"```(python|text)\n(.*?)```", text, flags=re.S)
    pairs = []
    for i, (kind, body) in enumerate(found):
        if kind == "python":
            follows = found[i + 1] if i + 1 < len(found) else None
            pairs.append((body, follows[1] if follows and follows[0] == "text" else None))
    return pairs


def test_notebook_blocks_print_what_it_shows():
    """Tests that every python block of the notebook prints exactly its text block."""
    pairs = blocks()
    assert len(pairs) >= 9
    namespace: dict = {}
    for n, (code, expected) in enumerate(pairs, 1):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(code, f"notebook.md block {n}", "exec"), namespace)
        if expected is not None:
            assert out.getvalue() == expected, f"block {n}:\n{code}"
