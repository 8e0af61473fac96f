"""Launch files for a world and a TurtleBot3: the writer, the spawn point, and a reader for real launch files.

The writer emits the class's launch file shape (the one of ``turtlebot3_gazebo``): args ``model``, ``x_pos``,
``y_pos``, ``z_pos``, ``yaw``; gazebo_ros's ``empty_world.launch`` included with ``world_name`` =
``$(find PKG)/worlds/WORLD`` and the usual ``paused``/``use_sim_time``/``gui``/``headless``/``debug`` args passed
through; ``robot_description`` from xacro; ``spawn_model`` named ``spawn_urdf``; optional extra nodes.

The spawn point of a world file is chosen inside its room: walls and obstacles are sliced in the robot's height
band, the free areas the walls close are found (the room holding the building's centre first), and the centre of
the largest circle inside it is taken. An explicit spawn inside a wall, closer to one than the robot's radius, or
outside the room is refused.

The reader (:func:`read_launch`) evaluates a launch file the way roslaunch does for what matters here — args and
their defaults, ``$(arg)``/``$(env)``/``$(optenv)``/``$(find)``/``$(dirname)``/``$(anon)``, groups and namespaces,
``if``/``unless``, includes with passed args — and reports the world, the robot model and every ``spawn_model``
pose, with findings for whatever cannot be resolved instead of failing. :func:`check_package` uses it to say what
would break in a catkin package.
"""

from __future__ import annotations

import math
import os
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

from .errors import InputError, WorldFileError
from .findings import Finding
from .spec import ROBOT_MODELS

MODEL_CHOICES = ("env",) + ROBOT_MODELS   # "env": the model comes from $(env TURTLEBOT3_MODEL) at run time
# Radius of the disc that holds each robot's footprint around base_footprint (ROBOTIS navigation parameters:
# burger robot_radius 0.105 m; waffle and waffle_pi footprint corners up to 0.257 m from the centre).
ROBOT_RADIUS = {"burger": 0.105, "waffle": 0.257, "waffle_pi": 0.257}
# The height band a TurtleBot3 occupies, where walls and obstacles are sliced: above a floor slab (Gazebo's
# asphalt_plane is a 0.1 m box half sunk into the ground; the validator counts slabs up to 0.1 m as floor) and up
# to the top of a burger (0.192 m) with some room.
SLICE_Z = (0.11, 0.3)
Pose = tuple[float, float, float, float]   # x, y, z, yaw


# ---------------------------------------------------------------------------------------------------------------
# Templates

def render_template(template: str, **context) -> str:
    """Render ``templates/TEMPLATE`` (Jinja2) with ``context``. XML templates (``*.xml.j2``, ``*.launch.j2``) escape
    their values; undefined names are errors, so a template and its caller cannot drift apart silently."""
    import jinja2

    from .resources import templates_dir

    env = _JINJA.get("env")
    if env is None:
        env = jinja2.Environment(
            loader=jinja2.FileSystemLoader(str(templates_dir())),
            autoescape=jinja2.select_autoescape(enabled_extensions=("xml.j2", "launch.j2"),
                                                default_for_string=False),
            undefined=jinja2.StrictUndefined, keep_trailing_newline=True, trim_blocks=True, lstrip_blocks=True)
        _JINJA["env"] = env
    return env.get_template(template).render(**context)


_JINJA: dict[str, object] = {}


# ---------------------------------------------------------------------------------------------------------------
# Names and numbers

_PKG_REF = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]*$")          # what catkin accepts for an existing package
_NODE_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")             # a ROS graph name (one segment)
_NODE_TYPE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.+-]*$")       # an executable's file name


@dataclass(frozen=True)
class NodeRef:
    """A node started by a launch file: ``pkg/type`` run under ``name`` (in namespace ``ns`` when read back)."""

    package: str
    type: str
    name: str
    ns: str = "/"
    args: str | None = None
    line: int | None = None

    @property
    def full_name(self) -> str:
        return _join_ns(self.ns, self.name)


def parse_node(text: str) -> NodeRef:
    """``PKG/TYPE[:NAME]`` → NodeRef. NAME defaults to TYPE without its extension (``stop_at_wall.py`` →
    ``stop_at_wall``), made a valid ROS name. Raises InputError for anything else."""
    hint = "write --node PACKAGE/EXECUTABLE[:NAME], e.g. --node lab_a_stop_at_wall/stop_at_wall.py:stopper"
    spec, _, name = text.partition(":")
    package, slash, node_type = spec.partition("/")
    if not slash or not _PKG_REF.match(package) or not _NODE_TYPE.match(node_type):
        raise InputError(f"bad --node value {text!r}", hint=hint)
    if not name:
        name = re.sub(r"[^A-Za-z0-9_]", "_", node_type.split(".")[0])
        if not name[:1].isalpha():
            name = "node_" + name
    if not _NODE_NAME.match(name):
        raise InputError(f"bad node name {name!r} in --node {text!r}",
                         hint="a node name starts with a letter and holds letters, digits and underscores")
    return NodeRef(package, node_type, name)


def format_number(value: float) -> str:
    """A fixed, short decimal form for launch and package files: ``1.5``, ``-5.5``, ``0.0``, ``0.125``."""
    text = f"{float(value):.4f}".rstrip("0")
    text = text + "0" if text.endswith(".") else text
    return "0.0" if text in ("-0.0", "0.0") else text


