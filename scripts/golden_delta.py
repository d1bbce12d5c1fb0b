#!/usr/bin/env python3
"""How far a regenerated golden set moved: scripts/golden_delta.py OLD_DIR NEW_DIR.

For every file in both sets, every number that changed (CSV fields, JSON values, numbers in
text) is compared. Ratios (names ending in _ratio) are already relative to the static
displacement; lengths (names ending in _m) are divided by the record's static_displacement_m
where it has one. Prints the largest change per file and kind, lists any change that is not
a number (a verdict, a status, a count), and exits 1 when there is one, or when a ratio or a
length moved by more than --bound (default 1e-12) of the static displacement.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import math
import pathlib
import re
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def records(path: pathlib.Path) -> list[dict]:
    """The file as a list of flat {key: value} records."""
    text = path.read_text()
    if path.suffix == ".csv":
        return list(csv.DictReader(io.StringIO(text)))
    body = text.rsplit("\nexit ", 1)[0] if "\nexit " in text else text
    try:
        data = json.loads(body)
    except ValueError:
        return [{f"token{i}": tok for i, tok in enumerate(text.split())}]
    flat: list[dict] = []

    def walk(node, into: dict, prefix: str) -> None:
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, into, f"{prefix}{k}." if isinstance(v, (dict, list)) else f"{prefix}{k}")
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, into, f"{prefix}{i}.")
        else:
            into[prefix.rstrip(".")] = node

    one: dict = {}
    walk(data, one, "")
    flat.append(one)
    return flat


def as_float(value) -> float | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str) and NUMBER.fullmatch(value.strip() or "x"):
        return float(value)
    return None


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--bound", type=float, default=1e-12)
    args = parser.parse_args()
    old_dir, new_dir = pathlib.Path(args.old), pathlib.Path(args.new)
    failed = False
    for old in sorted(old_dir.iterdir()):
        new = new_dir / old.name
        if not new.exists():
            print(f"{old.name}: missing in {new_dir}")
            failed = True
            continue
        if old.read_bytes() == new.read_bytes():
            continue
        a, b = records(old), records(new)
        if len(a) != len(b):
            print(f"{old.name}: {len(a)} records against {len(b)}")
            failed = True
            continue
        worst: dict[str, tuple[float, str]] = {}
        for ra, rb in zip(a, b):
            static = as_float(ra.get("static_displacement_m")) or as_float(ra.get("metrics.static_displacement_m"))
            for key in ra:
                va, vb = ra.get(key), rb.get(key)
                if va == vb:
                    continue
                fa, fb = as_float(va), as_float(vb)
                if fa is None or fb is None:
                    print(f"{old.name}: {key}: {va!r} -> {vb!r} (not a number)")
                    failed = True
                    continue
                if math.isnan(fa) and math.isnan(fb):
                    continue
                if key.endswith("_ratio"):
                    kind, delta = "ratio", abs(fa - fb)
                elif key.endswith("_m") and static:
                    kind, delta = "length/static", abs(fa - fb) / static
                else:
                    kind, delta = "relative", abs(fa - fb) / max(abs(fa), abs(fb))
                if delta > worst.get(kind, (-1.0, ""))[0]:
                    worst[kind] = (delta, key)
                if kind != "relative" and delta > args.bound:
                    failed = True
        for kind, (delta, key) in sorted(worst.items()):
            print(f"{old.name}: largest {kind} change {delta:.3g} ({key})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
