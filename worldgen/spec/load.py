"""The floorplan spec: a YAML/JSON (or ASCII-grid, or ROS map_server map) file read into validated, immutable
dataclasses.

Coordinates are metres in the world frame. A room's ``rect`` or ``polygon`` gives the walls' centre-lines, as the
Building Editor draws them; wall ``i`` runs from vertex ``i`` to vertex ``i+1``; an opening's ``offset`` is the
distance along the wall's centre-line from vertex ``i`` to the opening's near edge.

Parsing (``load_spec``) lives below the dataclasses; every error is a :class:`~worldgen.core.errors.SpecError` naming
the file and line. A map_server map (its own YAML, or a spec's ``map: FILE``) is read by :mod:`worldgen.spec.maps`.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, NoReturn, Tuple

import yaml

from ..core.errors import SpecError
from .grid import POST_PREFIX, plan_grid

Point = Tuple[float, float]

DEFAULT_THICKNESS = 0.15   # Building Editor default
DEFAULT_HEIGHT = 2.5       # Building Editor default (level height)
DEFAULT_MATERIAL = "Gazebo/Grey"
DOOR_HEIGHT = 2.0
WINDOW_HEIGHT = 0.8
WINDOW_SILL = 0.5
ROBOT_MODELS = ("burger", "waffle", "waffle_pi")
SPEC_SUFFIXES = (".yaml", ".yml", ".json", ".txt")   # the file names a spec has (a .txt is an ASCII grid)


@dataclass(frozen=True)
class Material:
    """A Gazebo material script name (``Gazebo/Grey``) or an RGBA colour (0–1 each); exactly one is set."""

    script: str | None = DEFAULT_MATERIAL
    rgba: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class WallStyle:
    thickness: float = DEFAULT_THICKNESS
    height: float = DEFAULT_HEIGHT
    material: Material = field(default_factory=Material)


@dataclass(frozen=True)
class Opening:
    """A door or window cut into wall ``wall`` of its room (or of its segment)."""

    type: Literal["door", "window"]
    wall: int
    offset: float
    width: float
    height: float
    sill: float = 0.0   # 0 for doors
    line: int | None = None


@dataclass(frozen=True)
class Room:
    name: str
    vertices: tuple[Point, ...]      # centre-line polygon, as written (either winding)
    style: WallStyle
    openings: tuple[Opening, ...] = ()
    line: int | None = None


@dataclass(frozen=True)
class Segment:
    """A free-standing straight wall (``segments:`` in the spec; ASCII grids become these)."""

    start: Point
    end: Point
    style: WallStyle
    openings: tuple[Opening, ...] = ()   # ``wall`` is always 0
    line: int | None = None


@dataclass(frozen=True)
class Obstacle:
    shape: Literal["box", "cylinder", "sphere"]
    at: Point
    yaw: float = 0.0
    size: tuple[float, float, float] | None = None   # box: x, y, z
    radius: float | None = None                        # cylinder, sphere
    height: float | None = None                        # cylinder
    material: Material = field(default_factory=Material)
    name: str | None = None
    line: int | None = None


@dataclass(frozen=True)
class RobotPose:
    model: str = "burger"
    at: Point = (0.0, 0.0)
    yaw: float = 0.0
    line: int | None = None


@dataclass(frozen=True)
class Spec:
    name: str
    style: WallStyle = field(default_factory=WallStyle)
    rooms: tuple[Room, ...] = ()
    segments: tuple[Segment, ...] = ()
    obstacles: tuple[Obstacle, ...] = ()
    robot: RobotPose | None = None
    source: str | None = None     # the file it came from, for messages


# --------------------------------------------------------------------------------------------------- parsing
# The text is composed into YAML nodes (not constructed straight to Python) so that every value keeps the line it
# came from; each check below then names the file and line of the value to change.

LIMIT = 1000.0        # metres: no size or coordinate may exceed it (a typo in units, most likely)
MIN_SIZE = 0.001      # metres: anything thinner is a typo too, and breaks the simulators
NAME_MAX = 64
DOOR_WIDTH = 0.9
WINDOW_WIDTH = 0.8
DEFAULT_CELL = 0.5
SHAPES = ("box", "cylinder", "sphere")
OPENING_TYPES = ("door", "window")
_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
# A number with an exponent (1e-05, 2E3): JSON and people write it, but YAML 1.1 reads it as text unless it has a
# decimal point and a signed exponent (1.0e+3), so a plain (unquoted) scalar of this form is taken as the number.
_EXPONENT_NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)[eE][-+]?\d+\Z")
_EPS = 1e-9

TOP_KEYS = ("name", "walls", "rooms", "segments", "grid", "obstacles", "robot", "map")
WALL_KEYS = ("thickness", "height", "material")
ROOM_KEYS = ("name", "rect", "polygon", "walls", "openings")
RECT_KEYS = ("center", "size")
OPENING_KEYS = ("type", "wall", "offset", "width", "height", "sill")
SEGMENT_KEYS = ("from", "to", "walls", "openings")
SHAPE_KEYS = {"box": ("size",), "cylinder": ("radius", "height"), "sphere": ("radius",)}
OBSTACLE_KEYS = ("shape", "name", "at", "yaw", "size", "radius", "height", "material")
ROBOT_KEYS = ("model", "at", "yaw")
GRID_KEYS = ("cell", "rows", "origin", "height", "material")
MATERIAL_KEYS = ("script", "rgba")

# How each required key is written, for "add …" hints.
_EXAMPLE = {
    "name": "name: my_world", "center": "center: [0, 0]", "size": "size: [5, 5]", "type": "type: door",
    "wall": "wall: 0", "from": "from: [0, 0]", "to": "to: [3, 0]", "shape": "shape: box", "radius": "radius: 0.2",
    "height": "height: 0.5",
    "rows": "rows: |  (then the grid lines, indented)",
}

# Gazebo's stock material scripts (media/materials/scripts/gazebo.material), for "did you mean" only: other
# script names are accepted as written, since a world may bring its own.
GAZEBO_MATERIALS = (
    "Gazebo/Grey", "Gazebo/DarkGrey", "Gazebo/White", "Gazebo/FlatBlack", "Gazebo/Black", "Gazebo/Red",
    "Gazebo/RedBright", "Gazebo/Green", "Gazebo/Blue", "Gazebo/SkyBlue", "Gazebo/Yellow", "Gazebo/ZincYellow",
    "Gazebo/DarkYellow", "Gazebo/Purple", "Gazebo/Turquoise", "Gazebo/Orange", "Gazebo/Indigo",
    "Gazebo/Wood", "Gazebo/WoodFloor", "Gazebo/WoodPallet", "Gazebo/Bricks", "Gazebo/CeilingTiled",
    "Gazebo/PaintedWall", "Gazebo/Residential", "Gazebo/Road", "Gazebo/Gravel", "Gazebo/Rockwall",
    "Gazebo/RustySteel", "Gazebo/Chrome", "Gazebo/Gold", "Gazebo/Grass", "Gazebo/GreyTransparent",
    "Gazebo/RedTransparent", "Gazebo/GreenTransparent", "Gazebo/BlueTransparent",
)


def spec_beside(world_path: str | Path) -> tuple[Path, Spec] | None:
    """The spec a world was built from, when it lies beside it with the same name (``room.world`` ←
    ``room.yaml``/``.yml``/``.json``) and loads; None otherwise."""
    for suffix in (".yaml", ".yml", ".json"):
        spec_path = Path(world_path).with_suffix(suffix)
        if spec_path.is_file():
            try:
                return spec_path, load_spec(spec_path)
            except SpecError:
                return None
    return None


def load_spec(path: str | Path) -> Spec:
    """Read and validate a floorplan spec: YAML or JSON, or a ``.txt`` ASCII grid (cell 0.5 m, named after the
    file), or a ROS map_server map's YAML (a YAML with an ``image`` key: its occupied pixels become walls, the world
    is named after the file; see :mod:`worldgen.spec.maps`). Raises SpecError naming the file and line of the first
    problem."""
    from .maps import IMAGE_SUFFIXES

    path = Path(path)
    if path.suffix.lower() in IMAGE_SUFFIXES:
        raise SpecError("is an image, not a spec", path=path,
                        hint="for a ROS map, give the map's YAML (map.yaml, as map_saver writes it beside the image)")
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SpecError("no such file", path=path, hint="check the spec's path") from None
    except IsADirectoryError:
        raise SpecError("is a folder, not a spec file", path=path, hint="give the .yaml file inside it") from None
    except UnicodeDecodeError as err:
        raise SpecError(f"is not UTF-8 text ({err.reason} at byte {err.start})", path=path,
                        hint="save the spec as plain UTF-8 text") from None
    except OSError as err:
        raise SpecError(f"cannot be read: {err.strerror}", path=path) from None
    if path.suffix.lower() == ".txt":
        return _Reader(str(path)).grid_file(text, path.stem)
    if path.suffix.lower() == ".json":
        text = text.replace("\t", "  ")   # JSON allows tabs between tokens, YAML does not; both keep the lines
    return parse_spec(text, str(path))


def parse_spec(text: str, source: str | None = None) -> Spec:
    """Validate a spec given as YAML (or JSON) text; ``source`` names it in messages."""
    return _Reader(source).spec(_compose(text, source))


def starter_spec(name: str) -> str:
    """The commented starter spec ``worldgen new NAME`` writes: a closed 5 m × 5 m room with a window, an
    obstacle and the robot in the middle, a door offered commented out (``templates/spec/starter.yaml.j2``)."""
    from ..core.resources import render_template

    check_name(name, "the world name")
    return render_template("spec/starter.yaml.j2", name=name)


def check_name(name: object, what: str, *, path: str | None = None, line: int | None = None) -> str:
    """Return ``name`` if it can name a world, model or file (letters, digits, underscores, starting with a
    letter; at most 64 characters); otherwise raise SpecError saying what to write instead."""
    if not isinstance(name, str):
        raise SpecError(f"{what} must be text, not {_describe(name)}", path=path, line=line,
                        hint="write it as a word, e.g. my_world")
    if len(name) > NAME_MAX:
        raise SpecError(f"{what} '{name[:20]}…' is {len(name)} characters long", path=path, line=line,
                        hint=f"keep it at most {NAME_MAX} characters")
    if not _NAME_RE.match(name):
        raise SpecError(f"{what} '{name}' is not a valid name", path=path, line=line,
                        hint=f"use letters, digits and underscores, starting with a letter, e.g. {_suggest_name(name)}")
    return name


def _suggest_name(name: str) -> str:
    cleaned = re.sub(r"[^A-Za-z0-9_]+", "_", name).strip("_") or "my_world"
    return (cleaned if cleaned[0].isalpha() else f"w_{cleaned}")[:NAME_MAX]


def _describe(value: object) -> str:
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


def _describe_sized(value: object) -> str:
    """:func:`_describe` for a value that must be a list of so many numbers: a list says how long it is."""
    if not isinstance(value, list):
        return _describe(value)
    return f"a list of {len(value)} number{'' if len(value) == 1 else 's'}"


def did_you_mean(word: str, choices, cutoff: float = 0.6) -> str:
    """``"; did you mean 'X'?"`` for the choice nearest ``word`` (difflib), or "" when none is near."""
    close = difflib.get_close_matches(word, choices, n=1, cutoff=cutoff)
    return f"; did you mean '{close[0]}'?" if close else ""


def _m(x: float) -> str:
    """A length for a message: up to 4 decimals, no trailing zeros."""
    return f"{round(x, 4):g}"


class _Node:
    """A YAML value with its line (1-based): ``value`` is a dict of key → _Node, a list of _Node, or a scalar."""

    __slots__ = ("value", "line", "key_lines", "style")

    def __init__(self, value, line: int, key_lines: dict[str, int] | None = None, style: str | None = None):
        self.value, self.line, self.key_lines, self.style = value, line, key_lines or {}, style


def _compose(text: str, source: str | None) -> _Node | None:
    """The spec text as _Nodes. libyaml's parser (``yaml.CSafeLoader``, when PyYAML was built with it) is several
    times faster on big specs; text it refuses is parsed again by the pure-Python parser, whose messages and
    marks the errors below are worded for, so an error reads the same (same line) with or without libyaml."""
    fast = getattr(yaml, "CSafeLoader", None)
    try:
        if fast is not None:
            try:
                return _nodes(fast(text), source)
            except yaml.YAMLError:
                pass   # reported by the pure-Python parser, below
        return _nodes(yaml.SafeLoader(text), source)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        problem = err.problem or "the text is not valid YAML"
        hint = "check the indentation and brackets on this line and the one above"
        if "\\t" in problem or "\t" in problem:
            hint = "indent with spaces, not tabs"
        elif "another document" in problem:
            hint = "a spec is one YAML document: remove this '---' and what follows, or put it in its own file"
        # PyYAML words some errors as context then problem ("expected a single document … but found another")
        parts = (err.context, problem) if problem.startswith("but ") else (problem, err.context)
        raise SpecError(f"invalid YAML: {' '.join(p for p in parts if p)}", path=source,
                        line=mark.line + 1 if mark else None, hint=hint) from None
    except yaml.YAMLError as err:
        raise SpecError(f"invalid YAML: {err}", path=source) from None
    except RecursionError:
        raise SpecError("lists or blocks are nested too deeply", path=source,
                        hint="a spec nests a few levels at most; check the brackets") from None


def _nodes(loader, source: str | None) -> _Node | None:
    """The single document ``loader`` reads, as _Nodes (None when the text holds none)."""
    try:
        root = loader.get_single_node()
        return None if root is None else _convert(root, loader, {}, set(), source)
    finally:
        loader.dispose()


def _convert(node, loader, memo: dict, active: set, source) -> _Node:
    """YAML node → _Node. Aliases share one converted value; a recursive alias is refused."""
    if id(node) in memo:
        return memo[id(node)]
    line = node.start_mark.line + 1
    if id(node) in active:
        raise SpecError("a YAML alias refers to itself", path=source, line=line, hint="remove the recursive *alias")
    if isinstance(node, yaml.ScalarNode):
        out = _Node(loader.construct_object(node), line, style=node.style or None)   # libyaml: '' for plain
    elif isinstance(node, yaml.SequenceNode):
        active.add(id(node))
        out = _Node([_convert(child, loader, memo, active, source) for child in node.value], line)
        active.discard(id(node))
    else:
        own = {id(k) for k, _ in node.value}
        loader.flatten_mapping(node)   # applies YAML merge keys (<<: *defaults): merged pairs come first
        active.add(id(node))
        values, lines, merged = {}, {}, set()
        for key_node, value_node in node.value:
            key_line = key_node.start_mark.line + 1
            if not isinstance(key_node, yaml.ScalarNode):
                raise SpecError("a key must be a plain word", path=source, line=key_line,
                                hint="write keys like `name:` or `walls:`")
            key = str(key_node.value)
            if id(key_node) not in own:
                merged.add(key)
            elif key in values and key not in merged:
                raise SpecError(f"key '{key}' is given twice in the same block", path=source, line=key_line,
                                hint=f"keep one; the first is on line {lines[key]}")
            else:
                merged.discard(key)   # the block's own value overrides the merged one; a third is a duplicate
            values[key] = _convert(value_node, loader, memo, active, source)
            lines[key] = key_line
        active.discard(id(node))
        out = _Node(values, line, lines)
    memo[id(node)] = out
    return out


class _Reader:
    """Turns the composed nodes into spec dataclasses, checking each value where it is read."""

    def __init__(self, source: str | None):
        self.source = source

    def fail(self, message: str, line: int | None, hint: str | None = None) -> NoReturn:
        raise SpecError(message, path=self.source, line=line, hint=hint)

    # ----------------------------------------------------------------------------------------- value checks
    def mapping(self, node: _Node, what: str, keys: tuple[str, ...], required: tuple[str, ...] = ()) -> dict:
        if not isinstance(node.value, dict):
            self.fail(f"{what} must be a block of keys ({', '.join(k + ':' for k in keys[:3])} …), "
                      f"not {_describe(node.value)}", node.line,
                      hint=f"{what} takes: {', '.join(keys)}")
        for key in node.value:
            if key not in keys:
                self.fail(f"unknown key '{key}' in {what}{did_you_mean(key, keys)}", node.key_lines[key],
                          hint=f"{what} takes: {', '.join(keys)}")
        for key in required:
            if key not in node.value:
                self.fail(f"{what} has no '{key}'", node.line, hint=f"add {_EXAMPLE.get(key, key + ': …')}")
        return node.value

    def listing(self, node: _Node | None, what: str) -> list[_Node]:
        if node is None or node.value is None:
            return []
        if not isinstance(node.value, list):
            self.fail(f"{what} must be a list, not {_describe(node.value)}", node.line,
                      hint="start each item on its own line with '- ', or write [item, item]")
        return node.value

    def number(self, node: _Node, what: str, hint: str | None = None) -> float:
        value = node.value
        if isinstance(value, str) and not node.style and _EXPONENT_NUMBER.match(value):
            value = float(value)   # 1e-05 as JSON writes it: a number, though YAML 1.1 reads text
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(f"{what} must be a number, not {_describe(value)}", node.line,
                      hint=hint or "write a plain number in metres, without quotes or units")
        if isinstance(value, int) and abs(value) > 1e300:
            self.fail(f"{what} is a {len(str(abs(value)))}-digit number", node.line,
                      hint=hint or "write a plain number in metres")
        value = float(value)
        if not math.isfinite(value):
            self.fail(f"{what} must be a finite number, not {value}", node.line,
                      hint=hint or "write a plain number in metres")
        return value

    def length(self, node: _Node, what: str) -> float:
        """A size: more than 0 (at least 1 mm) and at most 1000 m."""
        value = self.number(node, what)
        if value <= 0:
            self.fail(f"{what} must be more than 0, not {_m(value)}", node.line, hint="sizes are in metres")
        if value < MIN_SIZE:
            self.fail(f"{what} is {value:g} m: less than 1 mm", node.line, hint="sizes are in metres")
        if value > LIMIT:
            self.fail(f"{what} is {_m(value)} m: more than {LIMIT:g} m", node.line,
                      hint="sizes are in metres; did you write millimetres?")
        return value

    def distance(self, node: _Node, what: str) -> float:
        """A distance that may be 0 (offsets, sills), at most 1000 m."""
        value = self.number(node, what)
        if value < 0:
            self.fail(f"{what} must not be negative ({_m(value)})", node.line, hint="distances are in metres")
        if value > LIMIT:
            self.fail(f"{what} is {_m(value)} m: more than {LIMIT:g} m", node.line, hint="distances are in metres")
        return value

    def coordinate(self, node: _Node, what: str) -> float:
        value = self.number(node, what)
        if abs(value) > LIMIT:
            self.fail(f"{what} is {_m(value)}: farther than {LIMIT:g} m from the origin", node.line,
                      hint="coordinates are in metres; did you write millimetres?")
        return value

    def angle(self, node: _Node, what: str) -> float:
        value = self.number(node, what, hint="write the angle in radians, e.g. 1.5708 for 90 degrees")
        if abs(value) > 2 * math.pi + _EPS:
            self.fail(f"{what} is {_m(value)}: angles are in radians, between -6.2832 and 6.2832", node.line,
                      hint=f"for {value:g} degrees write {math.radians(math.fmod(value, 360)):.4f}")
        return value

    def point(self, node: _Node, what: str) -> Point:
        value = node.value
        if not isinstance(value, list) or len(value) != 2:
            self.fail(f"{what} must be a point [x, y], not {_describe_sized(value)}", node.line,
                      hint="write two numbers in metres, e.g. [1.0, 2.5]")
        return (self.coordinate(value[0], f"x of {what}"), self.coordinate(value[1], f"y of {what}"))

    def text(self, node: _Node, what: str, choices: tuple[str, ...]) -> str:
        value = node.value
        if isinstance(value, str) and value in choices:
            return value
        guess = did_you_mean(str(value).lower(), choices, cutoff=0.5)
        shown = f"'{value}'" if isinstance(value, str) else _describe(value)
        self.fail(f"{what} must be one of {', '.join(choices)}, not {shown}{guess}", node.line,
                  hint=f"write one of: {', '.join(choices)}")

    def material(self, node: _Node, what: str) -> Material:
        value = node.value
        if isinstance(value, dict):
            keys = self.mapping(node, what, MATERIAL_KEYS)
            if len(keys) != 1:
                self.fail(f"{what} needs exactly one of 'script' or 'rgba'", node.line,
                          hint="e.g. material: Gazebo/Wood or material: {rgba: [0.8, 0.2, 0.2, 1]}")
            key, inner = next(iter(keys.items()))
            if key == "rgba":
                return Material(script=None, rgba=self.rgba(inner, what))
            if not isinstance(inner.value, str):
                self.fail(f"{what} script must be text, not {_describe(inner.value)}", inner.line,
                          hint="e.g. script: Gazebo/Wood")
            return Material(script=self.script(inner, what))
        if isinstance(value, list):
            return Material(script=None, rgba=self.rgba(node, what))
        if isinstance(value, str):
            return Material(script=self.script(node, what))
        self.fail(f"{what} must be a Gazebo material name or an [r, g, b, a] colour, not {_describe(value)}",
                  node.line, hint="e.g. material: Gazebo/Wood or material: [0.8, 0.2, 0.2, 1]")

    def script(self, node: _Node, what: str) -> str:
        name = node.value.strip()
        if not name:
            self.fail(f"{what} is empty", node.line, hint="write a Gazebo material like Gazebo/Grey, or give a "
                                                           "colour [r, g, b, a]")
        if name in GAZEBO_MATERIALS:
            return name
        full = name if "/" in name else f"Gazebo/{name}"
        close = difflib.get_close_matches(full, GAZEBO_MATERIALS, n=1, cutoff=0.75)
        folded = {m.lower(): m for m in GAZEBO_MATERIALS}
        if "/" not in name or full.lower() in folded or (full.startswith("Gazebo/") and close):
            guess = folded.get(full.lower()) or (close[0] if close else "Gazebo/Grey")
            self.fail(f"{what} '{name}' is not a Gazebo material; did you mean '{guess}'?", node.line,
                      hint="Gazebo's materials are written like Gazebo/Grey, Gazebo/Wood, Gazebo/Bricks "
                           "(capitals matter), or give a colour [r, g, b, a]")
        if not re.fullmatch(r"[A-Za-z0-9_.\-]+(/[A-Za-z0-9_.\-]+)+", name):
            self.fail(f"{what} '{name}' is not a material script name", node.line,
                      hint="write it like Gazebo/Grey, or give a colour [r, g, b, a]")
        return name

    def rgba(self, node: _Node, what: str) -> tuple[float, float, float, float]:
        value = node.value
        if not isinstance(value, list) or len(value) not in (3, 4):
            self.fail(f"{what} colour must be a list [r, g, b, a] of numbers from 0 to 1, not "
                      f"{_describe_sized(value)}",
                      node.line, hint="e.g. [0.8, 0.2, 0.2, 1]")
        parts = [self.number(v, f"{what} colour component") for v in value]
        for v, part in zip(value, parts):
            if not 0 <= part <= 1:
                self.fail(f"{what} colour component {_m(part)} is outside 0–1", v.line,
                          hint="colours are fractions: 255 is 1, 128 is 0.5")
        return tuple(parts + [1.0] * (4 - len(parts)))

    def name(self, node: _Node, what: str) -> str:
        return check_name(node.value, what, path=self.source, line=node.line)

    # ------------------------------------------------------------------------------------------- sections
    def spec(self, root: _Node | None) -> Spec:
        if root is None:
            self.fail("the spec is empty", None, hint="start from the one `worldgen new NAME` writes")
        if not isinstance(root.value, dict):
            self.fail(f"a spec must be a block of keys (name:, walls:, rooms: …), not {_describe(root.value)}",
                      root.line, hint="start from the one `worldgen new NAME` writes")
        from .maps import is_map_yaml, map_spec

        if is_map_yaml(root.value):   # a ROS map_server map's own YAML
            return map_spec(self, root)
        keys = self.mapping(root, "the spec", TOP_KEYS, required=("name",))
        name = self.name(keys["name"], "the spec's name")
        style = self.style(keys["walls"], "walls", WallStyle()) if "walls" in keys else WallStyle()

        rooms = tuple(self.room(n, i, style) for i, n in enumerate(self.listing(keys.get("rooms"), "rooms")))
        seen: dict[str, int | None] = {}
        for room in rooms:
            if room.name in seen:
                self.fail(f"two rooms are named '{room.name}'", room.line,
                          hint=f"rename one; the other is on line {seen[room.name]}")
            seen[room.name] = room.line

        segments = [self.segment(n, i, style)
                    for i, n in enumerate(self.listing(keys.get("segments"), "segments"))]
        obstacles = [self.obstacle(n, i) for i, n in enumerate(self.listing(keys.get("obstacles"), "obstacles"))]
        grid_robot = None
        if "grid" in keys:
            grid_segments, posts, grid_robot = self.grid(keys["grid"], style)
            segments += grid_segments
            obstacles += posts
        if "map" in keys:
            from .maps import spec_map_parts

            map_segments, posts = spec_map_parts(self, keys["map"], style)
            segments += map_segments
            obstacles += posts
        names: dict[str, int | None] = {}
        for ob in obstacles:
            if ob.name is None:
                continue
            if ob.name == name or ob.name in names:
                other = "the spec itself" if ob.name == name else f"the obstacle on line {names[ob.name]}"
                self.fail(f"obstacle name '{ob.name}' is already used by {other}", ob.line,
                          hint="give every obstacle its own name")
            names[ob.name] = ob.line

        robot = self.robot(keys["robot"], grid_robot) if "robot" in keys else None
        if robot is None and grid_robot is not None:
            robot = RobotPose(at=grid_robot[0], yaw=grid_robot[1], line=keys["grid"].line)
        if not (rooms or segments or obstacles):
            self.fail("the spec has no rooms, segments, grid, map or obstacles: there is nothing to build", root.line,
                      hint="add a room, e.g. rooms: [{name: main, rect: {center: [0, 0], size: [5, 5]}}]")
        return Spec(name=name, style=style, rooms=rooms, segments=tuple(segments), obstacles=tuple(obstacles),
                    robot=robot, source=self.source)

    def style(self, node: _Node, what: str, base: WallStyle) -> WallStyle:
        if node.value is None:
            return base
        keys = self.mapping(node, what, WALL_KEYS)
        return WallStyle(
            thickness=self.length(keys["thickness"], f"{what} thickness") if "thickness" in keys else base.thickness,
            height=self.length(keys["height"], f"{what} height") if "height" in keys else base.height,
            material=self.material(keys["material"], f"{what} material") if "material" in keys else base.material,
        )

    def room(self, node: _Node, index: int, base: WallStyle) -> Room:
        keys = self.mapping(node, f"room {index + 1}", ROOM_KEYS, required=("name",))
        name = self.name(keys["name"], "room name")
        what = f"room '{name}'"
        if ("rect" in keys) == ("polygon" in keys):
            self.fail(f"{what} needs exactly one of 'rect' or 'polygon'", node.line,
                      hint="e.g. rect: {center: [0, 0], size: [5, 5]} or polygon: [[0, 0], [5, 0], [5, 5], [0, 5]]")
        style = self.style(keys["walls"], f"walls of {what}", base) if "walls" in keys else base
        if "rect" in keys:
            vertices = self.rect(keys["rect"], what, style)
        else:
            vertices = self.polygon(keys["polygon"], what)
        lengths = [math.dist(vertices[i], vertices[(i + 1) % len(vertices)]) for i in range(len(vertices))]
        openings = self.openings(keys.get("openings"), what, lengths, style, on_segment=False)
        return Room(name=name, vertices=vertices, style=style, openings=openings, line=node.line)

    def rect(self, node: _Node, what: str, style: WallStyle) -> tuple[Point, ...]:
        keys = self.mapping(node, f"rect of {what}", RECT_KEYS, required=RECT_KEYS)
        cx, cy = self.point(keys["center"], f"center of {what}")
        size = keys["size"]
        if not isinstance(size.value, list) or len(size.value) != 2:
            self.fail(f"size of {what} must be [width, depth] in metres, not {_describe_sized(size.value)}", size.line,
                      hint="e.g. size: [5, 4]")
        w = self.length(size.value[0], f"width (x size) of {what}")
        d = self.length(size.value[1], f"depth (y size) of {what}")
        for extent, axis, v in ((w, "x", size.value[0]), (d, "y", size.value[1])):
            if extent <= style.thickness + _EPS:
                self.fail(f"{what} is {_m(extent)} m along {axis}: not more than its walls' thickness "
                          f"{_m(style.thickness)} m, so it has no floor", v.line,
                          hint="sizes are between the walls' centre-lines; make the room larger")
        if max(abs(cx) + w / 2, abs(cy) + d / 2) > LIMIT:
            self.fail(f"{what} reaches farther than {LIMIT:g} m from the origin", node.line,
                      hint="coordinates are in metres")
        x0, x1, y0, y1 = (round(v, 9) for v in (cx - w / 2, cx + w / 2, cy - d / 2, cy + d / 2))
        return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))

    def polygon(self, node: _Node, what: str) -> tuple[Point, ...]:
        items = node.value
        if not isinstance(items, list):
            self.fail(f"polygon of {what} must be a list of points [[x, y], …], not {_describe(items)}",
                      node.line, hint="e.g. polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]")
        points = [self.point(p, f"corner {i} of {what}") for i, p in enumerate(items)]
        if len(points) >= 4 and math.dist(points[0], points[-1]) < MIN_SIZE:
            points.pop()   # the first point repeated at the end closes the ring: the same polygon
        if len(points) < 3:
            self.fail(f"the polygon of {what} has {len(points)} point{'s' if len(points) != 1 else ''}; "
                      "a room needs at least 3", node.line,
                      hint="list the corners of the room in order, e.g. [[0, 0], [4, 0], [4, 3], [0, 3]]")
        for j in range(len(points)):
            for i in range(j):
                gap = math.dist(points[i], points[j])
                if gap < MIN_SIZE:   # closer than 1 mm: one point, for the geometry too
                    near = f" to within {_m(gap * 1000)} mm" if gap else ""
                    self.fail(f"corner {j} of {what} repeats corner {i} ({_m(points[i][0])}, {_m(points[i][1])})"
                              f"{near}", items[j].line,
                              hint="remove it: list each corner once; only the first may be repeated at the end")
        crossing = _crossing_walls(points)
        if crossing:
            i, j = crossing
            self.fail(f"walls {i} and {j} of {what} cross or overlap", items[j].line,
                      hint="list the corners in order around the room, either direction; "
                           "wall i runs from corner i to corner i+1, counting from 0")
        area = sum(points[i][0] * points[(i + 1) % len(points)][1] - points[(i + 1) % len(points)][0] * points[i][1]
                   for i in range(len(points))) / 2
        if abs(area) < 1e-6:
            self.fail(f"the points of the polygon of {what} lie on one line: it has no floor", node.line,
                      hint="list the corners of the room in order around it")
        return tuple(points)

    def openings(self, node: _Node | None, owner: str, lengths: list[float], style: WallStyle, *,
                 on_segment: bool) -> tuple[Opening, ...]:
        openings = [self.opening(n, i, owner, lengths, style, on_segment)
                    for i, n in enumerate(self.listing(node, f"openings of {owner}"))]
        ordered = sorted(enumerate(openings), key=lambda io: (io[1].wall, io[1].offset))
        for (i, a), (j, b) in zip(ordered, ordered[1:]):
            if a.wall == b.wall and b.offset < a.offset + a.width + _EPS:
                first, second = sorted((i, j))
                self.fail(f"openings {first + 1} and {second + 1} of {owner} overlap or touch on wall {a.wall} "
                          f"({_m(a.offset)}–{_m(a.offset + a.width)} m and {_m(b.offset)}–{_m(b.offset + b.width)} "
                          "m along it)", openings[second].line,
                          hint="change the offset of one, or make them one wider opening")
        return tuple(openings)

    def opening(self, node: _Node, index: int, owner: str, lengths: list[float], style: WallStyle,
                on_segment: bool) -> Opening:
        label = f"opening {index + 1} of {owner}"
        keys = self.mapping(node, label, OPENING_KEYS, required=("type",) if on_segment else ("type", "wall"))
        kind = self.text(keys["type"], f"type of {label}", OPENING_TYPES)
        what = f"{kind} {index + 1} of {owner}"
        wall = 0
        if "wall" in keys:
            wnode = keys["wall"]
            if isinstance(wnode.value, bool) or not isinstance(wnode.value, int):
                self.fail(f"wall of {what} must be a wall number, not {_describe(wnode.value)}", wnode.line,
                          hint="walls are numbered from 0: wall i runs from point i to point i+1")
            wall = wnode.value
            if not 0 <= wall < len(lengths):
                hint = ("a segment is a single wall: write wall: 0 or leave it out" if on_segment else
                        f"use wall 0 to {len(lengths) - 1}: wall i runs from corner i to the next; a rect's "
                        "wall 0 is the bottom (min y) one, then counter-clockwise")
                self.fail(f"{what} is on wall {wall}, but {owner} has {len(lengths)} "
                          f"wall{'s' if len(lengths) > 1 else ''}", wnode.line, hint=hint)
        length, t, top = lengths[wall], style.thickness, style.height
        where = f"wall {wall}"

        def line(key: str) -> int:
            return keys[key].line if key in keys else node.line

        width = self.length(keys["width"], f"width of {what}") if "width" in keys else (
            DOOR_WIDTH if kind == "door" else WINDOW_WIDTH)
        if kind == "door":
            height = self.length(keys["height"], f"height of {what}") if "height" in keys else min(DOOR_HEIGHT, top)
            sill = self.distance(keys["sill"], f"sill of {what}") if "sill" in keys else 0.0
            if sill > 0:
                self.fail(f"{what} has a sill of {_m(sill)} m, but a door starts at the floor", keys["sill"].line,
                          hint="remove the sill, or make it type: window")
        else:
            height = self.length(keys["height"], f"height of {what}") if "height" in keys else WINDOW_HEIGHT
            sill = self.distance(keys["sill"], f"sill of {what}") if "sill" in keys else WINDOW_SILL

        room_for = length - t
        if room_for <= _EPS:
            self.fail(f"{what} is on {where}, which is {_m(length)} m long: no longer than the walls are thick "
                      f"({_m(t)} m), so it has no room for an opening", node.line,
                      hint="put the opening on a longer wall, or remove it")
        if width > room_for + _EPS:
            self.fail(f"{what} is {_m(width)} m wide, but {where} has only {_m(room_for)} m between its "
                      f"corners ({_m(length)} m long, less {_m(t)} m of wall thickness)", line("width"),
                      hint=f"make the width at most {_m(room_for)}, or put it on a longer wall")
        offset = self.distance(keys["offset"], f"offset of {what}") if "offset" in keys else (length - width) / 2
        lo, hi = t / 2, length - t / 2 - width
        span = f"use an offset from {_m(lo)} to {_m(hi)} m, or leave offset out to centre the {kind}"
        if offset < lo - _EPS:
            self.fail(f"{what} starts {_m(offset)} m along {where}: inside the corner, which takes the first "
                      f"{_m(lo)} m (half the wall thickness)", line("offset"), hint=span)
        if offset + width > length - lo + _EPS:
            self.fail(f"{what} ends {_m(offset + width)} m along {where}, which is {_m(length)} m long: inside the "
                      f"corner, which takes the last {_m(lo)} m (half the wall thickness)", line("offset"), hint=span)
        if kind == "door" and height > top + _EPS:
            self.fail(f"{what} is {_m(height)} m tall, but the walls of {owner} are {_m(top)} m", line("height"),
                      hint=f"make the door at most {_m(top)} m tall, or raise the walls with walls: {{height: …}}")
        if kind == "window" and sill + height > top + _EPS:
            self.fail(f"{what} reaches {_m(sill + height)} m up (sill {_m(sill)} + height {_m(height)}), above the "
                      f"{_m(top)} m walls of {owner}", line("height" if "height" in keys else "sill"),
                      hint=f"make sill + height at most {_m(top)} m")
        return Opening(type=kind, wall=wall, offset=round(offset, 9), width=width, height=height, sill=sill,
                       line=node.line)

    def segment(self, node: _Node, index: int, base: WallStyle) -> Segment:
        what = f"segment {index + 1}"
        keys = self.mapping(node, what, SEGMENT_KEYS, required=("from", "to"))
        start = self.point(keys["from"], f"'from' of {what}")
        end = self.point(keys["to"], f"'to' of {what}")
        length = math.dist(start, end)
        if length < MIN_SIZE:
            self.fail(f"{what} starts and ends at the same point", keys["to"].line,
                      hint="give 'from' and 'to' two different points")
        style = self.style(keys["walls"], f"walls of {what}", base) if "walls" in keys else base
        openings = self.openings(keys.get("openings"), what, [length], style, on_segment=True)
        return Segment(start=start, end=end, style=style, openings=openings, line=node.line)

    def obstacle(self, node: _Node, index: int) -> Obstacle:
        label = f"obstacle {index + 1}"
        keys = self.mapping(node, label, OBSTACLE_KEYS, required=("shape",))
        shape = self.text(keys["shape"], f"shape of {label}", SHAPES)
        name = self.name(keys["name"], "obstacle name") if "name" in keys else None
        what = f"obstacle '{name}'" if name else label
        for key in keys:
            if key in ("size", "radius", "height") and key not in SHAPE_KEYS[shape]:
                self.fail(f"{what} is a {shape}, which has no '{key}'", keys[key].line,
                          hint=f"a {shape} takes {' and '.join(SHAPE_KEYS[shape])}")
        for key in SHAPE_KEYS[shape]:
            if key not in keys:
                example = "size: [0.5, 0.5, 0.5]" if key == "size" else _EXAMPLE[key]
                self.fail(f"{what} has no '{key}'", node.line, hint=f"a {shape} takes "
                          f"{' and '.join(SHAPE_KEYS[shape])}; add {example}")
        if "at" not in keys:
            self.fail(f"{what} has no 'at'", node.line, hint="add at: [x, y], the centre of its footprint")
        size = radius = height = None
        if shape == "box":
            s = keys["size"]
            if not isinstance(s.value, list) or len(s.value) != 3:
                self.fail(f"size of {what} must be [x, y, z] in metres, not {_describe_sized(s.value)}", s.line,
                          hint="e.g. size: [0.5, 0.4, 0.8]")
            size = tuple(self.length(v, f"{axis} size of {what}") for v, axis in zip(s.value, "xyz"))
        else:
            radius = self.length(keys["radius"], f"radius of {what}")
            if shape == "cylinder":
                height = self.length(keys["height"], f"height of {what}")
        return Obstacle(
            shape=shape, at=self.point(keys["at"], f"'at' of {what}"),
            yaw=self.angle(keys["yaw"], f"yaw of {what}") if "yaw" in keys else 0.0,
            size=size, radius=radius, height=height,
            material=self.material(keys["material"], f"material of {what}") if "material" in keys else Material(),
            name=name, line=node.line)

    def robot(self, node: _Node, grid_robot: tuple[Point, float] | None) -> RobotPose:
        keys = self.mapping(node, "robot", ROBOT_KEYS)
        model = self.text(keys["model"], "robot model", ROBOT_MODELS) if "model" in keys else "burger"
        if grid_robot is not None:
            if "at" in keys or "yaw" in keys:
                self.fail("the robot is placed twice: by the grid and by robot: at/yaw", node.line,
                          hint="remove the R from the grid, or at/yaw from robot:")
            return RobotPose(model=model, at=grid_robot[0], yaw=grid_robot[1], line=node.line)
        if "at" not in keys:
            self.fail("robot has no 'at'", node.line, hint="add at: [x, y], where the robot spawns")
        return RobotPose(model=model, at=self.point(keys["at"], "robot 'at'"),
                         yaw=self.angle(keys["yaw"], "robot yaw") if "yaw" in keys else 0.0, line=node.line)

    def grid(self, node: _Node, base: WallStyle) -> tuple[list[Segment], list[Obstacle], tuple | None]:
        keys = self.mapping(node, "grid", GRID_KEYS, required=("rows",))
        cell = self.length(keys["cell"], "grid cell") if "cell" in keys else DEFAULT_CELL
        origin = self.point(keys["origin"], "grid origin") if "origin" in keys else (0.0, 0.0)
        height = self.length(keys["height"], "grid height") if "height" in keys else base.height
        material = self.material(keys["material"], "grid material") if "material" in keys else base.material
        rows_node = keys["rows"]
        value = rows_node.value
        if isinstance(value, str):
            if rows_node.style == ">":
                self.fail("grid rows are folded into one line by '>'", rows_node.line,
                          hint="write rows: | for a literal block, so that each line stays a row")
            rows = value.split("\n")
            if rows and rows[-1] == "":
                rows.pop()
            if rows_node.style == "|":   # a literal block: row i is i + 1 lines below 'rows: |'
                row_lines = [rows_node.line + 1 + i for i in range(len(rows))]
            else:                        # one quoted text: every row is on its line
                row_lines = [rows_node.line] * len(rows)
        elif isinstance(value, list):
            for i, row in enumerate(value):
                if not isinstance(row.value, str):
                    self.fail(f"grid row {i + 1} must be a line of text, not {_describe(row.value)}", row.line,
                              hint='quote each row, e.g. - "#####" (an unquoted # starts a comment), or write '
                                   "rows: | and the grid below it")
            rows, row_lines = [r.value for r in value], [r.line for r in value]
        else:
            self.fail(f"grid rows must be text lines, not {_describe(value)}", rows_node.line,
                      hint="write rows: | and the grid below it, one line per row")
        return self.grid_parts(rows, row_lines, cell, origin, WallStyle(cell, height, material), rows_node.line)

    def grid_parts(self, rows, row_lines, cell, origin, style, line):
        columns = max((len(r) for r in rows), default=0)
        if not rows or not columns:
            self.fail("the grid is empty", line, hint="draw walls with #, one character per cell")
        extent = [origin[0], origin[1], origin[0] + columns * cell, origin[1] + len(rows) * cell]
        if max(abs(v) for v in extent) > LIMIT:
            self.fail(f"the grid reaches farther than {LIMIT:g} m from the origin ({len(rows)} rows × {columns} "
                      f"columns of {_m(cell)} m)", line, hint="use a smaller cell, in metres, or a smaller grid")
        plan = plan_grid(rows, cell, origin, source=self.source, row_lines=row_lines)
        segments = [Segment(start=a, end=b, style=style, line=line) for a, b in plan.walls]
        posts = [Obstacle(shape="box", at=at, size=(cell, cell, style.height), material=style.material,
                          name=f"{POST_PREFIX}{r + 1}_{c + 1}", line=row_lines[r]) for r, c, at in plan.posts]
        return segments, posts, plan.robot

    def grid_file(self, text: str, stem: str) -> Spec:
        """A plain ``.txt`` grid: the whole file is the grid, with the default cell and walls."""
        rows = text.split("\n")
        if rows and rows[-1] == "":
            rows.pop()
        rows = [r.rstrip("\r") for r in rows]
        name = _suggest_name(stem)
        segments, posts, robot = self.grid_parts(rows, list(range(1, len(rows) + 1)), DEFAULT_CELL, (0.0, 0.0),
                                                 WallStyle(thickness=DEFAULT_CELL), 1)
        pose = RobotPose(at=robot[0], yaw=robot[1], line=1) if robot else None
        return Spec(name=name, segments=tuple(segments), obstacles=tuple(posts), robot=pose, source=self.source)


def _crossing_walls(points: list[Point]) -> tuple[int, int] | None:
    """The first pair of walls (edges) of a closed polygon that cross, touch or fold back, or None."""
    n = len(points)
    edges = [(points[i], points[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        a, b = edges[i]
        for j in range(i + 1, n):
            c, d = edges[j]
            if j == i + 1 or (i == 0 and j == n - 1):
                shared, p, q = (b, a, d) if j == i + 1 else (a, b, c)
                u, v = (p[0] - shared[0], p[1] - shared[1]), (q[0] - shared[0], q[1] - shared[1])
                if abs(u[0] * v[1] - u[1] * v[0]) <= 1e-9 * math.hypot(*u) * math.hypot(*v) and \
                        u[0] * v[0] + u[1] * v[1] > 0:
                    return (i, j)   # the two walls fold back over each other
            elif _segments_meet(a, b, c, d):
                return (i, j)
    return None


def _segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool:
    def orient(p, q, r):
        value = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        return 0 if abs(value) <= 1e-9 else (1 if value > 0 else -1)

    def within(p, q, r):   # q on segment p–r, given the three are collinear
        return min(p[0], r[0]) - 1e-9 <= q[0] <= max(p[0], r[0]) + 1e-9 and \
            min(p[1], r[1]) - 1e-9 <= q[1] <= max(p[1], r[1]) + 1e-9

    o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
    if o1 != o2 and o3 != o4 and 0 not in (o1, o2, o3, o4):
        return True
    return (o1 == 0 and within(a, c, b)) or (o2 == 0 and within(a, d, b)) or \
        (o3 == 0 and within(c, a, d)) or (o4 == 0 and within(c, b, d))
