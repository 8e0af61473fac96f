"""Top-down pictures of a world: what a TurtleBot3 meets at its own height, drawn to scale.

A world file is read into a :class:`~worldgen.core.scene.Scene`; a spec goes spec → geometry → SDF text → the same
reader, so the picture shows what the written world holds, not what the spec meant. Every shape is cut through
the robot's height band (:data:`worldgen.geometry.placement.SLICE_Z`, by :func:`worldgen.geometry.slices.footprints_between`):
walls and obstacles are filled, lintels over doors and anything else above the robot are left out, so a doorway
shows as a gap. A spec adds its openings (doors and windows, from the geometry) and its spawn pose.

The PNG is deterministic: matplotlib's default style, the Agg canvas without pyplot, no date or version in the
file. Matplotlib, shapely and numpy are imported only when a picture is drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence, Tuple

from ..check.sources import WorldSource
from ..core.inputs import refuse_unread
from ..core.scene import Scene
from ..spec.load import load_spec
from ..spec.model import SPEC_SUFFIXES, Spec
from ..core.mpl import matplotlib_agg
from ..geometry.markings import floor_markings, footprint
from ..geometry.placement import ROBOT_RADIUS, SLICE_Z
from ..geometry.slices import footprints_between
from ..sim.process import run_isolated
from .scene_data import spec_source

FIGSIZE = (8.0, 8.0)   # inches
DPI = 100              # so a picture is 800 × 800 pixels

WALL_COLOUR = "#3b3b3b"
OBSTACLE_COLOUR = "#2f6db5"
DOOR_COLOUR = "#e08a1e"
WINDOW_COLOUR = "#35b7d6"
ROBOT_COLOUR = "#d62728"
RAY_HIT_COLOUR = "#2ca02c"
RAY_MISS_COLOUR = "#b0b0b0"
MARKING_GREY = (0.7, 0.7, 0.7, 1.0)   # a floor marking whose colour the world does not say

Ray = Tuple[float, float, float, float, bool]   # x0, y0, x1, y1, hit


@dataclass(frozen=True)
class Mark:
    """An opening to draw: its footprint's corners in the world frame."""

    type: str   # "door" | "window"
    corners: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Spawn:
    x: float
    y: float
    yaw: float = 0.0
    model: str = "burger"


@dataclass(frozen=True)
class Picture:
    """What one preview holds; :func:`render` draws it."""

    scene: Scene
    title: str
    subtitle: str = ""
    marks: tuple[Mark, ...] = ()
    spawn: Spawn | None = None
    walls: frozenset[str] = frozenset()   # labels of the shapes drawn as walls (the rest are obstacles)
    legend: tuple[str, str] = ("wall", "obstacle")
    world: WorldSource | None = None    # where the scene came from, for the LiDAR job: a world file, or the
    # SDF text written for a spec


def is_spec_path(path: str | Path) -> bool:
    return Path(path).suffix.lower() in SPEC_SUFFIXES


def spec_picture(spec: Spec) -> Picture:
    """A spec's picture: its geometry written as SDF and read back (:func:`.scene_data.spec_source`), plus its
    openings and spawn pose."""
    source = spec_source(spec)
    spawn = Spawn(*source.spawn, spec.robot.model) if spec.robot else None
    walls = frozenset(s.label for s in source.scene.shapes if s.model in source.walls)
    return Picture(source.scene, spec.name, _short(Path(spec.source).name) if spec.source else "",
                   opening_marks(source.building), spawn, walls, world=source.world)


def opening_marks(building) -> tuple[Mark, ...]:
    """Each opening of each wall as a rectangle: along the wall from ``s0`` to ``s1``, the wall's thickness wide."""
    marks = []
    for wall in building.walls:
        c, s = math.cos(wall.yaw), math.sin(wall.yaw)
        half = wall.thickness / 2
        for opening in wall.openings:
            corners = []
            for along, across in ((opening.s0, -half), (opening.s1, -half), (opening.s1, half), (opening.s0, half)):
                corners.append((wall.start[0] + along * c - across * s, wall.start[1] + along * s + across * c))
            marks.append(Mark(opening.type, tuple(corners)))
    return tuple(marks)


