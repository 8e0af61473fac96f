"""A world as the 3D page draws it: plain JSON-able data (and one glTF binary for meshes) made from the scene a
world file, a spec or a launch file gives, exactly as ``validate`` and ``preview`` read it.

What Gazebo draws is the scene's visuals (collisions stand in for a model that has none), each as a primitive
(box, cylinder, sphere: the page builds them with three.js) or a mesh (exported to glTF with trimesh, one node per
mesh). Beside them: the plan at the robot's height (the walls' and obstacles' sections in the band
:data:`~worldgen.geometry.placement.SLICE_Z`, the same geometry ``preview`` fills, drawn as the cut in the top view),
the rooms (closed free areas, with their spec names) and openings (a spec's doors and windows) that hover labels
name, the TurtleBot3 from our own description at its spawn pose, and the LiDAR rays on request.

Numbers are rounded (millimetres, 1e-4 for unit quaternions) so the same input gives the same bytes.
"""

from __future__ import annotations

import base64
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

from ..check.sources import WorldSource
from ..core.scene import Scene, Shape

GREY = (0.7, 0.7, 0.7, 1.0)   # Gazebo/Grey: what a visual without a known material looks like
FLOOR_MARGIN = 3.0            # m of floor drawn around everything built


@dataclass
class ShownWorld:
    """What the page shows, read from the input: the scene, and a spec's building when it came from one."""

    scene: Scene
    title: str
    subtitle: str = ""
    spawn: tuple[float, float, float] | None = None
    robot: str = "burger"
    spec: object | None = None        # worldgen.spec.model.Spec
    building: object | None = None    # worldgen.geometry.building.Building
    world: WorldSource | None = None   # for the LiDAR job: a world file, or the SDF text written for a spec
    walls: frozenset = field(default_factory=frozenset)   # models drawn as walls (the rest are obstacles)
    others: tuple = ()   # a launch file's other robots: (namespace, model, (x, y, yaw)) each


def read_source(path: str | Path, model_paths: Sequence[str | Path] = ()) -> ShownWorld:
    """The world of a spec, a world file or a launch file (its world, spawn pose and robot)."""
    from ..check.validate import input_kind
    from ..core.errors import InputError

    path = Path(path)
    if not path.exists():
        raise InputError("no such file", path=path, hint="give a .world/.sdf file, a floorplan spec or a launch file")
    kind = input_kind(path)
    if kind == "spec":
        return _spec_source(path, model_paths)
    if kind == "launch":
        return _launch_source(path, model_paths)
    if kind != "world":
        raise InputError(f"is a {kind.replace('-', ' ')}, not a world", path=path,
                         hint="give one of its .world files, a spec or a launch file")
    return _world_source(path, model_paths)


def _spec_source(path: Path, model_paths) -> ShownWorld:
    from ..spec.load import load_spec

    return spec_source(load_spec(path), model_paths, path.name)


def spec_source(spec, model_paths=(), subtitle: str = "") -> ShownWorld:
    """A spec's world as ``worldgen build`` writes it (spec → geometry → SDF text → the reader), with the spec,
    its building, its robot's pose and its walls (the building and an ASCII grid's posts)."""
    from ..geometry.building import build_geometry
    from ..sdf.reader import read_world_text
    from ..sdf.writer import world_sdf
    from ..spec.grid import POST_PREFIX

    building = build_geometry(spec)
    text = world_sdf(building)
    scene = read_world_text(text, source=spec.source, model_paths=tuple(model_paths))
    spawn = (spec.robot.at[0], spec.robot.at[1], spec.robot.yaw) if spec.robot else None
    walls = frozenset(m for m in scene.models if m == building.name or m.startswith(POST_PREFIX))
    where = Path(spec.source).with_suffix(".world") if spec.source else Path(f"{spec.name}.world")
    return ShownWorld(scene, spec.name, subtitle, spawn, spec.robot.model if spec.robot else "burger", spec,
                      building, WorldSource(where, text), walls=walls)


def _world_source(path: Path, model_paths, title: str | None = None) -> ShownWorld:
    from ..sdf.reader import read_world

    scene = read_world(path, model_paths=tuple(model_paths))
    return ShownWorld(scene, title or world_title(scene, path), path.name, world=WorldSource(path),
                      walls=static_models(scene))


def world_title(scene: Scene, path: Path) -> str:
    """A world's name, unless it is the ``default`` that Gazebo gives every world: then its file's."""
    return f"world '{scene.world_name}'" if scene.world_name and scene.world_name != "default" else path.name


