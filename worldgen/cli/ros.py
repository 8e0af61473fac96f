"""``worldgen launch``, ``worldgen scaffold`` and ``worldgen course``: launch files and packages for ROS 1 (catkin,
the default ``--ros noetic``) and ROS 2 (ament_python, ``--ros humble|jazzy``).

A thin layer over :mod:`worldgen.launch.writer_xml`, :mod:`worldgen.launch.writer_py`, :mod:`worldgen.geometry.placement`,
:mod:`worldgen.packages.catkin`, :mod:`worldgen.packages.ament`, :mod:`worldgen.packages.course_ros1` and :mod:`worldgen.packages.course_ros2`.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import click

from ..launch.writer_xml import MODEL_CHOICES
from ..launch.targets import CMD_VEL_CHOICES, DEFAULT_ROS, ROS_TARGETS

ROS_HELP = ("The ROS and Gazebo to write for: noetic (ROS 1, Gazebo Classic), humble (ROS 2, Gazebo Classic) or "
            "jazzy (ROS 2, Gazebo Sim).")
CMD_VEL_HELP = ("jazzy: the ROS type of cmd_vel: stamped (geometry_msgs/msg/TwistStamped, TurtleBot3's default) or "
                "twist (geometry_msgs/msg/Twist).")


def ros_option(function):
    """The ``--ros noetic|humble|jazzy`` option (default noetic: the ROS 1 files, unchanged)."""
    return click.option("--ros", type=click.Choice(ROS_TARGETS), default=DEFAULT_ROS, show_default=True,
                        help=ROS_HELP)(function)


def cmd_vel_option(function):
    """The ``--cmd-vel stamped|twist`` option (Jazzy's bridge and class nodes; default: stamped there)."""
    return click.option("--cmd-vel", type=click.Choice(CMD_VEL_CHOICES), default=None, help=CMD_VEL_HELP)(function)


@click.command("launch")
@click.argument("world", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--package", "package", metavar="PKG",
              help="The package whose worlds/ folder holds WORLD (default: the package around WORLD).")
@click.option("--name", metavar="FILE", help="Launch file name (default: turtlebot3_in_<world>.launch, or "
                                               ".launch.py for ROS 2).")
@click.option("--model", type=click.Choice(MODEL_CHOICES), default="optenv", show_default=True,
              help="The launch file's default robot model: optenv writes $(optenv TURTLEBOT3_MODEL burger) "
                   "(TURTLEBOT3_MODEL when it is set, else burger); env the class's exact $(env TURTLEBOT3_MODEL) "
                   "(roslaunch fails when it is unset); or a fixed model.")
@click.option("--spawn", metavar="X,Y[,YAW]",
              help="Spawn pose in metres and radians, on the floor (default: the spec's robot pose, else the "
                   "deepest free point of the room).")
@click.option("--node", "nodes", multiple=True, metavar="PKG/TYPE[:NAME]",
              help="Also start this node (repeatable), e.g. lab_a_stop_at_wall/stop_at_wall.py.")
@click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path),
              help="Folder to write to (default: the package's launch/ folder when WORLD is in PKG/worlds/, "
                   "else the current folder).")
