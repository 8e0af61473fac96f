"""Reading a spec's obstacles (boxes, cylinders, spheres) and its robot (model and spawn pose)."""

from __future__ import annotations

from . import values
from .messages import describe_sized
from .model import (KEY_EXAMPLES, OBSTACLE_KEYS, ROBOT_KEYS, ROBOT_MODELS, SHAPE_KEYS, SHAPES, Material, Obstacle,
                    Point, RobotPose)
from .nodes import Node
from .values import Source


def read_obstacle(src: Source, node: Node, index: int) -> Obstacle:
    label = f"obstacle {index + 1}"
    keys = values.mapping(src, node, label, OBSTACLE_KEYS, required=("shape",))
    shape = values.text(src, keys["shape"], f"shape of {label}", SHAPES)
    name = values.name(src, keys["name"], "obstacle name") if "name" in keys else None
    what = f"obstacle '{name}'" if name else label
    for key in keys:
        if key in ("size", "radius", "height") and key not in SHAPE_KEYS[shape]:
            src.fail(f"{what} is a {shape}, which has no '{key}'", keys[key].line,
                     hint=f"a {shape} takes {' and '.join(SHAPE_KEYS[shape])}")
    for key in SHAPE_KEYS[shape]:
        if key not in keys:
            example = "size: [0.5, 0.5, 0.5]" if key == "size" else KEY_EXAMPLES[key]
            src.fail(f"{what} has no '{key}'", node.line, hint=f"a {shape} takes "
                     f"{' and '.join(SHAPE_KEYS[shape])}; add {example}")
    if "at" not in keys:
        src.fail(f"{what} has no 'at'", node.line, hint="add at: [x, y], the centre of its footprint")
    size = radius = height = None
    if shape == "box":
        s = keys["size"]
        if not isinstance(s.value, list) or len(s.value) != 3:
            src.fail(f"size of {what} must be [x, y, z] in metres, not {describe_sized(s.value)}", s.line,
                     hint="e.g. size: [0.5, 0.4, 0.8]")
        size = tuple(values.length(src, v, f"{axis} size of {what}") for v, axis in zip(s.value, "xyz"))
    else:
        radius = values.length(src, keys["radius"], f"radius of {what}")
        if shape == "cylinder":
            height = values.length(src, keys["height"], f"height of {what}")
    return Obstacle(
        shape=shape, at=values.point(src, keys["at"], f"'at' of {what}"),
        yaw=values.angle(src, keys["yaw"], f"yaw of {what}") if "yaw" in keys else 0.0,
        size=size, radius=radius, height=height,
        material=values.material(src, keys["material"], f"material of {what}") if "material" in keys else Material(),
        name=name, line=node.line)


def read_robot(src: Source, node: Node, grid_robot: tuple[Point, float] | None) -> RobotPose:
    keys = values.mapping(src, node, "robot", ROBOT_KEYS)
    model = values.text(src, keys["model"], "robot model", ROBOT_MODELS) if "model" in keys else "burger"
    if grid_robot is not None:
        if "at" in keys or "yaw" in keys:
            src.fail("the robot is placed twice: by the grid and by robot: at/yaw", node.line,
                     hint="remove the R from the grid, or at/yaw from robot:")
        return RobotPose(model=model, at=grid_robot[0], yaw=grid_robot[1], line=node.line)
    if "at" not in keys:
        src.fail("robot has no 'at'", node.line, hint="add at: [x, y], where the robot spawns")
    return RobotPose(model=model, at=values.point(src, keys["at"], "robot 'at'"),
                     yaw=values.angle(src, keys["yaw"], "robot yaw") if "yaw" in keys else 0.0, line=node.line)