def world_picture(path: str | Path, model_paths: Sequence[str | Path] = ()) -> Picture:
    """A world file's picture: static shapes drawn as walls, movable ones as obstacles."""
    from ..sdf.reader import read_world

    scene = read_world(path, model_paths=model_paths)
    walls = frozenset(s.label for s in scene.shapes if s.static)
    title = f"world '{scene.world_name}'" if scene.world_name else Path(path).name
    return Picture(scene, title, _short(Path(path).name), walls=walls, legend=("static", "movable"),
                   world=WorldSource(Path(path)))


def _shown(text: str) -> str:
    """``text`` that a font can draw: a file name that is not UTF-8 reaches Python with stand-in surrogate
    characters (PEP 383), which matplotlib refuses; they become U+FFFD."""
    try:
        return text.encode("utf-8", "surrogateescape").decode("utf-8", "replace")
    except UnicodeEncodeError:
        return text.encode("utf-8", "replace").decode("utf-8")


def _short(text: str, limit: int = 60) -> str:
    return text if len(text) <= limit else "…" + text[-(limit - 1):]


def picture(path: str | Path, model_paths: Sequence[str | Path] = ()) -> Picture:
    """The picture of a spec (``.yaml``/``.yml``/``.json``/``.txt``) or a world file (anything else but what no
    command reads as a world: :data:`worldgen.core.inputs.NOT_READ`)."""
    refuse_unread(path, "a world or spec")
    return spec_picture(load_spec(path)) if is_spec_path(path) else world_picture(path, model_paths)


def render(pic: Picture, rays: Sequence[Ray] | None = None) -> bytes:
    """Draw ``pic`` (and LiDAR ``rays``, if given) as PNG bytes, 800 × 800 px, the same bytes for the same input."""
    import io

    matplotlib = matplotlib_agg()
    with matplotlib.rc_context(_default_style()):
        fig = figure(pic, rays)
        out = io.BytesIO()
        fig.savefig(out, format="png", dpi=DPI, metadata={"Software": None})
    return out.getvalue()


def figure(pic: Picture, rays: Sequence[Ray] | None = None):
    """The matplotlib Figure :func:`render` saves (its first axes are the plan, in metres)."""
    matplotlib = matplotlib_agg()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    with matplotlib.rc_context(_default_style()):
        fig = Figure(figsize=FIGSIZE, dpi=DPI)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.1, 0.12, 0.85, 0.8))
        bounds, drawn, marked = draw_plan(ax, pic, rays)
        xmin, ymin, xmax, ymax = bounds.square(margin=0.5)
        ax.set_xlim(xmin, xmax)
        ax.set_ylim(ymin, ymax)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.grid(True, color="#e6e6e6", linewidth=0.5, zorder=0)
        ax.set_axisbelow(True)
        ax.set_title(_shown(pic.title), fontsize=12, loc="left")
        if pic.subtitle:
            ax.set_title(_shown(pic.subtitle), fontsize=8, loc="right", color="#555555")
        _scale_bar(ax, xmax - xmin)
        _legend(fig, pic, rays, drawn, marked)
    return fig


def draw_plan(ax, pic: Picture, rays: Sequence[Ray] | None = None):
    """Draw ``pic`` (and ``rays``) on the axes ``ax``, in metres: floor markings, what stands in the robot's band,
    openings, the spawn. Returns (the bounds of what was drawn, the colours used for walls and obstacles, the
    first floor marking's colour or None), for the caller's limits and legend (:func:`figure`; the contact sheet
    of :mod:`.sheet`)."""
    from matplotlib.collections import LineCollection

    bounds = _Bounds()
    prints = footprints_between(pic.scene, SLICE_Z[0], SLICE_Z[1])
    if not prints:
        ax.text(0.5, 0.5, f"nothing between {SLICE_Z[0]:g} and {SLICE_Z[1]:g} m above the floor",
                transform=ax.transAxes, ha="center", va="center", color="#555555")
    drawn = set()
    marked = _draw_markings(ax, pic.scene, bounds)
    for print_ in prints:
        colour = WALL_COLOUR if print_.label in pic.walls else OBSTACLE_COLOUR
        drawn.add(colour)
        for patch in _patches(print_.geometry, facecolor=colour, edgecolor=colour, linewidth=0.5, zorder=2):
            ax.add_patch(patch)
        bounds.add_geometry(print_.geometry)
    for mark in pic.marks:
        colour = DOOR_COLOUR if mark.type == "door" else WINDOW_COLOUR
        ax.add_patch(_polygon(mark.corners, facecolor=colour, edgecolor=colour, alpha=0.9, zorder=3))
        bounds.add_points(mark.corners)
    if rays:
        for hit, colour, alpha in ((False, RAY_MISS_COLOUR, 0.5), (True, RAY_HIT_COLOUR, 0.8)):
            lines = [((x0, y0), (x1, y1)) for x0, y0, x1, y1, h in rays if h == hit]
            ax.add_collection(LineCollection(lines, colors=colour, linewidths=0.5, alpha=alpha, zorder=1))
            if hit and lines:
                ax.plot([p[1][0] for p in lines], [p[1][1] for p in lines], linestyle="none", marker=".",
                        markersize=2, color=RAY_HIT_COLOUR, zorder=4)
        bounds.add_points([(r[0], r[1]) for r in rays] + [(r[2], r[3]) for r in rays])
    if pic.spawn:
        radius = ROBOT_RADIUS.get(pic.spawn.model, ROBOT_RADIUS["burger"])
        _draw_robot(ax, pic.spawn, radius)
        bounds.add_points([(pic.spawn.x, pic.spawn.y)], radius + 0.2)
    return bounds, drawn, marked