@ros_option
@cmd_vel_option
@click.option("--force", is_flag=True, help="Overwrite an existing launch file.")
def launch_command(world: Path, package: str | None, name: str | None, model: str, spawn: str | None,
                   nodes: tuple[str, ...], output: Path | None, ros: str, cmd_vel: str | None, force: bool) -> None:
    """Write the launch file that starts Gazebo with WORLD and spawns a TurtleBot3 in it (with --ros jazzy also
    the package's params/turtlebot3_bridge.yaml)."""
    from ..core.errors import InputError
    from ..core.inputs import refuse_unread
    from ..core.numbers import format_number
    from ..core.fsio import write_files
    from ..spec.model import SPEC_SUFFIXES
    from ..launch.gz_bridge_params import BRIDGE_FILE, bridge_yaml
    from ..launch.writer_xml import default_launch_name, launch_xml, package_name_of, parse_node
    from ..launch.writer_py import default_launch_py_name, launch_py, without_same_params
    from ..launch.targets import check_world_target, cmd_vel_type
    from ..core.spawnpose import floor_pose, parse_spawn
    from ..launch.spawn import spawn_for_world
    from ..packages.world_files import launch_depends_update, update_notes

    node_refs = [parse_node(n) for n in nodes]
    refuse_unread(world, "a world")
    if world.suffix.lower() in SPEC_SUFFIXES:
        raise InputError("is a floorplan spec, not a world", path=world,
                         hint="build it first (worldgen build SPEC --package PKG puts the world in the package beside "
                              "its launch file), or launch the .world worldgen build wrote")
    check_world_target(world, ros)
    world_pkg = world.resolve().parent.parent if world.resolve().parent.name == "worlds" else None
    if world_pkg is not None and not (world_pkg / "package.xml").is_file():
        world_pkg = None
    if package is None:
        if world_pkg is None:
            raise InputError("which package holds the world?", path=world,
                             hint="pass --package PKG (the launch file finds the world as $(find PKG)/worlds/...)")
        package = package_name_of(world_pkg)
    ros2 = ros != "noetic"
    suffixes = (".launch.py",) if ros2 else (".launch", ".launch.xml")
    launch_name = name or (default_launch_py_name(world.name) if ros2 else default_launch_name(world.name))
    if not launch_name.endswith(suffixes):
        launch_name += suffixes[0]
    if Path(launch_name).name != launch_name:
        raise InputError(f"--name {name!r} is a path, not a file name", hint="use -o DIR for the folder")
    if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.+-]*", launch_name):
        raise InputError(f"--name {name!r} cannot be passed to {'ros2 launch' if ros2 else 'roslaunch'}",
                         hint="name the launch file with letters, digits, '_', '-' and '.' only")
    kind = cmd_vel_type(ros, cmd_vel)
    given = floor_pose(parse_spawn(spawn)) if spawn is not None else None
    pose, source = spawn_for_world(world, model, given)
    if ros2:
        text = launch_py(world.name, package, ros, model, pose, node_refs, launch_name=launch_name)
    else:
        text = launch_xml(world.name, package, model, pose, node_refs, launch_name=launch_name)
    folder = output if output is not None else (world_pkg / "launch" if world_pkg is not None else Path("."))
    files = {folder / launch_name: text}
    if ros == "jazzy":   # the bridge's topics, in the package beside the world (or beside the launch file)
        files = without_same_params({**files, (world_pkg or folder) / "params" / BRIDGE_FILE: bridge_yaml(kind)})
    inside = world_pkg is not None and os.path.abspath(folder).startswith(os.path.join(os.path.abspath(world_pkg), ""))
    updated = launch_depends_update(world_pkg, ros, {n.package for n in node_refs}) if inside else {}
    said = update_notes(updated)
    written = write_files({**files, **updated}, force=force, within=world_pkg or folder, update=set(updated))
    target = written[0]
    from ..launch.unfound import unfound

    for line in unfound(target, package, world_pkg if inside else None, world.name, node_refs, ros):
        click.echo(f"worldgen: warning: {line}", err=True)
    for extra in written[1:]:
        click.echo(said.get(extra, f"wrote {extra} (the ros_gz_bridge topics; install params/ with the package)"))
    where = {"given": "--spawn", "spec": "the spec's robot pose", "world": "the deepest free point of the room",
             "open": "the world has no closed room: the deepest free point inside its walls"}
    click.echo(f"wrote {target} (spawn {format_number(pose[0])}, {format_number(pose[1])}, yaw "
               f"{format_number(pose[3])}: {where[source]})")


class _CatkinStyleCommand(click.Command):
    """Options -s/--sys-deps and -b/--boost-comps take every following word up to the next option, as
    catkin_create_pkg's do (``-s eigen opencv -b thread``)."""

    GREEDY = ("-s", "--sys-deps", "-b", "--boost-comps")

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        spread: list[str] = []
        current = None
        for i, word in enumerate(args):
            if word == "--":
                spread += args[i:]
                break
            if current is not None and not word.startswith("-"):
                spread += [current, word]
                continue
            current = word if word in self.GREEDY else None
            if current is None:
                spread.append(word)
        return super().parse_args(ctx, spread)