def parse_spawn(text: str) -> Pose:
    """``X,Y[,Z[,YAW]]`` (metres, radians) → (x, y, z, yaw). Raises InputError."""
    parts = [p.strip() for p in text.split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if not 2 <= len(values) <= 4 or not all(math.isfinite(v) for v in values):
        raise InputError(f"bad --spawn value {text!r}", hint="write --spawn X,Y or X,Y,Z or X,Y,Z,YAW in metres "
                                                             "and radians, e.g. --spawn 1.0,-0.5,0,1.57")
    values += [0.0] * (4 - len(values))
    return (values[0], values[1], values[2], values[3])


def check_package_ref(name: str) -> str:
    """``name`` if it can name an existing ROS package (catkin's lenient rule); InputError otherwise."""
    if not _PKG_REF.match(name or ""):
        raise InputError(f"bad package name {name!r}",
                         hint="a ROS package name holds lowercase letters, digits and underscores")
    return name


# ---------------------------------------------------------------------------------------------------------------
# Writer

def default_launch_name(world_file_name: str) -> str:
    """``turtlebot3_in_<world stem>.launch``, the class's naming."""
    return f"turtlebot3_in_{Path(world_file_name).name.split('.')[0]}.launch"


def launch_xml(world_file_name: str, package: str, model: str = "env", spawn: Sequence[float] = (0.0, 0.0),
               nodes: Sequence[NodeRef] = (), launch_name: str | None = None) -> str:
    """The launch file text for ``PKG/worlds/WORLD`` and a TurtleBot3.

    ``model`` is ``env`` (the default comes from ``$(env TURTLEBOT3_MODEL)``, as in the class) or a model name;
    ``spawn`` is (x, y[, z[, yaw]]) written as the ``x_pos``/``y_pos``/``z_pos``/``yaw`` defaults; ``nodes`` are
    extra nodes started beside Gazebo. Raises InputError for a bad model, package, world name or duplicate node.
    """
    if model not in MODEL_CHOICES:
        raise InputError(f"unknown robot model {model!r}", hint=f"use one of {', '.join(MODEL_CHOICES)}")
    check_package_ref(package)
    world = Path(world_file_name).name
    if not world or re.search(r"[\s$()<>&\"']", world):
        raise InputError(f"world file name {world_file_name!r} cannot be passed to Gazebo",
                         hint="rename the world file: letters, digits, '_', '-' and '.' only")
    pose = [float(v) for v in spawn] + [0.0] * (4 - len(spawn))
    seen = {"spawn_urdf", "gazebo", "gazebo_gui"}
    for node in nodes:
        if node.name in seen:
            raise InputError(f"two nodes would be named {node.name!r}",
                             hint="give each --node its own name: --node PKG/TYPE:NAME")
        seen.add(node.name)
    return render_template(
        "launch/turtlebot3_world.launch.j2", world=world, package=package,
        launch_hint=f"{package} {launch_name or default_launch_name(world)}",
        model_default="$(env TURTLEBOT3_MODEL)" if model == "env" else model,
        x=format_number(pose[0]), y=format_number(pose[1]), z=format_number(pose[2]), yaw=format_number(pose[3]),
        nodes=list(nodes))


def package_name_of(pkg_dir: str | Path) -> str:
    """The ``<name>`` of ``pkg_dir/package.xml``, or the folder's name when there is no readable package.xml."""
    pkg_dir = Path(pkg_dir)
    name = _manifest_name(pkg_dir / "package.xml")
    return name or pkg_dir.resolve().name


def package_world_files(pkg_dir: str | Path, world_name: str, world_text: str, spawn: Sequence[float],
                        model: str = "env") -> dict[Path, str]:
    """The files that put a built world into a catkin package: ``worlds/NAME.world`` and
    ``launch/turtlebot3_in_NAME.launch`` (path → text, for :func:`worldgen.fsio.write_files`)."""
    pkg_dir = Path(pkg_dir)
    world_file = f"{world_name}.world"
    launch_name = default_launch_name(world_file)
    package = check_package_ref(package_name_of(pkg_dir))
    return {pkg_dir / "worlds" / world_file: world_text,
            pkg_dir / "launch" / launch_name: launch_xml(world_file, package, model, spawn,
                                                          launch_name=launch_name)}


# ---------------------------------------------------------------------------------------------------------------
# Where a robot may spawn in a world file

@dataclass(frozen=True)
class Rooms:
    """The free floor of a world in the robot's height band.

    ``free`` are the connected free areas (walls and obstacles cut out), largest first; ``closed`` says which of
    them the walls close (the free area does not reach the outside, as for the validator's ``enclosed`` check);
    ``centre`` is the centre of the walls' bounding box (the building's origin, as the Building Editor writes
    it; None when nothing stands in the band); ``blocked`` is the walls' and obstacles' footprint; ``radius``
    the robot's.
    """

    free: tuple             # shapely Polygons
    closed: tuple[bool, ...]
    centre: tuple[float, float] | None
    blocked: object         # shapely geometry
    radius: float

    def fits(self, region) -> bool:
        """Whether a robot of :attr:`radius` fits somewhere in ``region`` (one of :attr:`free`)."""
        return not region.buffer(-self.radius, quad_segs=8).is_empty

    def rooms(self) -> list:
        """The closed free areas the robot fits in, largest first."""
        return [p for p, c in zip(self.free, self.closed) if c and self.fits(p)]


def world_rooms(scene, radius: float = ROBOT_RADIUS["burger"]) -> Rooms:
    """Slice ``scene`` (a :class:`worldgen.scene.Scene`) in the robot's height band (:data:`SLICE_Z`) and find
    its free areas and which of them are closed rooms."""
    import shapely

    from .enclosure import footprints_between, obstacle_union

    prints = footprints_between(scene, *SLICE_Z)
    if not prints:
        return Rooms((), (), None, shapely.Polygon(), radius)
    blocked = obstacle_union(prints)
    xmin, ymin, xmax, ymax = blocked.bounds
    margin = 2 * radius + 1.0
    frame = shapely.box(xmin - margin, ymin - margin, xmax + margin, ymax + margin)
    parts = sorted(_polygons(frame.difference(blocked)), key=lambda p: (-p.area, p.bounds))
    closed = tuple(p.exterior.distance(frame.exterior) > 1e-6 for p in parts)
    return Rooms(tuple(parts), closed, ((xmin + xmax) / 2, (ymin + ymax) / 2), blocked, radius)


def deepest_point(rooms: Rooms) -> tuple[float, float] | None:
    """The centre of the largest circle inside the room holding the building's centre (else inside the largest
    room), rounded to the centimetre. A world without a closed room: the same inside the walls' bounding box,
    else the free point nearest the centre. None when nothing stands in the robot's band."""
    import shapely
    from shapely.ops import nearest_points, polylabel

    if rooms.centre is None:
        return None
    centre = shapely.Point(rooms.centre)
    candidates = rooms.rooms()
    if not candidates:
        inside = shapely.box(*rooms.blocked.bounds)
        candidates = [p for p in sorted(_polygons(shapely.union_all(list(rooms.free)).intersection(inside)),
                                        key=lambda p: (-p.area, p.bounds)) if rooms.fits(p)]
    if candidates:
        region = next((p for p in candidates if p.covers(centre)), candidates[0])
        point = polylabel(region, tolerance=0.002)
    else:   # no room and no space inside the walls' bounds: the free point nearest the centre (1 cm to spare)
        region = shapely.union_all(list(rooms.free)).buffer(-(rooms.radius + 0.01), quad_segs=8)
        if region.is_empty:
            return None
        point = nearest_points(centre, region)[1]
    rounded = shapely.Point(round(point.x, 2), round(point.y, 2))
    if rooms.blocked.distance(rounded) >= rooms.radius and region.covers(rounded):
        point = rounded
    return (point.x + 0.0, point.y + 0.0)


def spawn_problem(rooms: Rooms, x: float, y: float) -> str | None:
    """Why a robot cannot spawn at (x, y) — inside a wall or obstacle, closer to one than its radius, outside
    every closed room of a world that has one — or None when it can."""
    import shapely

    if rooms.centre is None:
        return None
    point = shapely.Point(x, y)
    if rooms.blocked.covers(point):
        return "it is inside a wall or an obstacle"
    rooms_here = rooms.rooms()
    if rooms_here and not any(p.covers(point) for p in rooms_here):
        return "it is outside the room" if len(rooms_here) == 1 else "it is outside every room of the world"
    clearance = rooms.blocked.distance(point)
    if clearance < rooms.radius:
        return (f"it is {clearance:.2f} m from a wall or obstacle, and the robot reaches {rooms.radius:.3f} m "
                "from its centre")
    return None


def spawn_for_world(world_path: str | Path, model: str = "env", spawn: Sequence[float] | None = None
                    ) -> tuple[Pose, str]:
    """The spawn pose for a launch file of ``world_path`` and where it came from: ``given`` (``spawn``, checked
    against the world), ``spec`` (the robot pose of ``NAME.yaml``/``.yml``/``.json`` beside ``NAME.world``, the
    spec it was built from), ``world`` (the deepest point of the room) or ``open`` (the world has no closed
    room: the deepest free point inside its walls' bounds).

    Raises InputError when the pose is no place for the robot (see :func:`spawn_problem`) and WorldFileError
    when the world cannot be read.
    """
    from .sdf.reader import read_world

    world_path = Path(world_path)
    rooms = world_rooms(read_world(world_path), ROBOT_RADIUS.get(model, ROBOT_RADIUS["burger"]))
    if spawn is not None:
        return checked_spawn(rooms, spawn, source=world_path), "given"
    pose = _spec_pose(world_path)
    if pose is not None:
        return checked_spawn(rooms, pose, source=world_path, what="the spec's robot pose"), "spec"
    return checked_spawn(rooms, None, source=world_path), ("world" if rooms.rooms() else "open")


def spawn_in_scene(scene, model: str = "env", spawn: Sequence[float] | None = None, *,
                   source: str | Path | None = None, what: str = "--spawn") -> Pose:
    """:func:`checked_spawn` for a :class:`worldgen.scene.Scene` and a robot model."""
    return checked_spawn(world_rooms(scene, ROBOT_RADIUS.get(model, ROBOT_RADIUS["burger"])), spawn,
                         source=source, what=what)


def checked_spawn(rooms: Rooms, spawn: Sequence[float] | None, *, source: str | Path | None = None,
                  what: str = "--spawn") -> Pose:
    """``spawn`` (x, y[, z[, yaw]]) as a full pose when the robot may spawn there (InputError naming ``what``
    otherwise), or, when None, the :func:`deepest_point` (InputError when the robot fits nowhere)."""
    if spawn is not None:
        pose = tuple(float(v) for v in spawn) + (0.0,) * (4 - len(spawn))
        problem = spawn_problem(rooms, pose[0], pose[1])
        if problem:
            raise InputError(f"{what} ({format_number(pose[0])}, {format_number(pose[1])}) is no place for the "
                             f"robot: {problem}", path=source,
                             hint="choose a free point inside the room (or leave --spawn out to get one)")
        return pose
    point = deepest_point(rooms)
    if point is None:
        if rooms.centre is None:   # nothing stands in the robot's way: anywhere will do
            return (0.0, 0.0, 0.0, 0.0)
        raise InputError("the robot fits nowhere in this world", path=source, hint="pass --spawn X,Y")
    return (point[0], point[1], 0.0, 0.0)


def spec_spawn(spec, world_text: str, model: str = "env") -> Pose:
    """The spawn pose for the world built from ``spec``: the spec's robot pose, or without one the deepest point
    of the room of ``world_text`` (the built world)."""
    if spec.robot is not None:
        return (spec.robot.at[0], spec.robot.at[1], 0.0, spec.robot.yaw)
    from .sdf.reader import read_world_text

    return spawn_in_scene(read_world_text(world_text, source=spec.source), model, source=spec.source)


def _spec_pose(world_path: Path) -> Pose | None:
    from .errors import SpecError

    for suffix in (".yaml", ".yml", ".json"):
        spec_path = world_path.with_suffix(suffix)
        if spec_path.is_file():
            from .spec import load_spec
            try:
                spec = load_spec(spec_path)
            except SpecError:
                return None
            if spec.robot is not None:
                return (spec.robot.at[0], spec.robot.at[1], 0.0, spec.robot.yaw)
            return None
    return None


def _polygons(geometry) -> list:
    if geometry.is_empty:
        return []
    if geometry.geom_type == "Polygon":
        return [geometry]
    return [g for g in getattr(geometry, "geoms", []) if g.geom_type == "Polygon" and not g.is_empty]


# ---------------------------------------------------------------------------------------------------------------
# Reader

@dataclass(frozen=True)
class RobotSpawn:
    """One ``gazebo_ros/spawn_model`` node: its full name, the ``-model`` name, the ``-param`` it reads the
    description from, the robot model (burger/waffle/…) when known and the pose (None when unresolved)."""

    node: str
    model_name: str | None
    param: str | None
    robot: str | None
    pose: Pose | None
    line: int | None = None


@dataclass
class LaunchInfo:
    """What a launch file starts, as far as worlds and robots go.

    ``world_path`` is the world file passed to gazebo_ros as ``world_name`` (None when it cannot be resolved or
    none is passed); ``world_ref`` is that value with args expanded but ``$(find)`` kept; ``package`` is the
    package named by its ``$(find PKG)``. ``robots`` lists every spawn_model node (in file order, includes
    followed); ``model`` and ``spawn`` are the first robot's (for one-robot files: *the* robot), falling back to
    the ``model`` and ``x_pos``/``y_pos``/``z_pos``/``yaw`` args when no spawn node could be read.
    ``model_env`` names the environment variable the model depends on when it was not set. ``args`` are the
    top-level args' values (None when unresolved). ``findings`` say what could not be resolved and why.
    """

    path: Path
    world_path: Path | None = None
    world_ref: str | None = None
    package: str | None = None
    model: str | None = None
    model_env: str | None = None
    spawn: Pose | None = None
    args: dict[str, str | None] = field(default_factory=dict)
    robots: list[RobotSpawn] = field(default_factory=list)
    nodes: list[NodeRef] = field(default_factory=list)
    includes: list[Path] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)


