"""``worldgen build``: a floorplan spec becomes a Gazebo world (and, on request, a Building-Editor model folder).

A thin layer over :func:`worldgen.spec.load.load_spec`, :func:`worldgen.geometry.building.build_geometry` and
:func:`worldgen.sdf.writer.planned_files`. The command gathers every output in one ``{path: text}`` mapping and
writes it all-or-nothing, so further outputs (a package's worlds/ and launch/ folders, say) are one more
``files.update(...)`` before the write. A plain build imports only lxml and PyYAML, to keep it fast; with
``--package`` and no ``robot:`` in the spec, the robot's place is found in the built world (shapely, numpy).
"""

from __future__ import annotations

from pathlib import Path

import click

SDF_VERSION_CHOICES = ("1.6", "1.7", "1.8", "1.9")   # = worldgen.sdf.writer.SDF_VERSIONS, without importing it
ROS_CHOICES = ("noetic", "humble", "jazzy")          # = worldgen.launch.targets.ROS_TARGETS
CMD_VEL_CHOICES = ("stamped", "twist")               # = worldgen.launch.targets.CMD_VEL_CHOICES
WORLD_SUFFIXES = (".world", ".sdf")


@click.command("build")
@click.argument("spec", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=Path("."),
              show_default=True, help="Folder for NAME.world (created if missing).")
@click.option("--sdf-version", type=click.Choice(SDF_VERSION_CHOICES), default=None,
              help="SDF version to write: 1.6 (the default) for Gazebo 9/11 (ROS Melodic/Noetic/Humble), newer "
                   "on request; with --ros jazzy 1.8 (the default) or 1.9.")
@click.option("--model-dir", is_flag=True,
              help="Also write the building as a model folder OUT/NAME/ (model.config + model.sdf), as the "
                   "Building Editor saves it.")
@click.option("--package", "package_dir", type=click.Path(exists=True, file_okay=False, path_type=Path),
              metavar="DIR", help="A catkin package folder: write the world to DIR/worlds/NAME.world (instead of "
                                  "OUT) and its launch file to DIR/launch/turtlebot3_in_NAME.launch. With --ros "
                                  "humble|jazzy an ament_python package: DIR/launch/turtlebot3_in_NAME.launch.py "
                                  "(and, for jazzy, DIR/worlds/NAME.sdf and DIR/params/turtlebot3_bridge.yaml).")
@click.option("--ros", type=click.Choice(ROS_CHOICES), default="noetic", show_default=True,
              help="The ROS and Gazebo to write for: noetic (Gazebo Classic, roslaunch XML), humble (Gazebo "
                   "Classic, a .launch.py) or jazzy (a Gazebo Sim world NAME.sdf, a .launch.py and the "
                   "ros_gz_bridge topics).")
@click.option("--cmd-vel", type=click.Choice(CMD_VEL_CHOICES), default=None,
              help="jazzy: the ROS type cmd_vel is bridged as: stamped (geometry_msgs/msg/TwistStamped, "
                   "TurtleBot3's default) or twist (geometry_msgs/msg/Twist).")
