"""What the simulator node simulates: a world file, a floorplan spec (built as ``worldgen build`` would) or a
launch file (the world it starts, its robots and spawn poses, the parameters it sets) → a scene, a robot model and
a spawn pose, each with where it came from; and the node's config file for one run."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from pathlib import Path

from ..core.errors import InputError, WorldFileError
from ..core.scene import Scene
from ..check.sources import load_scene
from ..core.spawnpose import plan_pose


@dataclass
class World:
    path: Path
    scene: Scene
    robot: str
    robot_source: str
    spawn: tuple[float, float, float]
    spawn_source: str
    robots: list[dict] = field(default_factory=list)   # several robots: name, ns, robot, spawn, tf_prefix, mappings
    params: dict = field(default_factory=dict)          # what the launch file sets on the master (full name → value)


def load_world(path: str | Path, *, spawn=None, robot: str | None = None, launch: str | Path | None = None,
               model_paths=()) -> World:
    """Read the input (see the module docstring). ``spawn``/``robot`` override what the files say; ``launch``
    takes the spawn pose and robot from that launch file. InputError or WorldFileError when it cannot be read."""
    from ..check.validate import input_kind

    path = Path(path)
    if not path.exists():
        raise InputError("no such file", path=path, hint="give a .world/.sdf file, a floorplan spec or a launch file")
    kind = input_kind(path)
    found_robot, found_spawn, robot_src, spawn_src = None, None, "default", "the world's origin"
    world_file = path
    robots: list[dict] = []
    params: dict = {}
    if kind == "launch":
        world_file, found_robot, found_spawn, robots, params = _from_launch(path)
        robot_src = spawn_src = f"launch file {path}"
    elif kind == "package":
        raise InputError("is a catkin package folder, not a world", path=path,
                         hint="give the package's .world or .launch file")
    scene, spec_robot = load_scene(world_file, "spec" if kind == "spec" else "world", model_paths)
    if spec_robot is not None:
        found_robot, found_spawn = spec_robot["model"], tuple(spec_robot["spawn"])
        robot_src = spawn_src = f"spec {path}"
    if launch is not None:
        _, launch_robot, launch_spawn, robots, params = _from_launch(Path(launch), need_world=False)
        if launch_robot:
            found_robot, robot_src = launch_robot, f"launch file {launch}"
        if launch_spawn:
            found_spawn, spawn_src = launch_spawn, f"launch file {launch}"
    if robot is not None:
        found_robot, robot_src = robot, "--robot"
    if spawn is not None:
        found_spawn, spawn_src = tuple(spawn), "--spawn"
    if found_robot is not None:
        from ..robots import MODELS, robot_file

        file = robot_file(found_robot)   # InputError for an unknown model or missing file
        found_robot = found_robot if found_robot in MODELS else str(file)
    if robots and (robot is not None or spawn is not None):   # --robot/--spawn: the first robot's
        robots[0] = dict(robots[0], robot=found_robot or robots[0]["robot"],
                         spawn=list(found_spawn or robots[0]["spawn"]))
    return World(path, scene, found_robot or "burger", robot_src, tuple(found_spawn or (0.0, 0.0, 0.0)), spawn_src,
                 robots, params)


def _from_launch(path: Path, need_world: bool = True):
    from ..launch.reader import read_launch

    info = read_launch(path)
    spawn = plan_pose(info.spawn)
    world = info.world_path
    if need_world and (world is None or not Path(world).is_file()):
        raise WorldFileError(f"the world this launch file starts cannot be found: {info.world_ref or '(none)'}",
                             path=path, hint="is its package on ROS_PACKAGE_PATH? or give the world file itself "
                                             "and --launch THIS_FILE")
    return (world, info.model if info.model in ("burger", "waffle", "waffle_pi") else None, spawn, _robots(info),
            info.params)


def _robots(info) -> list[dict]:
    """Each robot a launch file spawns in a namespace of its own, or more than one (empty for the class's one
    robot in the global namespace): what the simulator node's config lists under ``robots``."""
    spawns = [r for r in info.robots if r.pose is not None]
    if not spawns or (len(spawns) == 1 and (spawns[0].robot_namespace or spawns[0].ns).strip("/") == ""):
        return []
    robots, names = [], set()
    for i, r in enumerate(spawns):
        ns = "/" + (r.robot_namespace if r.robot_namespace is not None else r.ns).strip("/")
        model = r.robot if r.robot in ("burger", "waffle", "waffle_pi") else (info.model or "burger")
        name = r.model_name or (ns.strip("/") or f"turtlebot3_{model}")
        if name in names:
            name = f"{name}_{i}"
        names.add(name)
        mappings = dict(a.split(":=", 1) for a in r.xacro_args)
        robots.append({"name": name, "ns": ns, "robot": model, "spawn": [r.pose[0], r.pose[1], r.pose[3]],
                       "tf_prefix": r.tf_prefix, "mappings": mappings or None})
    return robots


def graded_robot(world: World, which: str) -> World:
    """``world`` with the robot ``which`` (a namespace such as ``tb3_1`` or ``/tb3_1``, or a model name) as the
    one graded: its spawn pose and model are the run's. InputError naming the robots there are when none is."""
    for entry in world.robots:
        if which in (entry["ns"], entry["ns"].strip("/"), entry["name"]):
            x, y, yaw = entry["spawn"]
            return dataclasses.replace(world, robot=entry["robot"], spawn=(x, y, yaw),
                                       spawn_source=f"{world.spawn_source}, robot {entry['ns']}")
    have = ", ".join(e["ns"] for e in world.robots) or "one robot, in no namespace of its own"
    raise InputError(f"--robot-ns {which}: the launch file spawns no robot there (it has {have})",
                     path=world.path, hint="give one of those namespaces, or leave out --robot-ns")


def write_config(folder: Path, world: World, **options) -> Path:
    """The simulator node's config (and the pickled scene) in ``folder``; see :func:`.node.main`."""
    scene_file = folder / "scene.pickle"
    world.scene.save(scene_file)
    config = {"scene_file": str(scene_file), "robot": world.robot, "spawn": list(world.spawn),
              "robots": [dict(r, spawn=list(r["spawn"])) for r in world.robots] or None, **options}

    path = folder / "sim.json"
    path.write_text(json.dumps(config), encoding="utf-8")
    return path