def _draw_markings(ax, scene: Scene, bounds: "_Bounds"):
    """The scene's floor markings (:func:`worldgen.geometry.markings.floor_markings`: tape, painted patches) in
    their own colours, under the walls, the higher ones over the lower; the first one's colour (for the legend),
    or None when there are none."""
    import shapely

    found = sorted(floor_markings(scene), key=lambda m: m.top)
    for marking in found:
        for colour in marking.colors:
            outline = shapely.union_all([footprint(s) for s in marking.shapes if s.color == colour])
            for patch in _patches(outline, facecolor=colour or MARKING_GREY, edgecolor="none", linewidth=0,
                                  zorder=1.5):
                ax.add_patch(patch)
            bounds.add_geometry(outline)
    return (found[0].colors[0] or MARKING_GREY) if found else None


def _default_style() -> dict:
    """matplotlib's default settings, so that a user's matplotlibrc cannot change the picture."""
    matplotlib = matplotlib_agg()

    style = {k: v for k, v in matplotlib.rcParamsDefault.items() if k not in ("backend", "interactive")}
    style.update({"font.size": 9, "svg.hashsalt": "worldgen", "path.simplify": False})
    return style


class _Bounds:
    def __init__(self):
        self.box = [math.inf, math.inf, -math.inf, -math.inf]

    def add_points(self, points, pad: float = 0.0):
        for x, y in points:
            self.box = [min(self.box[0], x - pad), min(self.box[1], y - pad),
                        max(self.box[2], x + pad), max(self.box[3], y + pad)]

    def add_geometry(self, geometry):
        x0, y0, x1, y1 = geometry.bounds
        self.add_points([(x0, y0), (x1, y1)])

    def square(self, margin: float) -> tuple[float, float, float, float]:
        """The bounds grown by ``margin`` and to a square (the picture is square); 2 m around 0 when empty."""
        x0, y0, x1, y1 = self.box if math.isfinite(self.box[0]) else (-1.0, -1.0, 1.0, 1.0)
        side = max(x1 - x0, y1 - y0) + 2 * margin
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        return cx - side / 2, cy - side / 2, cx + side / 2, cy + side / 2


