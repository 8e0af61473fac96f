"""The SDF writer: a :class:`~worldgen.geometry.building.Building` becomes a Gazebo world, or a Building-Editor model folder.

The shape is the one Gazebo's Building Editor saves (see ``world_sdf``), so a class can open, edit and re-save the
result in Gazebo Classic, and it also suits pybullet's SDF loader: ``<static>1</static>`` rather than ``true``,
every element on its own short line, no ``<include>`` (ground plane and sun are written inline, so the world needs
no model path). Output is byte-identical for the same building: fixed element order, fixed float format.
"""

from __future__ import annotations

import math
from pathlib import Path

from lxml import etree

from ..core.numbers import format_numbers
from ..geometry.building import Building, Wall, build_geometry, obstacle_names
from ..geometry.tape import THICKNESS, layer_bottom, tape_pieces
from ..spec.markings import marking_names
from ..spec.model import MARKINGS_MODEL, Material, Obstacle, Spec

SDF_VERSIONS = ("1.6", "1.7", "1.8", "1.9")
DEFAULT_SDF_VERSION = "1.6"     # Gazebo 9 and 11 (ROS Melodic and Noetic) read it
MATERIAL_URI = "file://media/materials/scripts/gazebo.material"
XML_DECLARATION = '<?xml version="1.0"?>\n'

# The top-down GUI camera: Gazebo's user camera has a 60° horizontal field of view; the window is assumed no
# wider than 4:3, and the view keeps a margin around the building.
CAMERA_FOV = math.radians(60.0)
CAMERA_ASPECT = 4.0 / 3.0
CAMERA_MARGIN = 1.1             # times the building's half size …
CAMERA_PAD = 0.5                # … plus this, in metres
GROUND_SIZE = 100.0             # the ground plane's side, in metres, unless the building needs more


def _vec(*values: float) -> str:
    """Numbers as SDF text, space-separated: up to 6 decimals, trailing zeros trimmed, never ``-0``."""
    return format_numbers(values, 6, point=False)


def _el(parent, tag: str, text: str | None = None, **attrs: str):
    element = etree.SubElement(parent, tag, attrs)
    if text is not None:
        element.text = text
    return element


def _leaves(parent, **texts: str) -> None:
    """One child element per keyword, in order, each holding only its text."""
    for tag, text in texts.items():
        _el(parent, tag, text)


def _pose(parent, x: float = 0.0, y: float = 0.0, z: float = 0.0, yaw: float = 0.0, pitch: float = 0.0) -> None:
    _el(parent, "pose", _vec(x, y, z, 0.0, pitch, yaw))


def _check_version(sdf_version: str) -> None:
    if sdf_version not in SDF_VERSIONS:
        raise ValueError(f"SDF version {sdf_version!r} is not one of {', '.join(SDF_VERSIONS)}")


def _text(root) -> str:
    return XML_DECLARATION + etree.tostring(root, pretty_print=True, encoding="unicode")


# ------------------------------------------------------------------------------------------------ public
def spec_world_sdf(spec: Spec, sdf_version: str = DEFAULT_SDF_VERSION) -> str:
    """The ``.world`` text of a spec, as ``worldgen build`` writes it: spec → geometry → SDF."""
    return world_sdf(build_geometry(spec), sdf_version)


def world_sdf(building: Building, sdf_version: str = DEFAULT_SDF_VERSION) -> str:
    """The ``.world`` text: ``<world name="default">`` holding the scene, the sun, an inline ground plane, ODE
    physics as in the TurtleBot3 worlds, gravity, the building model, one static model per obstacle, the floor
    markings' model (when the spec has lines or patches) and a GUI camera looking straight down on the whole
    building."""
    _check_version(sdf_version)
    root = etree.Element("sdf", version=sdf_version)
    world = _el(root, "world", name="default")
    scene = _el(world, "scene")
    _el(scene, "ambient", "0.4 0.4 0.4 1")
    _el(scene, "background", "0.7 0.7 0.7 1")
    _el(scene, "shadows", "1")
    _sun(world)
    _ground_plane(world, building)
    _physics(world)
    _el(world, "gravity", "0 0 -9.8")
    if building.walls:
        _building_model(world, building)
    for name, obstacle in zip(obstacle_names(building.obstacles, building.name), building.obstacles):
        _obstacle_model(world, name, obstacle)
    if building.lines or building.patches:
        _markings_model(world, building)
    _gui_camera(world, building)
    return _text(root)


