"""Python values as YAML text: a --set value, a scenario given as a dict.

Flow style, one line: None null, bool true/false, int as written, float as repr (the
shortest text that reads back as the same double; inf .inf, nan .nan), str double-quoted
(JSON escapes, which YAML reads the same), mappings {k: v}, sequences and numpy arrays
[a, b].
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any


def to_yaml(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{json.dumps(str(k))}: {to_yaml(v)}" for k, v in value.items()) + "}"
    if hasattr(value, "tolist") and not isinstance(value, (int, float)):  # numpy arrays and scalars
        return to_yaml(value.tolist())
    if isinstance(value, int):
        return str(int(value))
    if isinstance(value, float):
        if math.isnan(value):
            return ".nan"
        if math.isinf(value):
            return ".inf" if value > 0 else "-.inf"
        return repr(float(value))
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(to_yaml(v) for v in value) + "]"
    raise TypeError(f"cannot write a {type(value).__name__} as YAML: {value!r}")