@click.command("scaffold", cls=_CatkinStyleCommand)
@click.argument("name")
@click.argument("dependencies", nargs=-1)
@click.option("--meta", is_flag=True, help="Create a metapackage.")
@click.option("-s", "--sys-deps", "sys_deps", multiple=True, metavar="DEP...", help="System dependencies.")
@click.option("-b", "--boost-comps", "boost_comps", multiple=True, metavar="COMP...", help="Boost components.")
@click.option("-V", "--pkg_version", "version", metavar="VERSION", help="Initial package version (0.0.0).")
@click.option("-D", "--description", help='Description (default "The NAME package").')
@click.option("-l", "--license", "licenses", multiple=True, help="A license (repeatable; default TODO).")
@click.option("-a", "--author", "authors", multiple=True, metavar="'NAME [<EMAIL>]'",
              help="An author (repeatable).")
@click.option("-m", "--maintainer", "maintainers", multiple=True, metavar="'NAME [<EMAIL>]'",
              help="A maintainer (repeatable; default: you, with NAME@todo.todo).")
@click.option("--rosdistro", default=lambda: os.environ.get("ROS_DISTRO"), metavar="DISTRO",
              help="The ROS distro (default: $ROS_DISTRO); ROS 1 only (ignored with --ros humble|jazzy).")
@click.option("-p", "--path", "parent", type=click.Path(file_okay=False, path_type=Path), default=Path("."),
              help="Folder to create the package in (default: the current folder).")
@click.option("--world", "world_spec", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              metavar="SPEC", help="Build this floorplan spec into worlds/ and its launch file into launch/.")
@ros_option
@cmd_vel_option
@click.option("--force", is_flag=True, help="Replace an existing package folder.")
def scaffold_command(name: str, dependencies: tuple[str, ...], meta: bool, sys_deps: tuple[str, ...],
                     boost_comps: tuple[str, ...], version: str | None, description: str | None,
                     licenses: tuple[str, ...], authors: tuple[str, ...], maintainers: tuple[str, ...],
                     rosdistro: str | None, parent: Path, world_spec: Path | None, ros: str, cmd_vel: str | None,
                     force: bool) -> None:
    """Create the catkin package NAME depending on DEPENDENCIES, as catkin_create_pkg does, with launch/,
    worlds/ and scripts/ folders that install, and optionally a world and its launch file. With --ros
    humble|jazzy an ament_python package as 'ros2 pkg create --build-type ament_python' makes it, with
    launch/ and worlds/ (jazzy: params/) that setup.py installs."""
    from ..packages.catkin import PackageArgs, create_package, package_request

    args = PackageArgs(name, tuple(dependencies), sys_deps=tuple(sys_deps), boost_comps=tuple(boost_comps),
                       version=version, description=description, licenses=tuple(licenses), authors=tuple(authors),
                       maintainers=tuple(maintainers), meta=meta, rosdistro=rosdistro)
    if ros != "noetic":
        from ..packages.ament import ament_request, create_ament_package

        target = create_ament_package(parent, ament_request(args), ros, world_spec=world_spec, cmd_vel=cmd_vel,
                                      force=force)
        click.echo(f"wrote {target}")
        return
    if cmd_vel == "stamped":
        from ..launch.targets import cmd_vel_type

        cmd_vel_type(ros, cmd_vel)
    target = create_package(parent, package_request(args), world_spec=world_spec, force=force)
    click.echo(f"wrote {target}")


@click.command("course")
@click.option("--workspace", "-w", type=click.Path(file_okay=False, path_type=Path), default=Path("."),
              show_default=True, help="The catkin (or colcon) workspace; packages go to WORKSPACE/src/intro_robo.")
@ros_option
@cmd_vel_option
@click.option("--force", is_flag=True, help="Replace an existing src/intro_robo folder.")
def course_command(workspace: Path, ros: str, cmd_vel: str | None, force: bool) -> None:
    """Write the class packages (labs, the enclosed-room world, its launch file) into a catkin workspace, or
    with --ros humble|jazzy into a colcon workspace."""
    from ..packages.course_ros1 import write_course

    if ros != "noetic":
        from ..packages.course_ros2 import write_course_ros2

        target = write_course_ros2(workspace, ros, cmd_vel=cmd_vel, force=force)
        click.echo(f"wrote {target}; build it with: cd {workspace} && colcon build")
        return
    if cmd_vel == "stamped":
        from ..launch.targets import cmd_vel_type

        cmd_vel_type(ros, cmd_vel)
    target = write_course(workspace, force=force)
    from ..packages.catkin_make import catkin_make_command

    click.echo(f"wrote {target}; build it with: cd {workspace} && {catkin_make_command()}")


COMMANDS = [launch_command, scaffold_command, course_command]