def static_models(scene: Scene) -> frozenset:
    """The models a world page draws as walls: those with static shapes."""
    return frozenset(s.model for s in scene.shapes if s.static)


def _launch_source(path: Path, model_paths) -> ShownWorld:
    import dataclasses

    from ..core.errors import InputError
    from ..core.spawnpose import plan_pose
    from ..launch.reader import read_launch
    from ..spec.model import ROBOT_MODELS

    info = read_launch(path)
    if info.world_path is None or not Path(info.world_path).is_file():
        raise InputError(f"the world this launch file starts cannot be found: {info.world_ref or '(none)'}",
                         path=path, hint="make its world_name an existing world file, or view the world itself")
    source = _world_source(Path(info.world_path), model_paths)
    spawn = plan_pose(info.spawn)
    robot = info.model if info.model in ROBOT_MODELS else "burger"
    others = tuple((r.ns, r.robot if r.robot in ROBOT_MODELS else robot, plan_pose(r.pose))
                   for r in info.robots[1:] if r.pose is not None)
    return dataclasses.replace(source, subtitle=f"{path.name} → {Path(info.world_path).name}", spawn=spawn,
                               robot=robot, others=others)



# ------------------------------------------------------------------------------------------------ the data
def r3(value: float) -> float:
    """Millimetres (and no negative zero)."""
    return round(float(value), 3) + 0.0


def r4(value: float) -> float:
    return round(float(value), 4) + 0.0


def hex_colour(color) -> str:
    r, g, b = (max(0, min(255, round(c * 255))) for c in (color or GREY)[:3])
    return f"#{r:02x}{g:02x}{b:02x}"


def shape_item(shape: Shape, group: str, meshes: list) -> dict | None:
    """One drawable: kind, pose, size, colour, group (wall, obstacle, marking, robot), label; a mesh's triangles
    go to ``meshes`` (exported as glTF) and the item names its index. None for what cannot be drawn."""
    item = {"k": shape.kind, "p": [r3(v) for v in shape.position], "q": [r4(v) for v in shape.orientation],
            "c": hex_colour(shape.color), "g": group, "n": shape.label}
    alpha = shape.color[3] if shape.color is not None and len(shape.color) > 3 else 1.0
    if alpha <= 0:
        return None
    if alpha < 1:
        item["a"] = r3(alpha)
    if shape.kind == "box" and shape.size is not None and all(s > 0 for s in shape.size):
        item["s"] = [r3(s) for s in shape.size]
    elif shape.kind == "cylinder" and (shape.radius or 0) > 0 and (shape.length or 0) > 0:
        item["r"], item["l"] = r3(shape.radius), r3(shape.length)
    elif shape.kind == "sphere" and (shape.radius or 0) > 0:
        item["r"] = r3(shape.radius)
    elif shape.kind == "mesh" and _valid_faces(shape):
        item["m"] = len(meshes)
        meshes.append(shape)
    else:
        return None
    return item


def _valid_faces(shape: Shape) -> int:
    """How many of a mesh's faces index its vertices (the rest are dropped)."""
    import numpy as np

    if shape.vertices is None or shape.faces is None:
        return 0
    count = len(np.asarray(shape.vertices).reshape(-1, 3))
    faces = np.asarray(shape.faces).reshape(-1, 3)
    return int(((faces >= 0) & (faces < count)).all(axis=1).sum())


def meshes_glb(shapes: list[Shape]) -> str:
    """The meshes as one binary glTF (base64), node ``m{i}`` holding mesh i in its own frame (the page places it)."""
    import numpy as np
    import trimesh

    scene = trimesh.Scene()
    for i, shape in enumerate(shapes):
        vertices = np.round(np.asarray(shape.vertices, float).reshape(-1, 3), 4)
        faces = np.asarray(shape.faces, int).reshape(-1, 3)
        faces = faces[(faces >= 0).all(axis=1) & (faces < len(vertices)).all(axis=1)]
        mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False)
        scene.add_geometry(mesh, node_name=f"m{i}", geom_name=f"m{i}")
    data = scene.export(file_type="glb", include_normals=False)
    return base64.b64encode(data).decode("ascii")


def _group(shape: Shape, walls: frozenset) -> str:
    from ..geometry.markings import is_floor_marking

    if is_floor_marking(shape):
        return "marking"
    return "wall" if shape.model in walls else "obstacle"