class _Unresolved(Exception):
    """A substitution that cannot be evaluated here (unset arg or env var, unknown package, ``$(eval)``)."""

    def __init__(self, reason: str, env: str | None = None, package: str | None = None):
        super().__init__(reason)
        self.reason, self.env, self.package = reason, env, package


_SUBST = re.compile(r"\$\((\w+)((?:\s+[^()\s]*)*)\s*\)")
_XACRO_MODEL = re.compile(r"turtlebot3_([A-Za-z0-9_]+)\.urdf(?:\.xacro)?\b")
_GAZEBO_FLAGS = {"-x": 0, "-y": 1, "-z": 2, "-Y": 3}
_MAX_INCLUDE_DEPTH = 16
_STOCK_PACKAGES = frozenset({"gazebo_ros", "xacro", "turtlebot3_description", "turtlebot3_gazebo"})


class PackageFinder:
    """``$(find PKG)`` for a launch file: the package holding the file first, then its sibling packages in the
    same catkin source tree, then ``ROS_PACKAGE_PATH`` (as rospack, not descending into packages)."""

    def __init__(self, launch_path: Path, ros_package_path: Sequence[str | Path] | None = None):
        own = _owning_package(launch_path)
        roots: list[Path] = []
        if own is not None:
            roots.append(own)
            roots.append(_source_tree(own))
        if ros_package_path is None:
            ros_package_path = [p for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
        roots += [Path(p) for p in ros_package_path]
        self.roots = roots
        self._found: dict[str, Path | None] = {}
        self._crawled: dict[Path, list[Path]] = {}

    def find(self, name: str) -> Path | None:
        if name not in self._found:
            self._found[name] = self._search(name)
        return self._found[name]

    def _search(self, name: str) -> Path | None:
        for root in self.roots:
            dirs = self._packages(root)
            for d in sorted(dirs, key=lambda d: d.name != name):   # folder named like the package first
                if _manifest_name(d / "package.xml") == name:
                    return d
        return None

    def _packages(self, root: Path) -> list[Path]:
        if root not in self._crawled:
            found: list[Path] = []
            if (root / "package.xml").is_file():
                found.append(root)
            elif root.is_dir():
                for dirpath, dirnames, filenames in os.walk(root):
                    if "package.xml" in filenames:
                        found.append(Path(dirpath))
                        dirnames.clear()
                    elif "CATKIN_IGNORE" in filenames:
                        dirnames.clear()
                    dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            self._crawled[root] = found
        return self._crawled[root]


def _owning_package(path: Path) -> Path | None:
    for parent in Path(path).resolve().parents:
        if (parent / "package.xml").is_file():
            return parent
    return None


def _source_tree(package_dir: Path) -> Path:
    """The catkin source space holding ``package_dir``: the nearest of its three closest ancestors that is named
    ``src`` or holds a top-level ``CMakeLists.txt`` (and is no package), else the package's parent folder."""
    for parent in list(package_dir.parents)[:3]:
        if parent.name == "src" or ((parent / "CMakeLists.txt").exists() and not (parent / "package.xml").exists()):
            return parent
    return package_dir.parent


def _manifest_name(manifest: Path) -> str | None:
    from lxml import etree

    try:
        root = etree.parse(str(manifest), _parser()).getroot()
    except (OSError, etree.XMLSyntaxError):
        return None
    name = root.findtext("name")
    return name.strip() if name else None


def _parser():
    from lxml import etree

    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, remove_comments=True,
                           remove_pis=True, huge_tree=False)