def model_sdf(building: Building, sdf_version: str = DEFAULT_SDF_VERSION) -> str:
    """The building model alone (``<sdf><model>``), as the Building Editor's Save writes ``model.sdf``."""
    _check_version(sdf_version)
    root = etree.Element("sdf", version=sdf_version)
    _building_model(root, building)
    return _text(root)


def model_config(building: Building, sdf_version: str = DEFAULT_SDF_VERSION, description: str | None = None) -> str:
    """The ``model.config`` beside ``model.sdf``: name, version, SDF file, author and description."""
    _check_version(sdf_version)
    root = etree.Element("model")
    _el(root, "name", building.name)
    _el(root, "version", "1.0")
    _el(root, "sdf", "model.sdf", version=sdf_version)
    author = _el(root, "author")
    _el(author, "name", "worldgen")
    _el(author, "email", "")
    _el(root, "description", description or f"{building.name}: walls built by worldgen")
    return _text(root)


def planned_files(building: Building, out_dir: str | Path, *, sdf_version: str = DEFAULT_SDF_VERSION,
                  model_dir: bool = False, description: str | None = None) -> dict[Path, str]:
    """What ``worldgen build`` writes, path → text: ``OUT/NAME.world``, and with ``model_dir`` the model folder
    ``OUT/NAME/model.config`` + ``model.sdf``."""
    out = Path(out_dir)
    files = {out / f"{building.name}.world": world_sdf(building, sdf_version)}
    if model_dir:
        folder = out / building.name
        files[folder / "model.config"] = model_config(building, sdf_version, description)
        files[folder / "model.sdf"] = model_sdf(building, sdf_version)
    return files


# ------------------------------------------------------------------------------------------ world parts
def _sun(world) -> None:
    """Gazebo's stock sun, inline."""
    light = _el(world, "light", name="sun", type="directional")
    _el(light, "cast_shadows", "1")
    _pose(light, z=10.0)
    _leaves(light, diffuse="0.8 0.8 0.8 1", specular="0.2 0.2 0.2 1")
    _leaves(_el(light, "attenuation"), range="1000", constant="0.9", linear="0.01", quadratic="0.001")
    _el(light, "direction", "-0.5 0.1 -0.9")


def _ground_plane(world, building: Building) -> None:
    """Gazebo's stock ground plane, inline, made large enough for the building."""
    reach = max((abs(v) for v in building.bounds), default=0.0)
    size = max(GROUND_SIZE, 10.0 * math.ceil((2 * reach + 20.0) / 10.0))
    model = _el(world, "model", name="ground_plane")
    _el(model, "static", "1")
    link = _el(model, "link", name="link")
    collision = _el(link, "collision", name="collision")
    _plane(collision, size)
    surface = _el(collision, "surface")
    ode = _el(_el(surface, "friction"), "ode")
    _el(ode, "mu", "100")
    _el(ode, "mu2", "50")
    visual = _el(link, "visual", name="visual")
    _el(visual, "cast_shadows", "0")
    _plane(visual, size)
    _material(visual, Material(script="Gazebo/Grey"))


def _plane(parent, size: float) -> None:
    plane = _el(_el(parent, "geometry"), "plane")
    _el(plane, "normal", "0 0 1")
    _el(plane, "size", _vec(size, size))