def world_items(source: ShownWorld, meshes: list) -> list[dict]:
    """Every visual of the scene (a model without visuals: its collisions), ground planes left to the page."""
    scene = source.scene
    with_visuals = {s.model for s in scene.visuals}
    shapes = list(scene.visuals) + [s for s in scene.shapes if s.model not in with_visuals]
    items = []
    for shape in shapes:
        if shape.kind == "plane":
            continue
        item = shape_item(shape, _group(shape, source.walls), meshes)
        if item is not None:
            items.append(item)
    return items


def polygon_rings(geometry) -> list[list[list[list[float]]]]:
    """A shapely (Multi)Polygon as a list of polygons, each [exterior, *holes] of [x, y] points (mm rounded;
    points within half a millimetre of the line through their neighbours left out)."""
    geometry = geometry.simplify(0.0005)
    polygons = [geometry] if geometry.geom_type == "Polygon" else \
        [g for g in getattr(geometry, "geoms", []) if g.geom_type == "Polygon"]
    out = []
    for polygon in polygons:
        if polygon.is_empty:
            continue
        rings = [polygon.exterior, *polygon.interiors]
        out.append([[[r3(x), r3(y)] for x, y in list(ring.coords)[:-1]] for ring in rings])
    return out


def plan(source: ShownWorld) -> dict:
    """The cut at the robot's height: sections (walls and obstacles apart), closed rooms with their names and
    sizes, the bounds of everything built."""
    import shapely

    from ..geometry.placement import SLICE_Z, world_rooms
    from ..geometry.slices import footprints_between

    prints = footprints_between(source.scene, *SLICE_Z)
    wall_prints = [p.geometry for p in prints if p.label.split("/")[0] in source.walls]
    other_prints = [p.geometry for p in prints if p.label.split("/")[0] not in source.walls]
    room_items = []
    if source.spec is not None:   # a spec's rooms, inside their walls (a door joins two, each keeps its name)
        regions = [(f"room '{name}'", polygon) for name, polygon in _spec_rooms(source)]
    else:                         # a world's: the closed free areas the robot fits in
        regions = [(f"closed room {i}", region) for i, region in enumerate(world_rooms(source.scene).rooms(), 1)]
    for text, region in regions:
        x0, y0, x1, y1 = region.bounds
        room_items.append({"n": f"{text}: {x1 - x0:.2f} × {y1 - y0:.2f} m inside, {region.area:.1f} m² of floor",
                           "poly": polygon_rings(region)})
    everything = [g for g in (shapely.union_all(wall_prints) if wall_prints else None,
                              shapely.union_all(other_prints) if other_prints else None) if g is not None]
    return {"z": SLICE_Z, "walls": polygon_rings(shapely.union_all(wall_prints)) if wall_prints else [],
            "obstacles": polygon_rings(shapely.union_all(other_prints)) if other_prints else [],
            "rooms": room_items, "_geometry": everything}


def _spec_rooms(source: ShownWorld) -> list:
    """Each room of the spec: its name and its floor inside the walls (the centre-line polygon less half the
    walls' thickness)."""
    import shapely

    out = []
    for room in source.spec.rooms:
        if len(room.vertices) < 3:
            continue
        inside = shapely.Polygon(room.vertices).buffer(-room.style.thickness / 2, join_style="mitre")
        if not inside.is_empty:
            out.append((room.name, inside))
    return out


def openings(source: ShownWorld) -> list[dict]:
    """A spec's doors and windows: where they are (centre, along-wall yaw, width × height, sill) and what to call
    them."""
    building = source.building
    if building is None:
        return []
    out = []
    for wall in building.walls:
        c, s = math.cos(wall.yaw), math.sin(wall.yaw)
        where = f"in the wall of room '{wall.rooms[0]}'" if wall.rooms else f"in wall {wall.index}"
        for opening in wall.openings:
            mid = (opening.s0 + opening.s1) / 2
            width, height = opening.s1 - opening.s0, opening.z1 - opening.z0
            sill = f", sill {opening.z0:.2f} m" if opening.type == "window" else ""
            out.append({"type": opening.type, "p": [r3(wall.start[0] + mid * c), r3(wall.start[1] + mid * s),
                                                    r3((opening.z0 + opening.z1) / 2)],
                        "yaw": r4(wall.yaw), "s": [r3(width), r3(wall.thickness), r3(height)],
                        "n": f"{opening.type} {width:.2f} m wide × {height:.2f} m high{sill}, {where}"})
    return out


