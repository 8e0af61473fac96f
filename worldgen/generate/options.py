"""Each kind's options as a frozen dataclass, the command-line flags that set them (one table, which the CLI and
the specs' header lines are both made from), and their checks.

A field left at ``None`` is sized for the robot when the world is made (a maze's cell, a door's width, the
narrowest gap); the header of a generated spec writes every option with the value it had, so the command it
shows makes the same file even after a default changes.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Dict, Optional, Tuple

from ..core.errors import InputError
from ..spec.model import ROBOT_MODELS
from .rng import MAX_SEED
from .robot import DEFAULT_ROBOT
from .text import number

KINDS = ("maze", "rooms", "clutter", "arena", "track")
Size = Tuple[float, float]
MIN_SIDE, MAX_SIDE = 1.0, 200.0   # m: a generated world's footprint, each side
MAX_COUNT = 10000


@dataclass(frozen=True)
class MazeOptions:
    size: Size = (6.0, 6.0)
    robot: str = DEFAULT_ROBOT
    cell: Optional[float] = None
    loops: float = 0.0
    exits: bool = False
    wall_height: float = 0.5


@dataclass(frozen=True)
class RoomsOptions:
    size: Size = (10.0, 8.0)
    robot: str = DEFAULT_ROBOT
    rooms: Optional[int] = None
    corridor: bool = True
    door: Optional[float] = None
    loops: float = 0.2
    furniture: int = 2
    windows: bool = True
    wall_height: float = 2.5


@dataclass(frozen=True)
class ClutterOptions:
    size: Size = (6.0, 5.0)
    robot: str = DEFAULT_ROBOT
    density: float = 0.08
    gap: Optional[float] = None
    shapes: str = "mixed"
    wall_height: float = 0.5


@dataclass(frozen=True)
class ArenaOptions:
    size: Size = (8.0, 6.0)
    robot: str = DEFAULT_ROBOT
    outline: str = "right"
    min_width: float = 1.2
    wall_height: float = 0.5


@dataclass(frozen=True)
class TrackOptions:
    size: Size = (5.0, 4.0)
    robot: str = DEFAULT_ROBOT
    min_radius: float = 0.5
    tape_width: float = 0.05
    color: str = "Gazebo/Yellow"
    wall_height: float = 0.5


OPTION_CLASSES = {"maze": MazeOptions, "rooms": RoomsOptions, "clutter": ClutterOptions, "arena": ArenaOptions,
                  "track": TrackOptions}


@dataclass(frozen=True)
class Flag:
    """A command-line flag: the field it sets, how it is written, what it takes, its help."""

    field: str
    flag: str
    type: str            # "size" | "float" | "int" | "bool" | "choice" | "text"
    help: str
    choices: Tuple[str, ...] = ()


COMMON = (
    Flag("size", "--size", "size", "the footprint, W x H metres (e.g. 6x4)"),
    Flag("robot", "--robot", "choice", "the TurtleBot3 the world is sized for: doors, gaps and turning room",
         ROBOT_MODELS),
)
WALL_HEIGHT = Flag("wall_height", "--wall-height", "float", "how tall the walls are (m)")
FLAGS: Dict[str, Tuple[Flag, ...]] = {
    "maze": COMMON + (
        Flag("cell", "--cell", "float", "the grid's cell, wall centre to wall centre (m; default: room for the "
                                        "robot to turn in place)"),
        Flag("loops", "--loops", "float", "the share of the inner walls a perfect maze keeps that are taken out "
                                          "too, making loops (0: one way between any two cells; 1: no inner walls)"),
        Flag("exits", "--exits/--closed", "bool", "an entrance on the left and an exit on the right, each into a "
                                                   "closed one-cell lobby (the robot starts in the entrance), or a "
                                                   "closed maze (the robot starts in a cell)"),
        WALL_HEIGHT),
    "rooms": COMMON + (
        Flag("rooms", "--rooms", "int", "how many rooms, a corridor counted (default: one per 14 m²)"),
        Flag("corridor", "--corridor/--no-corridor", "bool", "a corridor along the flat that most rooms open onto"),
        Flag("door", "--door", "float", "the doors' width (m; default 0.9, and at least the robot's width + 0.2)"),
        Flag("loops", "--loops", "float", "the chance that two rooms sharing a wall get a door even when they are "
                                          "already joined another way"),
        Flag("furniture", "--furniture", "int", "at most this many pieces of furniture per room, along its walls"),
        Flag("windows", "--windows/--no-windows", "bool", "windows in outer walls (above the LiDAR)"),
        WALL_HEIGHT),
    "clutter": COMMON + (
        Flag("density", "--density", "float", "the share of the floor the obstacles should cover (0 to 0.3; with "
                                               "every gap passable a room is full at about 0.1)"),
        Flag("gap", "--gap", "float", "the narrowest gap between obstacles, and between them and the walls (m; "
                                      "default: the robot's width + 0.2)"),
        Flag("shapes", "--shapes", "choice", "what stands in the room", ("mixed", "box", "cylinder")),
        WALL_HEIGHT),
    "arena": COMMON + (
        Flag("outline", "--outline", "choice", "right-angled walls on a grid, or a free polygon",
             ("right", "free")),
        Flag("min_width", "--min-width", "float", "the narrowest part of the floor, wall centre to wall centre (m)"),
        WALL_HEIGHT),
    "track": COMMON + (
        Flag("min_radius", "--min-radius", "float", "the tightest bend's radius (m; 0.5, the course track's corners, "
                                                    "which the course's line follower follows)"),
        Flag("tape_width", "--tape-width", "float", "the tape's width (m)"),
        Flag("color", "--color", "text", "the tape's colour: a Gazebo material (Gazebo/Yellow, Gazebo/Red, …)"),
        WALL_HEIGHT),
}


def make_options(kind: str, values: dict):
    """The options of ``kind`` from flag values (``None``: the default), checked."""
    if kind not in KINDS:
        raise InputError(f"there is no kind of world called '{kind}'", hint=f"choose one of {', '.join(KINDS)}")
    cls = OPTION_CLASSES[kind]
    given = {k: v for k, v in values.items() if v is not None}
    unknown = sorted(set(given) - {f.name for f in fields(cls)})
    if unknown:
        raise InputError(f"{kind} has no option {unknown[0]!r}",
                         hint=f"its options are {', '.join(f.flag.split('/')[0] for f in FLAGS[kind])}")
    options = cls(**given)
    check_options(kind, options)
    return options


def _range(value: float, low: float, high: float, flag: str, what: str | None = None) -> None:
    if not low <= value <= high:
        raise InputError(f"{flag} {number(value)} is out of range: " + (f"{what} is" if what else "it goes")
                         + f" from {number(low)} to {number(high)}",
                         hint=f"give {flag} a value from {number(low)} to {number(high)}")


def check_options(kind: str, options) -> None:
    """InputError naming the flag of the first value out of its range (sizes in metres)."""
    w, h = options.size
    for side in (w, h):
        _range(side, MIN_SIDE, MAX_SIDE, "--size", "each side")
    if options.robot not in ROBOT_MODELS:
        raise InputError(f"--robot {options.robot} is not a TurtleBot3", hint=f"use {', '.join(ROBOT_MODELS)}")
    _range(options.wall_height, 0.25, 10.0, "--wall-height", "the walls' height")
    for name, low, high in (("loops", 0.0, 1.0), ("density", 0.0, 0.3), ("cell", 0.3, 10.0),
                            ("door", 0.3, 5.0), ("gap", 0.1, 5.0), ("min_width", 0.5, 20.0),
                            ("min_radius", 0.1, 20.0), ("tape_width", 0.005, 0.5)):
        value = getattr(options, name, None)
        if value is not None:
            _range(value, low, high, "--" + name.replace("_", "-"))
    for name, low, high in (("rooms", 1, 64), ("furniture", 0, 8)):
        value = getattr(options, name, None)
        if value is not None and not low <= value <= high:
            raise InputError(f"--{name} {value} is out of range", hint=f"give --{name} from {low} to {high}")


def check_batch(seed: int, count: int) -> None:
    if not 0 <= seed <= MAX_SEED:
        raise InputError(f"--seed {seed} is out of range", hint=f"give a seed from 0 to {MAX_SEED}")
    if not 1 <= count <= MAX_COUNT:
        raise InputError(f"--count {count} is out of range", hint=f"give a count from 1 to {MAX_COUNT}")
    if seed + count - 1 > MAX_SEED:
        raise InputError(f"--seed {seed} with --count {count} runs past the last seed, {MAX_SEED}",
                         hint="start from a smaller seed")


def parse_size(text: str) -> Size:
    """``WxH`` (metres, ``x`` or ``X`` or ``*`` between) as a pair of floats; InputError otherwise."""
    parts = text.lower().replace("*", "x").replace("×", "x").split("x")
    try:
        if len(parts) == 2:
            return float(parts[0]), float(parts[1])
    except ValueError:
        pass
    raise InputError(f"--size {text!r} is not W x H", hint="write the footprint in metres as WxH, e.g. --size 6x4")


def _flag_text(flag: Flag, value) -> str:
    if flag.type == "bool":
        on, off = flag.flag.split("/")
        return on if value else off
    if flag.type == "size":
        return f"{flag.flag} {number(value[0])}x{number(value[1])}"
    if flag.type == "float":
        return f"{flag.flag} {number(value)}"
    return f"{flag.flag} {value}"


def command_line(kind: str, seed: int, options) -> str:
    """The ``worldgen generate`` command that makes exactly this world: every option written out."""
    parts = ["worldgen generate", kind, f"--seed {seed}"]
    parts += [_flag_text(f, getattr(options, f.field)) for f in FLAGS[kind] if getattr(options, f.field) is not None]
    return " ".join(parts)