def _physics(world) -> None:
    """ODE at 1 kHz, real time, as in ROBOTIS's TurtleBot3 worlds."""
    physics = _el(world, "physics", type="ode")
    _leaves(physics, max_step_size="0.001", real_time_factor="1", real_time_update_rate="1000")
    ode = _el(physics, "ode")
    _leaves(_el(ode, "solver"), type="quick", iters="150", precon_iters="0", sor="1.4",
            use_dynamic_moi_rescaling="1")
    _leaves(_el(ode, "constraints"), cfm="0.00001", erp="0.2", contact_max_correcting_vel="2000",
            contact_surface_layer="0.01")


def _gui_camera(world, building: Building) -> None:
    """A user camera straight above the building's centre, image up = +y, right = +x, high enough to show
    everything (the tops of the walls included) with a margin."""
    x0, y0, x1, y1 = building.bounds
    top = max([w.height for w in building.walls] + [_obstacle_height(o) for o in building.obstacles] + [0.0])
    half_x = CAMERA_MARGIN * (x1 - x0) / 2 + CAMERA_PAD
    half_y = CAMERA_MARGIN * (y1 - y0) / 2 + CAMERA_PAD
    tan_h = math.tan(CAMERA_FOV / 2)
    tan_v = tan_h / CAMERA_ASPECT
    z = top + max(half_x / tan_h, half_y / tan_v, 2.0)
    camera = _el(_el(world, "gui", fullscreen="0"), "camera", name="user_camera")
    _pose(camera, (x0 + x1) / 2, (y0 + y1) / 2, z, yaw=math.pi / 2, pitch=math.pi / 2)
    _el(camera, "view_controller", "orbit")
    _el(camera, "projection_type", "perspective")


# ------------------------------------------------------------------------------------------------ models
def _material(parent, material: Material) -> None:
    element = _el(parent, "material")
    if material.script:
        script = _el(element, "script")
        _el(script, "uri", MATERIAL_URI)
        _el(script, "name", material.script)
    elif material.rgba:
        _el(element, "ambient", _vec(*material.rgba))
        _el(element, "diffuse", _vec(*material.rgba))


def _building_model(parent, building: Building) -> None:
    """One static model at the walls' bounding-box centre; one link ``Wall_N`` per wall, posed relative to it."""
    ox, oy = building.origin
    model = _el(parent, "model", name=building.name)
    _pose(model, ox, oy)
    for wall in building.walls:
        _wall_link(model, wall, ox, oy)
    _el(model, "static", "1")


def _wall_link(model, wall: Wall, ox: float, oy: float) -> None:
    """A wall's link sits at its box's centre with the wall's yaw. An unsplit wall has ``Wall_N_Collision`` and
    ``Wall_N_Visual``; a wall split around openings has ``…_Collision_i`` / ``…_Visual_i``, one per piece."""
    name = f"Wall_{wall.index}"
    length = wall.length
    link = _el(model, "link", name=name)
    _pose(link, (wall.start[0] + wall.end[0]) / 2 - ox, (wall.start[1] + wall.end[1]) / 2 - oy, yaw=wall.yaw)
    single = len(wall.pieces) == 1 and not wall.openings
    for i, piece in enumerate(wall.pieces):
        suffix = "" if single else f"_{i}"
        pose = ((piece.s0 + piece.s1) / 2 - length / 2, 0.0, (piece.z0 + piece.z1) / 2)
        size = (piece.s1 - piece.s0, wall.thickness, piece.z1 - piece.z0)
        collision = _el(link, "collision", name=f"{name}_Collision{suffix}")
        _geometry_box(collision, pose, size)
        visual = _el(link, "visual", name=f"{name}_Visual{suffix}")
        _geometry_box(visual, pose, size)
        _material(visual, wall.material)


def _geometry_box(element, pose: tuple[float, float, float], size: tuple[float, float, float]) -> None:
    _pose(element, *pose)
    _el(_el(_el(element, "geometry"), "box"), "size", _vec(*size))


