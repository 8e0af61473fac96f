"""Reading one value of a spec: each function takes the :class:`Source` being read and a YAML :class:`Node`, checks
the value where it is read and returns it, or raises SpecError naming the file, the line and what to write instead.

Blocks and lists (``mapping``, ``listing``); numbers (``number``, and the checked kinds: ``length``, ``distance``,
``coordinate``, ``angle``, ``point``); words (``text``, ``name``, ``flag``); materials (``material``, ``script``,
``rgba``). The parts of a spec made of these are read in :mod:`.walls`, :mod:`.objects`, :mod:`.markings`,
:mod:`.grid_spec` and :mod:`.load`.
"""

from __future__ import annotations

import math
import re
from typing import NoReturn

from ..core.errors import SpecError
from .messages import check_name, describe, describe_sized, did_you_mean, metres
from .model import EPS, GAZEBO_MATERIALS, KEY_EXAMPLES, LIMIT, MATERIAL_KEYS, MIN_SIZE, Material, Point
from .nodes import Node

# A number with an exponent (1e-05, 2E3): JSON and people write it, but YAML 1.1 reads it as text unless it has a
# decimal point and a signed exponent (1.0e+3), so a plain (unquoted) scalar of this form is taken as the number.
EXPONENT_NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)[eE][-+]?\d+\Z")


class Source:
    """The file being read (``path``, None for text given without one): every check names it when it fails."""

    __slots__ = ("path",)

    def __init__(self, path: str | None):
        self.path = path

    def fail(self, message: str, line: int | None, hint: str | None = None) -> NoReturn:
        raise SpecError(message, path=self.path, line=line, hint=hint)


# ----------------------------------------------------------------------------------------- blocks and lists
def mapping(src: Source, node: Node, what: str, keys: tuple[str, ...], required: tuple[str, ...] = ()) -> dict:
    if not isinstance(node.value, dict):
        src.fail(f"{what} must be a block of keys ({', '.join(k + ':' for k in keys[:3])} …), "
                 f"not {describe(node.value)}", node.line,
                 hint=f"{what} takes: {', '.join(keys)}")
    for key in node.value:
        if key not in keys:
            src.fail(f"unknown key '{key}' in {what}{did_you_mean(key, keys)}", node.key_lines[key],
                     hint=f"{what} takes: {', '.join(keys)}")
    for key in required:
        if key not in node.value:
            src.fail(f"{what} has no '{key}'", node.line, hint=f"add {KEY_EXAMPLES.get(key, key + ': …')}")
    return node.value


def listing(src: Source, node: Node | None, what: str) -> list[Node]:
    if node is None or node.value is None:
        return []
    if not isinstance(node.value, list):
        src.fail(f"{what} must be a list, not {describe(node.value)}", node.line,
                 hint="start each item on its own line with '- ', or write [item, item]")
    return node.value


# -------------------------------------------------------------------------------------------------- numbers
def number(src: Source, node: Node, what: str, hint: str | None = None) -> float:
    value = node.value
    if isinstance(value, str) and not node.style and EXPONENT_NUMBER.match(value):
        value = float(value)   # 1e-05 as JSON writes it: a number, though YAML 1.1 reads text
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        src.fail(f"{what} must be a number, not {describe(value)}", node.line,
                 hint=hint or "write a plain number in metres, without quotes or units")
    if isinstance(value, int) and abs(value) > 1e300:
        src.fail(f"{what} is a {len(str(abs(value)))}-digit number", node.line,
                 hint=hint or "write a plain number in metres")
    value = float(value)
    if not math.isfinite(value):
        src.fail(f"{what} must be a finite number, not {value}", node.line,
                 hint=hint or "write a plain number in metres")
    return value


def length(src: Source, node: Node, what: str) -> float:
    """A size: more than 0 (at least 1 mm) and at most 1000 m."""
    value = number(src, node, what)
    if value <= 0:
        src.fail(f"{what} must be more than 0, not {metres(value)}", node.line, hint="sizes are in metres")
    if value < MIN_SIZE:
        src.fail(f"{what} is {value:g} m: less than 1 mm", node.line, hint="sizes are in metres")
    if value > LIMIT:
        src.fail(f"{what} is {metres(value)} m: more than {LIMIT:g} m", node.line,
                 hint="sizes are in metres; did you write millimetres?")
    return value


def distance(src: Source, node: Node, what: str) -> float:
    """A distance that may be 0 (offsets, sills), at most 1000 m."""
    value = number(src, node, what)
    if value < 0:
        src.fail(f"{what} must not be negative ({metres(value)})", node.line, hint="distances are in metres")
    if value > LIMIT:
        src.fail(f"{what} is {metres(value)} m: more than {LIMIT:g} m", node.line, hint="distances are in metres")
    return value


def coordinate(src: Source, node: Node, what: str) -> float:
    value = number(src, node, what)
    if abs(value) > LIMIT:
        src.fail(f"{what} is {metres(value)}: farther than {LIMIT:g} m from the origin", node.line,
                 hint="coordinates are in metres; did you write millimetres?")
    return value