def _parse_xml(path: Path, what: str = "launch file"):
    from lxml import etree

    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise WorldFileError(f"cannot read the {what}: {err.strerror or err}", path=path,
                             hint="check the path") from None
    try:
        root = etree.fromstring(data, _parser())
    except etree.XMLSyntaxError as err:
        line = err.lineno if getattr(err, "lineno", None) else None
        message = re.sub(r",\s*line \d+, column \d+\s*$", "", err.msg or "")
        raise WorldFileError(f"the {what} is not well-formed XML: {message}", path=path, line=line,
                             hint="fix the XML (every tag closed, attributes quoted, '<' and '&' escaped)") from None
    if root is None:
        raise WorldFileError(f"the {what} is empty", path=path, hint="a launch file holds one <launch> element")
    return root


@dataclass
class _Scope:
    """One launch file being evaluated: its args and where it is."""

    path: Path
    args: dict[str, str | _Unresolved]
    passed: dict[str, str | _Unresolved]
    ns: str


class _Reader:
    """Evaluates launch files into one :class:`LaunchInfo`, following includes."""

    def __init__(self, top: Path, finder: PackageFinder, environ: Mapping[str, str]):
        self.finder = finder
        self.environ = environ
        self.info = LaunchInfo(path=top)
        self.params: dict[str, str] = {}   # full name → text (unresolved parts marked, see expand_lenient)
        self.stack: list[Path] = []
        self.raw_args: dict[str, str | None] = {}   # the top-level args as written

    # -- findings ------------------------------------------------------------------------------------------
    def note(self, check: str, severity: str, message: str, scope: _Scope, line: int | None, fix: str | None):
        where = f"{scope.path}:{line}" if line else str(scope.path)
        finding = Finding(check, severity, message, where=where, fix=fix)
        if finding not in self.info.findings:
            self.info.findings.append(finding)

    def unresolved(self, err: _Unresolved, what: str, scope: _Scope, line: int | None):
        if err.package:
            # Gazebo's and the TurtleBot3's own packages are missing on most machines that are not robot PCs.
            severity = "info" if err.package in _STOCK_PACKAGES else "warning"
            self.note("launch-find", severity, f"{what}: {err.reason}", scope, line,
                      f"put the package {err.package} in this catkin workspace or on ROS_PACKAGE_PATH")
        elif err.env:
            self.note("launch-env", "info", f"{what}: {err.reason}", scope, line,
                      f"export {err.env} (or pass the arg on the command line)")
        else:
            self.note("launch-arg", "warning", f"{what}: {err.reason}", scope, line,
                      "pass the arg (name:=value) or give it a default")

    # -- substitutions -------------------------------------------------------------------------------------
    def expand(self, text: str, scope: _Scope, find: bool = False) -> str:
        """``text`` with every substitution evaluated; ``$(find)`` only when ``find`` (it is kept otherwise).
        Raises _Unresolved for the first one that cannot be evaluated."""
        if text.strip().startswith("$(eval "):
            raise _Unresolved("$(eval …) expressions are not evaluated here")
        return _SUBST.sub(lambda m: self.substitute(m, scope, find), text)

    def expand_lenient(self, text: str, scope: _Scope) -> tuple[str, list[_Unresolved]]:
        """Like :meth:`expand`, but each substitution that cannot be evaluated becomes the marker ``\\0N\\0``
        (N indexes the returned errors), so the parts that can be read still are."""
        errors: list[_Unresolved] = []

        def one(match: re.Match) -> str:
            try:
                return self.substitute(match, scope, False)
            except _Unresolved as err:
                errors.append(err)
                return f"\0{len(errors) - 1}\0"

        if text.strip().startswith("$(eval "):
            return "\x000\x00", [_Unresolved("$(eval …) expressions are not evaluated here")]
        return _SUBST.sub(one, text), errors

    def substitute(self, match: re.Match, scope: _Scope, find: bool) -> str:
        command, rest = match.group(1), match.group(2).split()
        if command == "arg" and len(rest) == 1:
            value = scope.args.get(rest[0])
            if value is None:
                raise _Unresolved(f"arg {rest[0]!r} is not declared")
            if isinstance(value, _Unresolved):
                raise value
            return value
        if command == "env" and len(rest) == 1:
            if rest[0] not in self.environ:
                raise _Unresolved(f"environment variable {rest[0]} is not set", env=rest[0])
            return self.environ[rest[0]]
        if command == "optenv" and rest:
            return self.environ.get(rest[0], " ".join(rest[1:]))
        if command == "dirname" and not rest:
            return str(scope.path.resolve().parent)
        if command == "anon" and len(rest) == 1:
            return f"{rest[0]}_anon"
        if command == "find" and len(rest) == 1:
            if not find:
                return match.group(0)
            found = self.finder.find(rest[0])
            if found is None:
                raise _Unresolved(f"package {rest[0]!r} not found", package=rest[0])
            return str(found)
        raise _Unresolved(f"cannot evaluate {match.group(0)}")

    def condition(self, el, scope: _Scope) -> bool:
        for attr, want in (("if", True), ("unless", False)):
            raw = el.get(attr)
            if raw is None:
                continue
            try:
                value = self.expand(raw, scope, find=True).strip().lower()
            except _Unresolved as err:
                self.unresolved(err, f"<{el.tag} {attr}=…> assumed satisfied", scope, el.sourceline)
                continue
            if value not in ("true", "1", "false", "0"):
                raise WorldFileError(f"<{el.tag} {attr}=\"{raw}\"> is neither true nor false", path=scope.path,
                                     line=el.sourceline, hint="use true/false or 1/0")
            if (value in ("true", "1")) != want:
                return False
        return True

    # -- elements ------------------------------------------------------------------------------------------
    def load(self, path: Path, passed: dict[str, str | _Unresolved], ns: str, line: int | None) -> None:
        path = Path(path)
        if path.resolve() in self.stack:
            raise WorldFileError("a launch file includes itself", path=path, line=line,
                                 hint="remove the circular <include>")
        if len(self.stack) >= _MAX_INCLUDE_DEPTH:
            raise WorldFileError("includes nest too deeply", path=path, line=line, hint="remove circular includes")
        root = _parse_xml(path)
        if root.tag != "launch":
            raise WorldFileError(f"the root element is <{root.tag}>, not <launch>", path=path,
                                 line=root.sourceline, hint="a launch file holds one <launch> element")
        self.stack.append(path.resolve())
        scope = _Scope(path, {}, passed, ns)
        self.walk(root, scope)
        self.stack.pop()
        if len(self.stack) == 0:
            self.info.args = {k: (None if isinstance(v, _Unresolved) else self._found_path(v, scope))
                              for k, v in scope.args.items()}

    def _found_path(self, value: str, scope: _Scope) -> str | None:
        try:
            return self.expand(value, scope, find=True)
        except _Unresolved:
            return None

    def walk(self, parent, scope: _Scope) -> None:
        for el in parent:
            if not isinstance(el.tag, str) or not self.condition(el, scope):
                continue
            handler = getattr(self, f"on_{el.tag}", None)
            if handler is not None:
                handler(el, scope)

    def on_arg(self, el, scope: _Scope) -> None:
        name = el.get("name")
        if not name:
            raise WorldFileError("<arg> without a name", path=scope.path, line=el.sourceline,
                                 hint='write <arg name="..." default="..."/>')
        if el.get("value") is not None and el.get("default") is not None:
            raise WorldFileError(f"<arg name=\"{name}\"> has both value and default", path=scope.path,
                                 line=el.sourceline, hint="keep one of them")
        value: str | _Unresolved
        if el.get("value") is not None:
            value = self._try(el.get("value"), scope)
        elif name in scope.passed:
            value = scope.passed[name]
        elif el.get("default") is not None:
            value = self._try(el.get("default"), scope)
        else:
            value = _Unresolved(f"arg {name!r} has no value (it must be passed: {name}:=...)")
        scope.args[name] = value
        if len(self.stack) == 1:
            self.raw_args[name] = el.get("value", el.get("default"))

    def _try(self, text: str, scope: _Scope) -> str | _Unresolved:
        try:
            return self.expand(text, scope)
        except _Unresolved as err:
            return err

    def on_group(self, el, scope: _Scope) -> None:
        ns = _join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        self.walk(el, _Scope(scope.path, scope.args, scope.passed, ns))   # args are shared with the file

    def on_param(self, el, scope: _Scope) -> None:
        name = el.get("name")
        if not name:
            return
        raw = el.get("command") or el.get("value") or el.get("textfile") or ""
        self.params[_join_ns(scope.ns, self._try_str(name, scope))] = self.expand_lenient(raw, scope)[0]

    def _try_str(self, text: str, scope: _Scope) -> str:
        value = self._try(text, scope)
        return text if isinstance(value, _Unresolved) else value

    def on_include(self, el, scope: _Scope) -> None:
        raw = el.get("file")
        if not raw:
            raise WorldFileError("<include> without a file", path=scope.path, line=el.sourceline,
                                 hint='write <include file="$(find PKG)/launch/NAME.launch">')
        passed: dict[str, str | _Unresolved] = {}
        if el.get("pass_all_args", "").lower() in ("true", "1"):
            passed.update(scope.args)
        for child in el:
            if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") and self.condition(child, scope):
                passed[child.get("name")] = self._try(child.get("value", child.get("default", "")), scope)
        if "world_name" in passed and self.info.world_ref is None:
            self.world(passed["world_name"], _child_line(el, "world_name"), scope)
        ns = _join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        try:
            target = Path(self.expand(raw, scope, find=True))
        except _Unresolved as err:
            self.unresolved(err, f"<include file=\"{raw}\"> not followed", scope, el.sourceline)
            return
        if not target.is_file():
            self.note("launch-include", "warning", f"included file {target} does not exist", scope,
                      el.sourceline, "fix the path of the <include>")
            return
        self.info.includes.append(target)
        self.load(target, passed, ns, el.sourceline)

    def world(self, value: str | _Unresolved, line: int | None, scope: _Scope) -> None:
        if isinstance(value, _Unresolved):
            self.unresolved(value, "world_name", scope, line)
            return
        self.info.world_ref = value
        found = re.match(r"\s*\$\(find\s+([^)\s]+)\)", value)
        self.info.package = found.group(1) if found else None
        try:
            resolved = self.expand(value, scope, find=True).strip()
        except _Unresolved as err:
            self.unresolved(err, f"world_name {value}", scope, line)
            return
        if not os.path.isabs(resolved):
            self.note("launch-world", "info", f"world_name {resolved!r} is found through Gazebo's resource path",
                      scope, line, "give the world as $(find PKG)/worlds/NAME.world to check it")
            return
        self.info.world_path = Path(resolved)

    def on_node(self, el, scope: _Scope) -> None:
        pkg, node_type, name = el.get("pkg"), el.get("type"), el.get("name")
        if not pkg or not node_type:
            raise WorldFileError("<node> without pkg or type", path=scope.path, line=el.sourceline,
                                 hint='write <node pkg="PKG" type="EXECUTABLE" name="NAME"/>')
        ns = _join_ns(scope.ns, self._try_str(el.get("ns") or "", scope))
        args, errors = self.expand_lenient(el.get("args") or "", scope)
        node = NodeRef(pkg, node_type, self._try_str(name or node_type, scope), ns,
                       None if errors else args, el.sourceline)
        self.info.nodes.append(node)
        if (pkg, node_type) == ("gazebo_ros", "spawn_model"):
            self.spawn(node, args, errors, scope, el.sourceline)

    def spawn(self, node: NodeRef, args: str, errors: list[_Unresolved], scope: _Scope, line: int | None) -> None:
        """Record a spawn_model node: its -x -y -z -Y pose (0 when not given, as spawn_model does), -model and
        -param. A pose number that cannot be resolved or read leaves the pose unknown, with a finding."""
        words = shlex.split(args)
        pose: list[float] | None = [0.0, 0.0, 0.0, 0.0]
        model_name = param = None
        for i, word in enumerate(words):
            following = words[i + 1] if i + 1 < len(words) else None
            if word in _GAZEBO_FLAGS:
                marker = re.search(r"\0(\d+)\0", following or "")
                if marker:
                    self.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name} {word}", scope,
                                    line)
                    pose = None
                    continue
                try:
                    value = float(following)
                except (TypeError, ValueError):
                    self.note("launch-spawn", "error", f"spawn_model {word} {following!r} is not a number", scope,
                              line, "give the pose as numbers (or $(arg NAME) with a numeric default)")
                    pose = None
                    continue
                if pose is not None:
                    pose[_GAZEBO_FLAGS[word]] = value
            elif word == "-model":
                model_name = None if following is None or "\0" in following else following
            elif word == "-param":
                param = None if following is None or "\0" in following else following
        for i, word in enumerate(words):   # an unresolved word that is no flag's value may hold the pose itself
            marker = re.search(r"\0(\d+)\0", word)
            if marker and not (i > 0 and words[i - 1].startswith("-")):
                self.unresolved(errors[int(marker.group(1))], f"spawn_model {node.full_name}: pose unknown",
                                scope, line)
                pose = None
        robot = self.robot_of(param, node.ns)
        self.info.robots.append(RobotSpawn(node.full_name, model_name, param, robot,
                                           None if pose is None else (pose[0], pose[1], pose[2], pose[3]), line))

    def robot_of(self, param: str | None, ns: str) -> str | None:
        if not param:
            return None
        text = self.params.get(param if param.startswith("/") else _join_ns(ns, param))
        found = _XACRO_MODEL.search(text or "")
        return found.group(1) if found else None