def bounds(source: ShownWorld, plan_geometry: list, spawns) -> list[float]:
    """xmin, ymin, xmax, ymax of the plan, the floor markings and the robots' spawns (None: none; 2 m around the
    origin when empty)."""
    from ..geometry.markings import floor_markings, footprint

    boxes = [g.bounds for g in plan_geometry]
    for marking in floor_markings(source.scene):
        for shape in marking.shapes:
            boxes.append(footprint(shape).bounds)
    for spawn in (s for s in spawns if s is not None):
        boxes.append((spawn[0] - 0.3, spawn[1] - 0.3, spawn[0] + 0.3, spawn[1] + 0.3))
    if not boxes:
        return [-1.0, -1.0, 1.0, 1.0]
    return [r3(min(b[0] for b in boxes)), r3(min(b[1] for b in boxes)), r3(max(b[2] for b in boxes)),
            r3(max(b[3] for b in boxes))]


def floor(source: ShownWorld, box: list[float]) -> dict:
    """The ground the page draws under the world: the scene's ground plane's colour, the bounds and a margin."""
    planes = [s for s in list(source.scene.visuals) + list(source.scene.shapes) if s.kind == "plane"]
    colour = next((s.color for s in planes if s.color is not None), GREY)
    return {"c": hex_colour(colour), "box": [r3(box[0] - FLOOR_MARGIN), r3(box[1] - FLOOR_MARGIN),
                                             r3(box[2] + FLOOR_MARGIN), r3(box[3] + FLOOR_MARGIN)],
            "ground": bool(planes)}


def robot_data(model: str, spawn) -> dict:
    """Our TurtleBot3 ``model`` as primitives in its base_footprint frame, its LiDAR's pose and beams, and the
    spawn pose (x, y, yaw)."""
    from ..geometry.placement import robot_radius
    from ..robots.description import robot_file, robot_urdf
    from ..robots.profile import link_frames, robot_profile
    from ..robots.visuals import link_visuals

    urdf = robot_urdf(model)
    profile = robot_profile(urdf)
    frames = link_frames(profile.joints, profile.base_frame if profile.base_frame in profile.links
                         else profile.root_link)
    parts, meshes = [], []
    for shape in link_visuals(urdf, robot_file(model)):
        if shape.link not in frames:
            continue
        placed = _in_frame(shape, frames[shape.link])
        item = shape_item(placed, "robot", meshes)
        if item is not None and "m" not in item:   # our descriptions are primitives; a mesh would need its GLB
            item["n"] = f"{model}: {shape.link}"
            parts.append(item)
    lidar = None
    if profile.lidar is not None and profile.lidar.link in frames:
        xyz, _ = frames[profile.lidar.link]
        lp = profile.lidar
        lidar = {"p": [r3(xyz[0] + lp.pose[0]), r3(xyz[1] + lp.pose[1]), r3(xyz[2] + lp.pose[2])],
                 "min": r4(lp.min_angle), "inc": r4(lp.angle_increment), "n": lp.samples,
                 "max": r3(lp.range_max)}
    return {"model": model, "parts": parts, "radius": r3(robot_radius(model)), "lidar": lidar,
            "spawn": [r3(v) for v in spawn] if spawn is not None else None}


def _in_frame(shape: Shape, frame) -> Shape:
    """``shape`` (posed in its link) posed in the base frame, given the link's (xyz, rotation) there."""
    import dataclasses

    from ..core import poses

    xyz, rotation = frame
    link = poses.transform(xyz, rotation)
    placed = link @ poses.transform(shape.position, poses.quat_matrix(*shape.orientation))
    return dataclasses.replace(shape, position=tuple(float(v) for v in placed[:3, 3]),
                               orientation=poses.matrix_quat(placed[:3, :3]))


def rays_data(rays) -> list[list]:
    """LiDAR rays (x0, y0, x1, y1, hit) rounded."""
    return [[r3(x0), r3(y0), r3(x1), r3(y1), 1 if hit else 0] for x0, y0, x1, y1, hit in rays]


def world_data(source: ShownWorld, rays=None) -> dict:
    """Everything the page draws of a world (see the module docstring)."""
    meshes: list[Shape] = []
    items = world_items(source, meshes)
    cut = plan(source)
    geometry = cut.pop("_geometry")
    box = bounds(source, geometry, [source.spawn, *(pose for _, _, pose in source.others)])
    data = {"title": source.title, "subtitle": source.subtitle, "items": items, "plan": cut,
            "openings": openings(source), "bounds": box, "floor": floor(source, box),
            "robot": robot_data(source.robot, source.spawn)}
    if source.others:
        data["others"] = [dict(robot_data(model, pose), ns=ns) for ns, model, pose in source.others]
    if meshes:
        data["glb"] = meshes_glb(meshes)
    if rays:
        data["rays"] = rays_data(rays)
    return data

