"""The exceptions of shapebench: a bad input (ConfigError) and a solver failure (SolverError).

Their str() is the line the CLI prints after "error: " (exit 2 and exit 3).
"""

from __future__ import annotations


class Error(Exception):
    """Base class of the errors shapebench raises."""


class ConfigError(Error, ValueError):
    """A bad input, located where the CLI locates it (its exit 2).

    str(error) is "FILE:LINE:COL: key.path: message" (the position left out when line is 0,
    e.g. a file that cannot be read or a scenario given as a dict); a --set value reads
    "--set:N:1" with N its 1-based position among the overrides.
    """

    def __init__(self, file: str, line: int, column: int, key_path: str, message: str,
                 text: str | None = None) -> None:
        if text is None:
            from . import _core
            text = _core.config_error_text(file, line, column, key_path, message)
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.key_path = key_path
        self.message = message

    def __reduce__(self):
        return (type(self), (self.file, self.line, self.column, self.key_path, self.message, str(self)))


class SolverError(Error, RuntimeError):
    """The solver failed (the CLI's exit 3): str(error) is "solver failed: FLAG: message"."""

    def __init__(self, flag_name: str, message: str, text: str | None = None) -> None:
        super().__init__(text if text is not None else f"solver failed: {flag_name}: {message}")
        self.flag_name = flag_name
        self.message = message

    def __reduce__(self):
        return (type(self), (self.flag_name, self.message, str(self)))