def _child_line(el, arg_name: str) -> int | None:
    for child in el:
        if isinstance(child.tag, str) and child.tag == "arg" and child.get("name") == arg_name:
            return child.sourceline
    return el.sourceline


def _join_ns(ns: str, name: str) -> str:
    if name.startswith("/"):
        return "/" + name.strip("/")
    parts = [p for p in ns.split("/") + name.split("/") if p]
    return "/" + "/".join(parts)


def read_launch(path: str | Path, args: Mapping[str, str] | None = None, *,
                ros_package_path: Sequence[str | Path] | None = None,
                environ: Mapping[str, str] | None = None) -> LaunchInfo:
    """Read a roslaunch XML file: world, robot model, spawn poses, args, nodes (see :class:`LaunchInfo`).

    ``args`` are command-line overrides (``x_pos:=1.5`` → ``{"x_pos": "1.5"}``); ``ros_package_path`` and
    ``environ`` default to the process's. Raises WorldFileError (with the line) for a file roslaunch could not
    parse either: malformed XML, a root other than ``<launch>``, an ``<arg>``/``<node>``/``<include>`` missing
    its required attributes, circular includes. Unresolvable references become findings, and only what depends
    on them stays unknown (roslaunch stops at the first one: an unset ``$(env TURTLEBOT3_MODEL)`` default fails
    it even when ``model:=`` is passed).
    """
    path = Path(path)
    environ = os.environ if environ is None else environ
    reader = _Reader(path, PackageFinder(path, ros_package_path), environ)
    reader.load(path, {k: str(v) for k, v in (args or {}).items()}, "/", None)
    info = reader.info
    if info.robots:
        info.spawn, info.model = info.robots[0].pose, info.robots[0].robot
    if info.model is None:
        info.model = info.args.get("model")
    model_arg = reader.raw_args.get("model")
    if info.model is None and model_arg:
        env = re.search(r"\$\((?:opt)?env\s+(\w+)", model_arg)
        info.model_env = env.group(1) if env else None
    if info.spawn is None and not info.robots and "x_pos" in info.args:   # args only: a file that includes the spawn
        try:
            info.spawn = tuple(float(info.args.get(k) or 0.0) for k in ("x_pos", "y_pos", "z_pos", "yaw"))
        except ValueError:
            reader.note("launch-spawn", "error", "x_pos/y_pos/z_pos/yaw are not numbers", _Scope(path, {}, {}, "/"),
                        None, "give the spawn args numeric defaults")
    return info