def _patches(geometry, **style):
    """matplotlib patches for a shapely Polygon / MultiPolygon / collection (holes kept)."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    polygons = []
    if geometry.geom_type == "Polygon":
        polygons = [geometry]
    elif hasattr(geometry, "geoms"):
        polygons = [g for g in geometry.geoms if g.geom_type == "Polygon"]
    for polygon in polygons:
        if polygon.is_empty:
            continue
        rings = [polygon.exterior, *polygon.interiors]
        paths = [MplPath(list(ring.coords), closed=True) for ring in rings]
        yield PathPatch(MplPath.make_compound_path(*paths), **style)


def _polygon(corners, **style):
    from matplotlib.patches import Polygon

    return Polygon(list(corners), closed=True, **style)


def _draw_robot(ax, spawn: Spawn, radius: float) -> None:
    from matplotlib.patches import Circle, FancyArrow

    ax.add_patch(Circle((spawn.x, spawn.y), radius, facecolor=ROBOT_COLOUR, edgecolor=ROBOT_COLOUR,
                        alpha=0.25, linewidth=1.0, zorder=5))
    length = max(radius * 2.2, 0.3)
    ax.add_patch(FancyArrow(spawn.x, spawn.y, length * math.cos(spawn.yaw), length * math.sin(spawn.yaw),
                            width=length * 0.08, head_width=length * 0.3, head_length=length * 0.3,
                            length_includes_head=True, color=ROBOT_COLOUR, zorder=6))


def _nice_length(span: float) -> float:
    """A 1, 2 or 5 × 10^k length near a fifth of ``span``."""
    target = span / 5
    power = 10 ** math.floor(math.log10(target))
    return max((m * power for m in (1, 2, 5) if m * power <= target), default=power)


def _scale_bar(ax, span: float) -> None:
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    length = _nice_length(span)
    label = f"{length:g} m"
    ax.add_artist(AnchoredSizeBar(ax.transData, length, label, "upper right", pad=0.2, sep=3, frameon=False,
                                  size_vertical=span / 150, color="black", bbox_to_anchor=(1.0, -0.06),
                                  bbox_transform=ax.transAxes))


def _legend(fig, pic: Picture, rays, drawn: set[str], marked=None) -> None:
    """A legend of what the picture shows, in one row below it (``marked``: the colour of the first floor
    marking, when there are any)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(color=colour, label=label) for colour, label in zip((WALL_COLOUR, OBSTACLE_COLOUR), pic.legend)
               if colour in drawn]
    if marked is not None:
        handles.append(Patch(facecolor=marked, edgecolor="#555555", linewidth=0.5, label="floor marking"))
    types = {m.type for m in pic.marks}
    if "door" in types:
        handles.append(Patch(color=DOOR_COLOUR, label="door"))
    if "window" in types:
        handles.append(Patch(color=WINDOW_COLOUR, label="window"))
    if pic.spawn:
        handles.append(Patch(color=ROBOT_COLOUR, alpha=0.5, label=f"{pic.spawn.model} spawn"))
    if rays:
        handles.append(Line2D([], [], color=RAY_HIT_COLOUR, label="LiDAR hit"))
        handles.append(Line2D([], [], color=RAY_MISS_COLOUR, label="LiDAR miss"))
    if handles:
        fig.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.08, 0.0), ncol=len(handles),
                   frameon=False, fontsize=9)


def lidar_rays(pic: Picture, spawn: Spawn, model_paths: Sequence[str | Path] = (), timeout: float = 120.0) \
        -> list[Ray]:
    """One noiseless LiDAR scan of the robot at ``spawn`` in ``pic``'s world, simulated in a child process
    (pybullet, see :mod:`worldgen.sim.process`): a ray per beam from the sensor to its hit, or to the sensor's
    range where it hits nothing."""
    reply = run_isolated(f"{__name__}:scan_rays", {
        "world": str(pic.world.path) if pic.world else None, "world_text": pic.world.text if pic.world else None,
        "model_paths": [str(p) for p in model_paths],
        "robot": spawn.model, "spawn": [spawn.x, spawn.y, spawn.yaw]}, timeout)
    return [(x0, y0, x1, y1, bool(hit)) for x0, y0, x1, y1, hit in reply["rays"]]


def scan_rays(world: str, world_text: str | None, model_paths: list[str], robot: str, spawn: list[float]) -> dict:
    """The child-process side of :func:`lidar_rays` (JSON in, JSON out): ``world`` and ``world_text`` are the
    picture's :class:`~worldgen.check.sources.WorldSource`."""
    from ..sim.session import Session

    scene = WorldSource(Path(world), world_text).read(model_paths)
    with Session(scene, robot, tuple(spawn), seed=None) as session:
        scan = session.scan(noise=False)
    ox, oy, _, yaw = scan.origin
    rays = []
    for angle, true, point in zip(scan.angles, scan.true_ranges, scan.points):
        if point is not None and math.isfinite(true):
            rays.append([ox, oy, point[0], point[1], True])
        else:
            rays.append([ox, oy, ox + scan.range_max * math.cos(yaw + angle),
                         oy + scan.range_max * math.sin(yaw + angle), False])
    return {"rays": rays}