def angle(src: Source, node: Node, what: str) -> float:
    value = number(src, node, what, hint="write the angle in radians, e.g. 1.5708 for 90 degrees")
    if abs(value) > 2 * math.pi + EPS:
        src.fail(f"{what} is {metres(value)}: angles are in radians, between -6.2832 and 6.2832", node.line,
                 hint=f"for {value:g} degrees write {math.radians(math.fmod(value, 360)):.4f}")
    return value


def point(src: Source, node: Node, what: str) -> Point:
    value = node.value
    if not isinstance(value, list) or len(value) != 2:
        src.fail(f"{what} must be a point [x, y], not {describe_sized(value)}", node.line,
                 hint="write two numbers in metres, e.g. [1.0, 2.5]")
    return (coordinate(src, value[0], f"x of {what}"), coordinate(src, value[1], f"y of {what}"))


# ---------------------------------------------------------------------------------------------------- words
def text(src: Source, node: Node, what: str, choices: tuple[str, ...]) -> str:
    value = node.value
    if isinstance(value, str) and value in choices:
        return value
    guess = did_you_mean(str(value).lower(), choices, cutoff=0.5)
    shown = f"'{value}'" if isinstance(value, str) else describe(value)
    src.fail(f"{what} must be one of {', '.join(choices)}, not {shown}{guess}", node.line,
             hint=f"write one of: {', '.join(choices)}")


def name(src: Source, node: Node, what: str) -> str:
    return check_name(node.value, what, path=src.path, line=node.line)


def flag(src: Source, node: Node, what: str) -> bool:
    """A yes/no value: YAML's ``true`` or ``false``."""
    if not isinstance(node.value, bool):
        src.fail(f"{what} must be true or false, not {describe(node.value)}", node.line,
                 hint="write true or false, without quotes")
    return node.value


# ------------------------------------------------------------------------------------------------ materials
def material(src: Source, node: Node, what: str, key: str = "material") -> Material:
    """A material as written under ``key`` (``material:``, a marking's ``color:``): a script name, a colour list,
    or ``{script: …}`` / ``{rgba: …}``."""
    value = node.value
    if isinstance(value, dict):
        keys = mapping(src, node, what, MATERIAL_KEYS)
        if len(keys) != 1:
            src.fail(f"{what} needs exactly one of 'script' or 'rgba'", node.line,
                     hint=f"e.g. {key}: Gazebo/Wood or {key}: {{rgba: [0.8, 0.2, 0.2, 1]}}")
        form, inner = next(iter(keys.items()))
        if form == "rgba":
            return Material(script=None, rgba=rgba(src, inner, what))
        if not isinstance(inner.value, str):
            src.fail(f"{what} script must be text, not {describe(inner.value)}", inner.line,
                     hint="e.g. script: Gazebo/Wood")
        return Material(script=script(src, inner, what))
    if isinstance(value, list):
        return Material(script=None, rgba=rgba(src, node, what))
    if isinstance(value, str):
        return Material(script=script(src, node, what))
    src.fail(f"{what} must be a Gazebo material name or an [r, g, b, a] colour, not {describe(value)}",
             node.line, hint=f"e.g. {key}: Gazebo/Wood or {key}: [0.8, 0.2, 0.2, 1]")


def script(src: Source, node: Node, what: str) -> str:
    name = node.value.strip()
    if not name:
        src.fail(f"{what} is empty", node.line, hint="write a Gazebo material like Gazebo/Grey, or give a "
                                                     "colour [r, g, b, a]")
    if name in GAZEBO_MATERIALS:
        return name
    import difflib   # only a name that is not a stock material needs it: not imported at start-up

    full = name if "/" in name else f"Gazebo/{name}"
    close = difflib.get_close_matches(full, GAZEBO_MATERIALS, n=1, cutoff=0.75)
    folded = {m.lower(): m for m in GAZEBO_MATERIALS}
    if "/" not in name or full.lower() in folded or (full.startswith("Gazebo/") and close):
        guess = folded.get(full.lower()) or (close[0] if close else "Gazebo/Grey")
        src.fail(f"{what} '{name}' is not a Gazebo material; did you mean '{guess}'?", node.line,
                 hint="Gazebo's materials are written like Gazebo/Grey, Gazebo/Wood, Gazebo/Bricks "
                      "(capitals matter), or give a colour [r, g, b, a]")
    if not re.fullmatch(r"[A-Za-z0-9_.\-]+(/[A-Za-z0-9_.\-]+)+", name):
        src.fail(f"{what} '{name}' is not a material script name", node.line,
                 hint="write it like Gazebo/Grey, or give a colour [r, g, b, a]")
    return name


def rgba(src: Source, node: Node, what: str) -> tuple[float, float, float, float]:
    value = node.value
    if not isinstance(value, list) or len(value) not in (3, 4):
        src.fail(f"{what} colour must be a list [r, g, b, a] of numbers from 0 to 1, not "
                 f"{describe_sized(value)}",
                 node.line, hint="e.g. [0.8, 0.2, 0.2, 1]")
    parts = [number(src, v, f"{what} colour component") for v in value]
    for v, part in zip(value, parts):
        if not 0 <= part <= 1:
            src.fail(f"{what} colour component {metres(part)} is outside 0–1", v.line,
                     hint="colours are fractions: 255 is 1, 128 is 0.5")
    return tuple(parts + [1.0] * (4 - len(parts)))