def package_launch_files(pkg_dir: str | Path) -> list[Path]:
    """Every launch file of a package (``*.launch``, ``*.launch.xml``), sorted; hidden folders and nested
    packages are skipped."""
    pkg_dir = Path(pkg_dir)
    found: list[Path] = []
    for dirpath, dirnames, filenames in os.walk(pkg_dir):
        here = Path(dirpath)
        if here != pkg_dir and "package.xml" in filenames:
            dirnames.clear()
            continue
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        found += [here / f for f in filenames if f.endswith((".launch", ".launch.xml"))]
    return sorted(found)


# ---------------------------------------------------------------------------------------------------------------
# Checking a package

def check_package(pkg_dir: str | Path, *, ros_package_path: Sequence[str | Path] | None = None,
                  environ: Mapping[str, str] | None = None) -> list[Finding]:
    """What would break in the catkin package at ``pkg_dir``: package.xml that catkin_pkg cannot parse (or a
    name catkin rejects), a CMakeLists.txt without ``project(NAME)``/``catkin_package()`` or not installing its
    launch/worlds/models folders, scripts without their executable bit, launch files that do not parse, name a
    world file that does not exist or an unknown robot model, and missing exec_depends on the packages the
    launch files use."""
    pkg_dir = Path(pkg_dir)
    findings: list[Finding] = []

    def add(check, severity, message, where=None, fix=None):
        findings.append(Finding(check, severity, message, where=str(where) if where else None, fix=fix))

    manifest = pkg_dir / "package.xml"
    if not manifest.is_file():
        add("package-xml", "error", "no package.xml: this folder is not a catkin package", pkg_dir,
            "create it with 'worldgen scaffold NAME' or catkin_create_pkg")
        return findings
    name, depends = _read_manifest(manifest, add)
    cmake = pkg_dir / "CMakeLists.txt"
    if not cmake.is_file():
        add("cmake", "error", "no CMakeLists.txt", pkg_dir, "every catkin package needs one (see catkin_create_pkg)")
    else:
        _check_cmake(cmake, name, pkg_dir, add)
    scripts = pkg_dir / "scripts"
    if scripts.is_dir():
        for script in sorted(p for p in scripts.rglob("*") if p.is_file() and not p.name.startswith(".")):
            if not os.access(script, os.X_OK):
                add("script-executable", "error", "script is not executable: rosrun and roslaunch cannot start it",
                    script, f"chmod +x {script}")
            elif script.suffix == ".py" and not script.read_bytes().startswith(b"#!"):
                add("script-executable", "error", "Python script has no #! line", script,
                    "start it with #!/usr/bin/env python3")
    used: set[str] = set()
    for launch in package_launch_files(pkg_dir):
        _check_launch(launch, name, pkg_dir, used, add, ros_package_path, environ)
    if depends is not None:
        for dep in sorted(used - depends - {name}):
            add("package-depends", "warning", f"launch files use the package {dep} but package.xml does not "
                f"exec_depend on it", manifest, f"add <exec_depend>{dep}</exec_depend>")
    return findings


