"""Reading a floorplan spec: a YAML/JSON (or ASCII-grid, or ROS map_server map) file read into the validated,
immutable dataclasses of :mod:`worldgen.spec.model`.

The entry points are here (``load_spec``, ``parse_spec``, ``spec_beside``, ``starter_spec``), and ``read_spec``,
which reads a spec's top level. The text is composed into line-numbered YAML nodes (:mod:`.nodes`); each part is
read by a function of its own (:mod:`.walls`: wall style, rooms, segments, openings; :mod:`.objects`: obstacles,
robot; :mod:`.markings`: lines and patches on the floor; :mod:`.grid_spec`: an ASCII grid; :mod:`.maps`: a
map_server map), each value by one of :mod:`.values`.
Every error is a :class:`~worldgen.core.errors.SpecError` naming the file and line.
"""

from __future__ import annotations

from pathlib import Path

from ..core.errors import SpecError
from ..core.inputs import MAX_SPEC_BYTES, read_text_capped, refuse_unread
from . import values
from .grid_spec import read_grid, read_grid_file
from .messages import check_name, describe
from .markings import read_markings
from .model import MARKINGS_MODEL, TOP_KEYS, RobotPose, Spec, WallStyle
from .nodes import Node, compose
from .objects import read_obstacle, read_robot
from .values import Source
from .walls import read_room, read_segment, read_style
from ..core.resources import render_template
from .maps import IMAGE_SUFFIXES, is_map_yaml, map_spec, spec_map_parts


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
    path = Path(path)
    if path.suffix.lower() in IMAGE_SUFFIXES:
        raise SpecError("is an image, not a spec", path=path,
                        hint="for a ROS map, give the map's YAML (map.yaml, as map_saver writes it beside the image)")
    refuse_unread(path, "a spec", SpecError)
    try:
        text = read_text_capped(path, MAX_SPEC_BYTES, SpecError, "spec")
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
        return read_grid_file(Source(str(path)), text, path.stem)
    if path.suffix.lower() == ".json":
        text = text.replace("\t", "  ")   # JSON allows tabs between tokens, YAML does not; both keep the lines
    return parse_spec(text, str(path))


def parse_spec(text: str, source: str | None = None) -> Spec:
    """Validate a spec given as YAML (or JSON) text; ``source`` names it in messages."""
    return read_spec(Source(source), compose(text, source))


# The specs ``worldgen new --template T NAME`` writes: template name → file under templates/.
STARTERS = {"room": "spec/starter.yaml.j2", "line-track": "spec/line_track.yaml.j2"}


def starter_spec(name: str, template: str = "room") -> str:
    """The commented starter spec ``worldgen new NAME`` writes: by default (``room``) a closed 5 m × 5 m room with
    a window, an obstacle and the robot in the middle, a door offered commented out; ``line-track`` a closed
    4 × 3 m room with a loop of yellow tape on its floor and a Waffle Pi on the tape (``templates/spec/``)."""
    check_name(name, "the world name")
    return render_template(STARTERS[template], name=name)


def read_spec(src: Source, root: Node | None) -> Spec:
    """A whole spec from its composed YAML (or a map_server map's own YAML, read by :mod:`.maps`): its name and wall
    style, then its rooms, segments, obstacles, grid, map, lines and patches and robot, each read by its own
    function, then the checks across them (names used twice, nothing to build)."""
    if root is None:
        src.fail("the spec is empty", None, hint="start from the one `worldgen new NAME` writes")
    if not isinstance(root.value, dict):
        bridge = isinstance(root.value, list) and any(isinstance(item.value, dict) and "ros_topic_name" in item.value
                                                      for item in root.value)
        src.fail("this is a ros_gz_bridge parameter file (a list of topics), not a floorplan spec" if bridge else
                 f"a spec must be a block of keys (name:, walls:, rooms: …), not {describe(root.value)}", root.line,
                 hint="validate the package that holds it: its launch file and world are checked with it" if bridge
                 else "start from the one `worldgen new NAME` writes")

    if is_map_yaml(root.value):   # a ROS map_server map's own YAML
        return map_spec(src, root)
    keys = values.mapping(src, root, "the spec", TOP_KEYS, required=("name",))
    name = values.name(src, keys["name"], "the spec's name")
    style = read_style(src, keys["walls"], "walls", WallStyle()) if "walls" in keys else WallStyle()

    rooms = tuple(read_room(src, n, i, style)
                  for i, n in enumerate(values.listing(src, keys.get("rooms"), "rooms")))
    seen: dict[str, int | None] = {}
    for room in rooms:
        if room.name in seen:
            src.fail(f"two rooms are named '{room.name}'", room.line,
                     hint=f"rename one; the other is on line {seen[room.name]}")
        seen[room.name] = room.line

    segments = [read_segment(src, n, i, style)
                for i, n in enumerate(values.listing(src, keys.get("segments"), "segments"))]
    obstacles = [read_obstacle(src, n, i)
                 for i, n in enumerate(values.listing(src, keys.get("obstacles"), "obstacles"))]
    grid_robot = None
    if "grid" in keys:
        grid_segments, posts, grid_robot = read_grid(src, keys["grid"], style)
        segments += grid_segments
        obstacles += posts
    if "map" in keys:
        map_segments, posts = spec_map_parts(src, keys["map"], style)
        segments += map_segments
        obstacles += posts
    names: dict[str, int | None] = {}
    for ob in obstacles:
        if ob.name is None:
            continue
        if ob.name == name or ob.name in names:
            other = "the spec itself" if ob.name == name else f"the obstacle on line {names[ob.name]}"
            src.fail(f"obstacle name '{ob.name}' is already used by {other}", ob.line,
                     hint="give every obstacle its own name")
        names[ob.name] = ob.line

    lines, patches = read_markings(src, keys)
    if lines or patches:
        taken = [ob for ob in obstacles if ob.name == MARKINGS_MODEL]
        if taken or (name == MARKINGS_MODEL and (rooms or segments)):
            src.fail(f"'{MARKINGS_MODEL}' names the model of the spec's lines and patches, so "
                     f"{'an obstacle' if taken else 'the spec'} cannot be called that",
                     taken[0].line if taken else keys["name"].line, hint="choose another name")
    robot = read_robot(src, keys["robot"], grid_robot) if "robot" in keys else None
    if robot is None and grid_robot is not None:
        robot = RobotPose(at=grid_robot[0], yaw=grid_robot[1], line=keys["grid"].line)
    if not (rooms or segments or obstacles or lines or patches):
        src.fail("the spec has no rooms, segments, grid, map, obstacles, lines or patches: there is nothing to "
                 "build", root.line,
                 hint="add a room, e.g. rooms: [{name: main, rect: {center: [0, 0], size: [5, 5]}}]")
    return Spec(name=name, style=style, rooms=rooms, segments=tuple(segments), obstacles=tuple(obstacles),
                robot=robot, source=src.path, lines=lines, patches=patches)
