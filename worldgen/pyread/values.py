"""The values :mod:`.evaluate` reads Python into: plain Python values, plus :class:`Unknown` (what cannot be known
without running the file, and why), :class:`Located` (a path in a ROS package's share folder), :class:`Symbol` (a
name the file imports), :class:`Function` (one it defines), and the state of one read (:class:`Ctx`)."""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any, Callable, Dict, Mapping, Optional

MAX_DEPTH = 120            # nested expressions evaluated (deeper: Unknown)
MAX_CALL_DEPTH = 12        # functions of the file followed inside one another
MAX_CALLS = 2000           # functions of the file followed in one read
MAX_SIZE = 1_000_000       # characters of a string, items of a list
MAX_INT = 10 ** 18
MAX_NESTING = 32           # lists inside lists looked into (a value nested deeper is not a plain one)
MAX_SHOWN = 400            # characters of an unknown value's reading kept for messages
MAX_WORK = 20_000_000      # expressions evaluated plus the length of every string and list they give, per file
MAX_ITERATIONS = 100_000   # items all the comprehensions of a file go through, when they are run (setup.py)
MAX_PYTHON_BYTES = 4 * 2 ** 20       # a Python launch file or setup.py larger than this is refused


class Unknown:
    """A value that cannot be known without running the file: why (``reason``), the line it comes from, how it
    would read with the unknown part marked (``shown``), and the package or environment variable it waits on."""

    __slots__ = ("reason", "line", "shown", "package", "env", "skipped")

    def __init__(self, reason: str, line: int | None = None, shown: str | None = None,
                 package: str | None = None, env: str | None = None, skipped: bool = False):
        if shown is not None and len(shown) > MAX_SHOWN:   # a string doubled in a file stays short in messages
            shown = shown[:MAX_SHOWN // 2] + "…" + shown[-MAX_SHOWN // 4:]
        self.reason, self.line, self.shown, self.package, self.env = reason, line, shown, package, env
        self.skipped = skipped   # set in code that is not run (already reported where it is skipped)

    def like(self, shown: str | None) -> "Unknown":
        """The same unknown, read as ``shown`` (a path or string built around it)."""
        return Unknown(self.reason, self.line, shown, self.package, self.env, self.skipped)

    def __repr__(self) -> str:
        return f"Unknown({self.reason!r}, line={self.line})"


class Located(str):
    """A path string inside a ROS package's share folder (``get_package_share_directory``); ``package`` names it."""

    package: str = ""

    @classmethod
    def make(cls, text: str, package: str) -> "Located":
        value = cls(text)
        value.package = package
        return value


@dataclass(frozen=True)
class Symbol:
    """A name the file imports or uses without defining it (``os.path.join``, ``Node``), by its dotted name."""

    name: str


@dataclass(frozen=True)
class Function:
    """A function defined in the file, with the frame it was defined in and its default values."""

    node: Any
    frame: "Frame"
    defaults: tuple = ()
    kw_defaults: tuple = ()


@dataclass
class Call:
    """A call of a known name: its dotted name, evaluated arguments and line."""

    name: str
    args: list
    kwargs: dict
    line: int | None
    node: Any = None

    def arg(self, index: int, keyword: str, default=None):
        """Argument ``index`` (positional) or ``keyword``; ``default`` when absent."""
        if keyword in self.kwargs:
            return self.kwargs[keyword]
        return self.args[index] if index is not None and len(self.args) > index else default


class Frame:
    """The names bound in one function call (or the module), with the frame it sees through."""

    def __init__(self, parent: Optional["Frame"] = None):
        self.names: Dict[str, Any] = {}
        self.parent = parent

    def lookup(self, name: str):
        frame: Optional[Frame] = self
        while frame is not None:
            if name in frame.names:
                return frame.names[name]
            frame = frame.parent
        return Symbol(name)


@dataclass
class Returned:
    value: Any


# on_skip(ctx, kind, node, frame, reason): code that is not run ("for", "while", "if", "except", "match",
# "comprehension"); reason says why (the condition's Unknown, for an if)
SkipHook = Callable[["Ctx", str, Any, Frame, Optional[str]], None]


@dataclass
class Ctx:
    """One read of one file: its path, the environment, the calls taught by the caller (dotted or bare names →
    ``handler(ctx, call)``), the hook for code not run, and the bounds' counters. ``env_reads`` records each
    environment variable read (name → value or None, line)."""

    path: Path
    environ: Mapping[str, str]
    calls: Mapping[str, Callable[["Ctx", Call], Any]] = field(default_factory=dict)
    on_skip: Optional[SkipHook] = None
    env_reads: Dict[str, tuple] = field(default_factory=dict)
    depth: int = 0
    call_depth: int = 0
    calls_made: int = 0
    work: int = 0       # see MAX_WORK
    state: Any = None   # the caller's own (the launch reader's current scope)
    comprehensions: bool = False   # run comprehensions whose iterables and conditions are known (setup.py)
    iterations: int = 0            # items comprehensions went through, in all (see MAX_ITERATIONS)


# --------------------------------------------------------------------------------------------- helpers

def shown(value) -> str:
    """How a value reads inside a path or message (unknown parts marked ‹…›)."""
    if isinstance(value, Unknown):
        return value.shown or "‹?›"
    if isinstance(value, (str, int, float, PurePosixPath)) and not isinstance(value, bool):
        return str(value)
    if isinstance(value, Symbol):
        return f"‹{value.name}›"
    return "‹…›"


def first_unknown(values) -> Unknown | None:
    return next((v for v in values if isinstance(v, Unknown)), None)


def sized(value, line: int | None):
    """``value``, or an Unknown when it is a string or list past MAX_SIZE, or an integer past MAX_INT."""
    if isinstance(value, (str, list, tuple)) and len(value) > MAX_SIZE:
        return Unknown(f"a value of over {MAX_SIZE} items is not built here", line)
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > MAX_INT:
        return Unknown("a number this large is not computed here", line)
    return value


def truth(value) -> bool | None:
    """Python's truth of a value; None when it cannot be known."""
    if isinstance(value, Unknown):
        return None
    if isinstance(value, (str, int, float, list, tuple, dict)) or value is None:
        return bool(value)
    return True   # objects (actions, substitutions, paths, functions) are true in Python


def describe(node) -> str:
    """The source text of a callee (``os.path.join``) for messages."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return f"{describe(node.value)}.{node.attr}"
    if isinstance(node, ast.Call):
        return f"{describe(node.func)}(…)"
    return "…"


def not_run(kind: str, node) -> str:
    """How code that is not run is named in messages: ``the for loop at line 12``."""
    names = {"for": "for loop", "while": "while loop", "if": "if", "except": "except block",
             "match": "match", "comprehension": "comprehension"}
    return f"the {names.get(kind, kind)} at line {getattr(node, 'lineno', '?')}"