def _read_manifest(manifest: Path, add) -> tuple[str, set[str] | None]:
    try:
        from catkin_pkg.package import InvalidPackage, parse_package
    except ImportError:   # catkin_pkg is a test dependency; without it, read the name only
        name = _manifest_name(manifest)
        if not name:
            add("package-xml", "error", "package.xml has no readable <name>", manifest, "fix package.xml")
        return name or manifest.parent.name, None
    warnings: list[str] = []
    try:
        package = parse_package(str(manifest), warnings=warnings)
    except (InvalidPackage, ValueError, Exception) as err:   # catkin_pkg raises plain Exceptions on bad XML
        add("package-xml", "error", f"catkin_pkg cannot parse package.xml: {' '.join(str(err).split())}",
            manifest, "fix package.xml (compare with one made by 'worldgen scaffold')")
        return _manifest_name(manifest) or manifest.parent.name, None
    for warning in warnings:
        add("package-xml", "warning", warning, manifest, None)
    deps = {d.name for d in package.exec_depends + package.build_depends + package.buildtool_depends}
    return package.name, deps


def _check_cmake(cmake: Path, name: str, pkg_dir: Path, add) -> None:
    text = re.sub(r"#[^\n]*", "", cmake.read_text(encoding="utf-8", errors="replace"))
    project = re.search(r"\bproject\s*\(\s*([^\s)]+)", text, re.IGNORECASE)
    if not project:
        add("cmake", "error", "CMakeLists.txt has no project() call", cmake, f"add project({name})")
    elif project.group(1) != name:
        add("cmake", "error", f"project({project.group(1)}) does not match the package name {name}", cmake,
            f"write project({name})")
    if not re.search(r"\bcatkin_(package|metapackage)\s*\(", text):
        add("cmake", "error", "CMakeLists.txt never calls catkin_package()", cmake, "add catkin_package()")
    installed = set()
    for match in re.finditer(r"\binstall\s*\(\s*DIRECTORY([^)]*)\)", text, re.IGNORECASE):
        words = match.group(1).split()
        installed.update(w.rstrip("/") for w in words[:words.index("DESTINATION")] if "DESTINATION" in words)
    for folder in ("launch", "worlds", "models"):
        if (pkg_dir / folder).is_dir() and any((pkg_dir / folder).iterdir()) and folder not in installed:
            add("cmake-install", "warning", f"{folder}/ is not installed: 'catkin_make install' leaves it out",
                cmake, f"add install(DIRECTORY {folder} DESTINATION ${{CATKIN_PACKAGE_SHARE_DESTINATION}})")


