"""The class's catkin packages, ready for ``catkin_make``: ``WORKSPACE/src/intro_robo/``.

* ``lab_a_spin_circles`` — ``scripts/spin_in_circles.py``: a constant Twist on ``cmd_vel``;
* ``lab_a_stop_at_wall`` — ``scripts/stop_at_wall.py``: P (PID) control on the LiDAR's front distance, the law
  of :mod:`worldgen.core.stoplaw` that ``worldgen drive`` runs (``inf`` from Gazebo and ``0`` from the real
  LDS-01 both mean "nothing seen");
* ``class_meeting_02_custom_gazebo_world`` — ``worlds/enclosed_room.world`` (built from
  ``examples/enclosed_room.yaml``, shipped in the wheel too) and ``launch/turtlebot3_in_enclosed_room.launch``;
* ``lab_b_line_follower`` — ``scripts/line_follower.py``: proportional steering on a tape line seen by the Waffle
  Pi's camera (cv_bridge, an HSV mask, the mask's centroid), and its own world with a tape loop
  (``worlds/line_track.world``, from ``examples/line_track.yaml``) whose launch file starts a Waffle Pi on the tape;
* ``intro_robo`` — a metapackage grouping the four.

Each lab package also has a launch file that starts the class world with its node. The node scripts are rendered
from ``templates/nodes/``; everything else comes from :mod:`worldgen.packages.catkin`, so the packages are exactly what
``worldgen scaffold`` would make.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ..launch.writer_xml import default_launch_name, launch_xml, parse_node
from ..core import stoplaw
from ..core.numbers import format_number
from ..core.resources import examples_dir, render_template
from .catkin import PackageArgs, PackageFiles, PackageRequest, package_files, package_request, world_from_spec
from ..core.fsio import write_tree
from .course_names import LINE_PACKAGE, REPOSITORY, WORLD_PACKAGE

DEPENDENCIES = ("rospy", "std_msgs", "geometry_msgs", "sensor_msgs")
VERSION = "0.1.0"
LICENSE = "BSD"
SPIN = {"linear_speed": 0.1, "angular_speed": 0.5}
# yellow tape (OpenCV's hue runs 0-180); the gains follow the line_track example's loop at --rate 1 and max
LINE = {"hsv_lower": [20, 80, 80], "hsv_upper": [40, 255, 255], "kp": 0.8, "max_speed": 0.12, "slow_down": 0.5,
        "search_top": 0.6, "search_turn": 0.4}
LINE_RUNTIME = ("cv_bridge",)   # a rospy node's import: exec_depend only (catkin_make needs no cv_bridge to build it)
# the node's defaults are worldgen drive's, so the two run the same law (worldgen.core.stoplaw)
STOP = {"target_distance": stoplaw.TARGET, "kp": stoplaw.KP, "max_speed": stoplaw.MAX_SPEED,
        "front_angle": format_number(stoplaw.FRONT_ANGLE), "stop_band": stoplaw.STOP_BAND,
        "resume_margin": stoplaw.RESUME_MARGIN}


def _request(name: str, description: str, maintainer: str | None, exec_only=()) -> PackageRequest:
    req = package_request(PackageArgs(name, DEPENDENCIES, version=VERSION, description=description,
                                      licenses=(LICENSE,), maintainers=(maintainer,) if maintainer else ()))
    return replace(req, exec_only=tuple(exec_only))


def course_files(maintainer: str | None = None) -> PackageFiles:
    """Every file of the class repository, relative to ``src/intro_robo`` (see the module docstring)."""
    world_file, world_text, spawn = world_from_spec(examples_dir() / "enclosed_room.yaml")
    worlds = {world_file: world_text}
    launches = {default_launch_name(world_file): launch_xml(world_file, WORLD_PACKAGE, "optenv", spawn)}
    world_pkg = package_files(
        _request(WORLD_PACKAGE, "Class meeting 02: a custom Gazebo world (a closed room) and the launch file that "
                                "puts a TurtleBot3 in it", maintainer), worlds, launches)

    def lab(name: str, script: str, params: dict, description: str) -> PackageFiles:
        node = parse_node(f"{name}/{script}")
        launch_name = f"{node.name}.launch"
        launch = launch_xml(world_file, WORLD_PACKAGE, "optenv", spawn, nodes=[node],
                            launch_name=launch_name, home=name)
        code = render_template(f"nodes/{script}.j2", package=name, **params)
        return package_files(_request(name, description, maintainer, exec_only=[WORLD_PACKAGE]),
                             launches={launch_name: launch}, scripts={script: code})

    spin = lab("lab_a_spin_circles", "spin_in_circles.py", SPIN,
               "Lab A: drive a TurtleBot3 in circles by publishing a Twist on cmd_vel")
    stop = lab("lab_a_stop_at_wall", "stop_at_wall.py", STOP,
               "Lab A: drive a TurtleBot3 to a wall and stop there, with proportional control on the LiDAR")
    line = _line_lab(maintainer)
    meta_req = package_request(PackageArgs(REPOSITORY, version=VERSION, licenses=(LICENSE,), meta=True,
                                           description="The intro robotics class: its labs and Gazebo worlds",
                                           maintainers=(maintainer,) if maintainer else ()))
    meta = package_files(replace(meta_req, exec_only=("lab_a_spin_circles", "lab_a_stop_at_wall", LINE_PACKAGE,
                                                      WORLD_PACKAGE)))

    merged = PackageFiles({}, set())
    for folder, pkg in ((REPOSITORY, meta), ("lab_a_spin_circles", spin), ("lab_a_stop_at_wall", stop),
                        (LINE_PACKAGE, line), (WORLD_PACKAGE, world_pkg)):
        placed = pkg.under(folder)
        merged.files.update(placed.files)
        merged.executable |= placed.executable
    return merged


def _line_lab(maintainer: str | None) -> PackageFiles:
    """Lab B: the line follower, with its world (a tape loop) and a launch file that starts a Waffle Pi on it."""
    world_file, world_text, spawn = world_from_spec(examples_dir() / "line_track.yaml", "waffle_pi")
    node = parse_node(f"{LINE_PACKAGE}/line_follower.py")
    launch_name = f"{node.name}.launch"
    launch = launch_xml(world_file, LINE_PACKAGE, "waffle_pi", spawn, nodes=[node], launch_name=launch_name)
    code = render_template("nodes/line_follower.py.j2", package=LINE_PACKAGE, **LINE)
    req = _request(LINE_PACKAGE, "Lab B: follow a line of tape on the floor with the Waffle Pi's camera, with "
                                 "proportional control on where the line is in the image", maintainer,
                   exec_only=LINE_RUNTIME)
    return package_files(req, worlds={world_file: world_text}, launches={launch_name: launch},
                         scripts={"line_follower.py": code})


def write_course(workspace: str | Path, *, force: bool = False, maintainer: str | None = None) -> Path:
    """Write ``WORKSPACE/src/intro_robo`` all at once (nothing on error). An existing ``intro_robo`` folder is
    refused unless ``force``, which replaces it. Returns the folder."""
    pkg = course_files(maintainer)
    return write_tree(Path(workspace) / "src" / REPOSITORY, pkg.files, force=force, executable=pkg.executable)
