"""How the spec's messages name things: a value as a student wrote it (``describe``), a length in metres, a
"did you mean" hint, and the check that a name can name a world, model or file. Shared by the spec reader, the map
reader (:mod:`worldgen.spec.maps`) and the geometry's own checks."""

from __future__ import annotations

import re

from ..core.errors import SpecError
from .model import NAME_MAX

_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


def check_name(name: object, what: str, *, path: str | None = None, line: int | None = None) -> str:
    """Return ``name`` if it can name a world, model or file (letters, digits, underscores, starting with a
    letter; at most 64 characters); otherwise raise SpecError saying what to write instead."""
    if not isinstance(name, str):
        raise SpecError(f"{what} must be text, not {describe(name)}", path=path, line=line,
                        hint="write it as a word, e.g. my_world")
    if len(name) > NAME_MAX:
        raise SpecError(f"{what} '{name[:20]}…' is {len(name)} characters long", path=path, line=line,
                        hint=f"keep it at most {NAME_MAX} characters")
    if not _NAME_RE.match(name):
        raise SpecError(f"{what} '{name}' is not a valid name", path=path, line=line,
                        hint=f"use letters, digits and underscores, starting with a letter, e.g. {suggest_name(name)}")
    return name


def suggest_name(name: str) -> str:
    cleaned = re.sub(r"[^A-Za-z0-9_]+", "_", name).strip("_") or "my_world"
    return (cleaned if cleaned[0].isalpha() else f"w_{cleaned}")[:NAME_MAX]


def describe(value: object) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f"the text '{value}'" if len(value) < 40 else "a long text"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a mapping of keys"
    if isinstance(value, int):
        return f"the number {value}" if abs(value) < 10 ** 20 else "a very long number"
    if isinstance(value, float):
        return f"the number {value:g}"
    return f"a {type(value).__name__}"


def describe_sized(value: object) -> str:
    """:func:`describe` for a value that must be a list of so many numbers: a list says how long it is."""
    if not isinstance(value, list):
        return describe(value)
    return f"a list of {len(value)} number{'' if len(value) == 1 else 's'}"


def did_you_mean(word: str, choices, cutoff: float = 0.6) -> str:
    """``"; did you mean 'X'?"`` for the choice nearest ``word`` (difflib), or "" when none is near."""
    import difflib   # only a message needs it: not imported at start-up

    close = difflib.get_close_matches(word, choices, n=1, cutoff=cutoff)
    return f"; did you mean '{close[0]}'?" if close else ""


def metres(x: float) -> str:
    """A length for a message: up to 4 decimals, no trailing zeros."""
    return f"{round(x, 4):g}"