def _check_launch(launch: Path, name: str, pkg_dir: Path, used: set[str], add, ros_package_path, environ) -> None:
    try:
        info = read_launch(launch, ros_package_path=ros_package_path, environ=environ or {})
    except WorldFileError as err:
        add("launch-parse", "error", err.message, f"{err.path}:{err.line}" if err.line else err.path, err.hint)
        return
    for finding in info.findings:
        if finding.severity in ("error", "warning"):
            add(finding.check, finding.severity, finding.message, finding.where, finding.fix)
    if info.world_path is not None and not info.world_path.is_file():
        add("launch-world", "error", f"the world file {info.world_path} does not exist", launch,
            "build it (worldgen build SPEC --package DIR) or fix world_name")
    elif info.world_path is None and info.package == name and info.world_ref:
        add("launch-world", "error", f"world_name {info.world_ref} cannot be resolved", launch, "fix world_name")
    known = set(ROBOT_MODELS)
    models = {r.robot for r in info.robots if r.robot} | ({info.model} if info.model else set())
    for model in sorted(models - known):
        add("launch-model", "error", f"unknown TurtleBot3 model {model!r}", launch,
            f"use one of {', '.join(sorted(known))}")
    for node in info.nodes:
        used.add(node.package)
        if node.package == name:
            exe = next((p for p in pkg_dir.rglob(node.type) if p.is_file()), None)
            if exe is None:
                add("launch-node", "error", f"node {node.full_name}: {node.package}/{node.type} is not in the package",
                    f"{launch}:{node.line}", f"add scripts/{node.type} or fix type=")
            elif not os.access(exe, os.X_OK):
                add("launch-node", "error", f"node {node.full_name}: {exe} is not executable",
                    f"{launch}:{node.line}", f"chmod +x {exe}")
    text = launch.read_text(encoding="utf-8", errors="replace")
    used.update(re.findall(r"\$\(find\s+([^)\s]+)\)", text))
