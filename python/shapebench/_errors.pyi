class Error(Exception): ...

class ConfigError(Error, ValueError):
    """A bad input, located as the CLI locates it: str() is the CLI's exit-2 line after "error: "."""

    file: str
    line: int
    column: int
    key_path: str
    message: str
    def __init__(self, file: str, line: int, column: int, key_path: str, message: str,
                 text: str | None = None) -> None: ...

class SolverError(Error, RuntimeError):
    """The solver failed: str() is "solver failed: FLAG: message" (the CLI's exit 3)."""

    flag_name: str
    message: str
    def __init__(self, flag_name: str, message: str, text: str | None = None) -> None: ...