@click.option("--force", is_flag=True, help="Overwrite existing files.")
def build_command(spec: Path, out_dir: Path, sdf_version: str | None, model_dir: bool, package_dir: Path | None,
                  ros: str, cmd_vel: str | None, force: bool) -> None:
    """Build the Gazebo world of the floorplan SPEC (YAML/JSON, or an ASCII grid .txt) as OUT/NAME.world
    (OUT/NAME.sdf, a Gazebo Sim world, with --ros jazzy)."""
    from ..core.errors import InputError
    from ..geometry.building import build_geometry
    from ..launch.targets import SDF_VERSION
    from ..sdf.writer import planned_files
    from ..spec.load import load_spec

    if spec.suffix.lower() in WORLD_SUFFIXES:
        raise InputError(f"{spec} is a Gazebo world, not a floorplan spec",
                         hint="build takes a .yaml/.json spec or a .txt grid (worldgen new NAME writes one); "
                              "check a world with worldgen validate, draw it with worldgen preview")
    if out_dir.suffix.lower() in WORLD_SUFFIXES + (".launch", ".yaml") and not out_dir.is_dir():
        raise InputError("-o is the folder the world is written into, and this is named like a file", path=out_dir,
                         hint=f"give a folder: -o {out_dir.parent} writes {out_dir.parent / 'NAME'}.world, where NAME "
                              "is the spec's name:")
    plan = load_spec(spec)
    building = build_geometry(plan)
    if model_dir and not building.walls:
        raise InputError(f"{spec} has no walls, so there is no building model for --model-dir",
                         hint="leave out --model-dir, or add rooms or segments")
    if ros == "jazzy":
        return _build_gzsim(spec, plan, building, out_dir, sdf_version, model_dir, package_dir, cmd_vel, force)
    if cmd_vel == "stamped":
        raise InputError(f"--cmd-vel stamped is for --ros jazzy: {ros}'s Gazebo diff drive takes a Twist",
                         hint="leave out --cmd-vel, or pass --ros jazzy")
    files = planned_files(building, out_dir, sdf_version=sdf_version or SDF_VERSION[ros], model_dir=model_dir,
                          description=f"{building.name}: built by worldgen from {_text(spec.name)}")
    if package_dir is not None:   # the world moves into the package, beside its launch file
        from ..launch.spawn import launch_model, spec_spawn
        from ..packages.world_files import package_world_files

        world_text = files.pop(out_dir / f"{building.name}.world")
        model = launch_model(plan)
        spawn = spec_spawn(plan, world_text, model)
        files.update(package_world_files(package_dir, building.name, world_text, spawn, ros, model))
    _write(files, force, package_dir if package_dir is not None else out_dir, package_dir, ros)


def _build_gzsim(spec: Path, plan, building, out_dir: Path, sdf_version: str | None, model_dir: bool,
                 package_dir: Path | None, cmd_vel: str | None, force: bool) -> None:
    """build --ros jazzy: the Gazebo Sim world OUT/NAME.sdf, or with --package the world, its launch file and
    the bridge's parameters in the package (a parameter file already there with the same bytes is kept)."""
    from ..core.errors import InputError
    from ..sdf.gzsim import GZ_SDF_VERSIONS, gzsim_world
    from ..sdf.writer import world_sdf

    if model_dir:
        raise InputError("--model-dir writes the Building Editor's model folder, which is Gazebo Classic's",
                         hint="leave out --model-dir with --ros jazzy")
    version = sdf_version or GZ_SDF_VERSIONS[0]
    if version not in GZ_SDF_VERSIONS:
        raise InputError(f"--ros jazzy writes SDF {' or '.join(GZ_SDF_VERSIONS)}, not {version}",
                         hint="leave out --sdf-version, or pass --sdf-version 1.9")
    classic = world_sdf(building, version)
    world_text = gzsim_world(classic, version)
    if package_dir is None:
        files = {out_dir / f"{building.name}.sdf": world_text}
    else:
        from ..launch.spawn import launch_model, spec_spawn
        from ..launch.writer_py import without_same_params
        from ..packages.world_files import package_world_files

        model = launch_model(plan)
        files = without_same_params(package_world_files(package_dir, building.name, world_text,
                                                        spec_spawn(plan, classic, model), "jazzy", model, cmd_vel))
    _write(files, force, package_dir if package_dir is not None else out_dir, package_dir, "jazzy")


def _write(files: dict, force: bool, within: Path, package_dir: Path | None, ros: str) -> None:
    """Write the files, all or none; into a package, its package.xml is given the exec_depends the launch file
    needs when it lacks them (a package scaffolded without --world), so that validate has nothing to say."""
    from ..core.fsio import write_files
    from ..packages.world_files import launch_depends_update, update_notes

    updated = launch_depends_update(package_dir, ros) if package_dir is not None else {}
    said = update_notes(updated)
    for path in write_files({**files, **updated}, force=force, within=within, update=set(updated)):
        click.echo(said.get(path, f"wrote {path}"))


def _text(name: str) -> str:
    """A file name as text for a file: one that is not UTF-8 (PEP 383 stand-ins) gets U+FFFD for its odd bytes."""
    import os

    return os.fsencode(name).decode("utf-8", "replace")


COMMANDS = [build_command]
