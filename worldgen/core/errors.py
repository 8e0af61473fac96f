"""Domain errors: what went wrong, where (file and line), and how to fix it.

The CLI prints ``str(error)`` as one line and exits with code 2; nothing is written when one is raised.
"""

from __future__ import annotations

from pathlib import Path

# Exit codes of every command: checks passed; checks ran and failed; bad input or usage (one line on stderr).
EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2


class WorldgenError(Exception):
    """Base of every error a user can act on.

    ``path`` and ``line`` say where, ``hint`` says how to fix it. ``str()`` gives the one-line form
    ``file:line: message (hint)``.
    """

    def __init__(self, message: str, *, path: str | Path | None = None, line: int | None = None,
                 hint: str | None = None):
        super().__init__(message)
        self.message = message
        self.path = str(path) if path is not None else None
        self.line = line
        self.hint = hint

    def __str__(self) -> str:
        where = ""
        if self.path:
            where = f"{self.path}:{self.line}: " if self.line else f"{self.path}: "
        text = f"{where}{self.message}"
        if self.hint:
            text += f" ({self.hint})"
        return " ".join(text.split())  # one line, whatever the parts held


class SpecError(WorldgenError):
    """A floorplan spec that cannot be built."""


class WorldFileError(WorldgenError):
    """A world, model or launch file that cannot be read at all."""


class OutputExistsError(WorldgenError):
    """An output file or folder exists and --force was not given."""


class InputError(WorldgenError):
    """A command-line value that makes no sense (unknown robot model, bad spawn pose, …)."""
