"""Launch files for a world and a TurtleBot3: the writer, and the names and numbers it writes.

The writer emits the class's launch file shape (the one of ``turtlebot3_gazebo``): args ``model``, ``x_pos``,
``y_pos``, ``z_pos``, ``yaw``; gazebo_ros's ``empty_world.launch`` included with ``world_name`` =
``$(find PKG)/worlds/WORLD`` and the usual ``paused``/``use_sim_time``/``gui``/``headless``/``debug`` args passed
through; ``robot_description`` from xacro; ``spawn_model`` named ``spawn_urdf``; optional extra nodes.

Where the robot spawns is :mod:`worldgen.geometry.placement`'s job; reading launch files back is
:mod:`worldgen.launch.reader`'s, checking a catkin package :mod:`worldgen.packages.check`'s.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

from ..core.errors import InputError
from ..core.numbers import format_number
from ..core.resources import render_template
from ..core.packages import manifest_name
from ..spec.model import ROBOT_MODELS
from .model import NodeRef

# The launch file's default model: "optenv" is TURTLEBOT3_MODEL when set, else burger (works in a fresh shell);
# "env" is the class's exact $(env TURTLEBOT3_MODEL) (roslaunch fails when it is unset); or a fixed model.
MODEL_DEFAULTS = {"optenv": "$(optenv TURTLEBOT3_MODEL burger)", "env": "$(env TURTLEBOT3_MODEL)"}
MODEL_CHOICES = tuple(MODEL_DEFAULTS) + ROBOT_MODELS


# ---------------------------------------------------------------------------------------------------------------
# Names and numbers

_PKG_REF = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]*$")          # what catkin accepts for an existing package
_NODE_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")             # a ROS graph name (one segment)
_NODE_TYPE = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.+-]*$")       # an executable's file name


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


def check_package_ref(name: str) -> str:
    """``name`` if it can name an existing ROS package (catkin's lenient rule); InputError otherwise."""
    if not _PKG_REF.match(name or ""):
        raise InputError(f"bad package name {name!r}",
                         hint="a ROS package name holds lowercase letters, digits and underscores")
    return name


def check_world_name(world_file_name: str) -> str:
    """The file name of ``world_file_name`` if a launch file can pass it to Gazebo (no blanks, quotes or
    substitution characters); InputError otherwise."""
    world = Path(world_file_name).name
    if not world or re.search(r"[\s$()<>&\"']", world):
        raise InputError(f"world file name {world_file_name!r} cannot be passed to Gazebo",
                         hint="rename the world file: letters, digits, '_', '-' and '.' only")
    return world


# ---------------------------------------------------------------------------------------------------------------
# Writer

def default_launch_name(world_file_name: str) -> str:
    """``turtlebot3_in_<world stem>.launch``, the class's naming."""
    return f"turtlebot3_in_{Path(world_file_name).name.split('.')[0]}.launch"


def launch_xml(world_file_name: str, package: str, model: str = "optenv", spawn: Sequence[float] = (0.0, 0.0),
               nodes: Sequence[NodeRef] = (), launch_name: str | None = None, home: str | None = None) -> str:
    """The launch file text for ``PKG/worlds/WORLD`` and a TurtleBot3.

    ``model`` is ``optenv`` (the default is ``$(optenv TURTLEBOT3_MODEL burger)``), ``env`` (the class's exact
    ``$(env TURTLEBOT3_MODEL)``) or a model name; ``spawn`` is (x, y[, z[, yaw]]) written as the ``x_pos``/``y_pos``/``z_pos``/``yaw`` defaults; ``nodes`` are
    extra nodes started beside Gazebo; ``home`` is the package the launch file is in (default ``package``, the one
    whose ``worlds/`` holds the world), named in the file's ``roslaunch HOME NAME`` usage comment. Raises InputError for a bad model, package, world name or duplicate node.
    """
    if model not in MODEL_CHOICES:
        raise InputError(f"unknown robot model {model!r}", hint=f"use one of {', '.join(MODEL_CHOICES)}")
    check_package_ref(package)
    home = check_package_ref(home or package)
    world = check_world_name(world_file_name)
    pose = [float(v) for v in spawn] + [0.0] * (4 - len(spawn))
    seen = {"spawn_urdf", "gazebo", "gazebo_gui"}
    for node in nodes:
        if node.name in seen:
            raise InputError(f"two nodes would be named {node.name!r}",
                             hint="give each --node its own name: --node PKG/TYPE:NAME")
        seen.add(node.name)
    return render_template(
        "launch/turtlebot3_world.launch.j2", world=world, package=package,
        launch_hint=f"{home} {launch_name or default_launch_name(world)}",
        model_default=MODEL_DEFAULTS.get(model, model),
        x=format_number(pose[0]), y=format_number(pose[1]), z=format_number(pose[2]), yaw=format_number(pose[3]),
        nodes=list(nodes))


def package_name_of(pkg_dir: str | Path) -> str:
    """The ``<name>`` of ``pkg_dir/package.xml``, or the folder's name when there is no readable package.xml."""
    pkg_dir = Path(pkg_dir)
    name = manifest_name(pkg_dir / "package.xml")
    return name or pkg_dir.resolve().name