def _obstacle_height(o: Obstacle) -> float:
    if o.shape == "box":
        return o.size[2]
    if o.shape == "cylinder":
        return o.height
    return 2 * o.radius


def _obstacle_model(world, name: str, o: Obstacle) -> None:
    """A static model standing on the ground: one link with a box, cylinder or sphere."""
    model = _el(world, "model", name=name)
    _pose(model, o.at[0], o.at[1], _obstacle_height(o) / 2, yaw=o.yaw)
    link = _el(model, "link", name="link")
    for tag in ("collision", "visual"):
        element = _el(link, tag, name=tag)
        shape = _el(_el(element, "geometry"), o.shape)
        if o.shape == "box":
            _el(shape, "size", _vec(*o.size))
        elif o.shape == "cylinder":
            _el(shape, "radius", _vec(o.radius))
            _el(shape, "length", _vec(o.height))
        else:
            _el(shape, "radius", _vec(o.radius))
        if tag == "visual":
            _material(element, o.material)
    _el(model, "static", "1")


# ------------------------------------------------------------------------------------------ floor markings
def _markings_model(world, building: Building) -> None:
    """The spec's lines and patches: one static model, a link per patch and per line named as the spec names
    them, holding visuals only (no ``<collision>``: the robot drives over them and its LiDAR never sees them).
    Each piece is a box or a disc :data:`~worldgen.geometry.tape.THICKNESS` thick lying on the ground plane:
    a patch one box or disc, a line a box per segment and a disc at each joint (:mod:`worldgen.geometry.tape`).
    Patches come first, then lines, each a :data:`~worldgen.geometry.tape.LAYER` above the one before, so that
    where they cross the later one is seen."""
    line_names, patch_names = marking_names(building.lines, building.patches)
    model = _el(world, "model", name=MARKINGS_MODEL)
    _pose(model)
    layer = 0
    for name, patch in zip(patch_names, building.patches):
        link = _el(model, "link", name=name)
        z = layer_bottom(layer) + THICKNESS / 2
        if patch.shape == "rect":
            _flat_piece(link, f"{name}_Visual", patch.color, (patch.center[0], patch.center[1], z, patch.yaw),
                        size=(patch.size[0], patch.size[1]))
        else:
            _flat_piece(link, f"{name}_Visual", patch.color, (patch.center[0], patch.center[1], z, 0.0),
                        radius=patch.radius)
        layer += 1
    for name, line in zip(line_names, building.lines):
        link = _el(model, "link", name=name)
        z = layer_bottom(layer) + THICKNESS / 2
        strips, joints = tape_pieces(line.points, line.closed)
        for i, strip in enumerate(strips):
            _flat_piece(link, f"{name}_Segment_{i}", line.color, (strip.center[0], strip.center[1], z, strip.yaw),
                        size=(strip.length, line.width))
        first = 0 if line.closed else 1   # joints are numbered by their point
        for i, (x, y) in enumerate(joints):
            _flat_piece(link, f"{name}_Joint_{first + i}", line.color, (x, y, z, 0.0), radius=line.width / 2)
        layer += 1
    _el(model, "static", "1")


def _flat_piece(link, name: str, material: Material, pose: tuple[float, float, float, float],
                size: tuple[float, float] | None = None, radius: float | None = None) -> None:
    """One ``<visual>`` lying on the floor: a box ``size`` (x, y) or a disc of ``radius``, THICKNESS thick,
    centred at ``pose`` (x, y, z, yaw)."""
    visual = _el(link, "visual", name=name)
    _el(visual, "cast_shadows", "0")
    x, y, z, yaw = pose
    _pose(visual, x, y, z, yaw=yaw)
    geometry = _el(visual, "geometry")
    if size is not None:
        _el(_el(geometry, "box"), "size", _vec(size[0], size[1], THICKNESS))
    else:
        cylinder = _el(geometry, "cylinder")
        _el(cylinder, "radius", _vec(radius))
        _el(cylinder, "length", _vec(THICKNESS))
    _material(visual, material)
