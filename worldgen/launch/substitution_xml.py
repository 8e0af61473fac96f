"""roslaunch's ``$(...)`` substitutions and ``if``/``unless`` conditions, evaluated the way roslaunch does for
what matters here: ``$(arg)``, ``$(env)``, ``$(optenv)``, ``$(find)``, ``$(dirname)``, ``$(anon)``.

A substitution that cannot be evaluated here (an unset arg or environment variable, an unknown package,
``$(eval)``) raises :class:`Unresolved`; :func:`expand_lenient` marks it instead, so the readable parts still are.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Dict, List, Mapping, Optional, Tuple, Union

from ..core import packages as rospkg
from ..core.errors import WorldFileError

SUBSTITUTION = re.compile(r"\$\((\w+)((?:\s+[^()\s]*)*)\s*\)")


class Unresolved(Exception):
    """A substitution that cannot be evaluated here (unset arg or env var, unknown package, ``$(eval)``)."""

    def __init__(self, reason: str, env: str | None = None, package: str | None = None):
        super().__init__(reason)
        self.reason, self.env, self.package = reason, env, package


ArgValue = Union[str, Unresolved]


@dataclass
class Scope:
    """One launch file being evaluated (or a ``<group>`` in it): its args, the args passed to it, where it is,
    its namespace, and the ``<remap>``s and ``<env>``s in effect for the nodes it declares next."""

    path: Path
    args: Dict[str, ArgValue]
    passed: Dict[str, ArgValue]
    ns: str
    remaps: Tuple[Tuple[str, str], ...] = ()
    env: Tuple[Tuple[str, str], ...] = ()
    node: Optional[str] = None   # inside a <node>: its full name (whose private namespace ~ names are in)

    def inner(self, ns: str) -> "Scope":
        """A ``<group>``'s scope: the file's args, its own namespace, the remaps and env in effect so far."""
        return Scope(self.path, self.args, self.passed, ns, self.remaps, self.env)


@dataclass(frozen=True)
class Lookup:
    """What substitutions look things up in: the package index for ``$(find)``, the environment for
    ``$(env)``/``$(optenv)``."""

    finder: rospkg.PackageIndex
    environ: Mapping[str, str]


# report(error, what was not resolved, scope, line): turns an Unresolved into a finding
Report = Callable[[Unresolved, str, Scope, Optional[int]], None]


def expand(lookup: Lookup, text: str, scope: Scope, find: bool = False) -> str:
    """``text`` with every substitution evaluated; ``$(find)`` only when ``find`` (it is kept otherwise).
    Raises Unresolved for the first one that cannot be evaluated."""
    if text.strip().startswith("$(eval "):
        raise Unresolved("$(eval …) expressions are not evaluated here")
    return SUBSTITUTION.sub(lambda m: substitute(lookup, m, scope, find), text)


def expand_lenient(lookup: Lookup, text: str, scope: Scope) -> Tuple[str, List[Unresolved]]:
    """Like :func:`expand`, but each substitution that cannot be evaluated becomes the marker ``\\0N\\0``
    (N indexes the returned errors), so the parts that can be read still are."""
    errors: List[Unresolved] = []

    def one(match: re.Match) -> str:
        try:
            return substitute(lookup, match, scope, False)
        except Unresolved as err:
            errors.append(err)
            return f"\0{len(errors) - 1}\0"

    if text.strip().startswith("$(eval "):
        return "\x000\x00", [Unresolved("$(eval …) expressions are not evaluated here")]
    return SUBSTITUTION.sub(one, text), errors


def try_expand(lookup: Lookup, text: str, scope: Scope) -> ArgValue:
    """``text`` expanded, or the Unresolved that stopped it (an arg's value may stay unknown until used)."""
    try:
        return expand(lookup, text, scope)
    except Unresolved as err:
        return err


def expand_or_keep(lookup: Lookup, text: str, scope: Scope) -> str:
    """``text`` expanded, or as written when it cannot be (names and namespaces)."""
    value = try_expand(lookup, text, scope)
    return text if isinstance(value, Unresolved) else value


def substitute(lookup: Lookup, match: re.Match, scope: Scope, find: bool) -> str:
    """The value of one ``$(command args)`` match."""
    command, rest = match.group(1), match.group(2).split()
    if command == "arg" and len(rest) == 1:
        value = scope.args.get(rest[0])
        if value is None:
            raise Unresolved(f"arg {rest[0]!r} is not declared")
        if isinstance(value, Unresolved):
            raise value
        return value
    if command == "env" and len(rest) == 1:
        if rest[0] not in lookup.environ:
            raise Unresolved(f"environment variable {rest[0]} is not set", env=rest[0])
        return lookup.environ[rest[0]]
    if command == "optenv" and rest:
        return lookup.environ.get(rest[0], " ".join(rest[1:]))
    if command == "dirname" and not rest:
        return str(scope.path.resolve().parent)
    if command == "anon" and len(rest) == 1:
        return f"{rest[0]}_anon"
    if command == "find" and len(rest) == 1:
        if not find:
            return match.group(0)
        found = lookup.finder.find(rest[0])
        if found is None:
            raise Unresolved(f"package {rest[0]!r} not found", package=rest[0])
        return str(found)
    raise Unresolved(f"cannot evaluate {match.group(0)}")


def condition(lookup: Lookup, el, scope: Scope, report: Report) -> bool:
    """Whether element ``el`` is in effect: its ``if``/``unless`` evaluated (one that cannot be is assumed
    satisfied, and reported). Raises WorldFileError for a value that is neither true nor false."""
    for attr, want in (("if", True), ("unless", False)):
        raw = el.get(attr)
        if raw is None:
            continue
        try:
            value = expand(lookup, raw, scope, find=True).strip().lower()
        except Unresolved as err:
            report(err, f"<{el.tag} {attr}=…> assumed satisfied", scope, el.sourceline)
            continue
        if value not in ("true", "1", "false", "0"):
            raise WorldFileError(f"<{el.tag} {attr}=\"{raw}\"> is neither true nor false", path=scope.path,
                                 line=el.sourceline, hint="use true/false or 1/0")
        if (value in ("true", "1")) != want:
            return False
    return True
