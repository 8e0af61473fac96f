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
WORLD_SUFFIXES = (".world", ".sdf")


@click.command("build")
@click.argument("spec", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=Path("."),
              show_default=True, help="Folder for NAME.world (created if missing).")
@click.option("--sdf-version", type=click.Choice(SDF_VERSION_CHOICES), default="1.6", show_default=True,
              help="SDF version to write: 1.6 for Gazebo 9/11 (ROS Melodic/Noetic), newer on request.")
@click.option("--model-dir", is_flag=True,
              help="Also write the building as a model folder OUT/NAME/ (model.config + model.sdf), as the "
                   "Building Editor saves it.")
@click.option("--package", "package_dir", type=click.Path(exists=True, file_okay=False, path_type=Path),
              metavar="DIR", help="A catkin package folder: write the world to DIR/worlds/NAME.world (instead of "
                                  "OUT) and its launch file to DIR/launch/turtlebot3_in_NAME.launch.")
@click.option("--force", is_flag=True, help="Overwrite existing files.")
def build_command(spec: Path, out_dir: Path, sdf_version: str, model_dir: bool, package_dir: Path | None,
                  force: bool) -> None:
    """Build the Gazebo world of the floorplan SPEC (YAML/JSON, or an ASCII grid .txt) as OUT/NAME.world."""
    from ..core.errors import InputError
    from ..core.fsio import write_files
    from ..geometry.building import build_geometry
    from ..sdf.writer import planned_files
    from ..spec.load import load_spec

    if spec.suffix.lower() in WORLD_SUFFIXES:
        raise InputError(f"{spec} is a Gazebo world, not a floorplan spec",
                         hint="build takes a .yaml/.json spec or a .txt grid (worldgen new NAME writes one); "
                              "check a world with worldgen validate, draw it with worldgen preview")
    plan = load_spec(spec)
    building = build_geometry(plan)
    if model_dir and not building.walls:
        raise InputError(f"{spec} has no walls, so there is no building model for --model-dir",
                         hint="leave out --model-dir, or add rooms or segments")
    files = planned_files(building, out_dir, sdf_version=sdf_version, model_dir=model_dir,
                          description=f"{building.name}: built by worldgen from {_text(spec.name)}")
    if package_dir is not None:   # the world moves into the package, beside its launch file
        from ..ros.launch import package_world_files
        from ..ros.spawn import spec_spawn

        world_text = files.pop(out_dir / f"{building.name}.world")
        files.update(package_world_files(package_dir, building.name, world_text, spec_spawn(plan, world_text)))
    for path in write_files(files, force=force):
        click.echo(f"wrote {path}")


def _text(name: str) -> str:
    """A file name as text for a file: one that is not UTF-8 (PEP 383 stand-ins) gets U+FFFD for its odd bytes."""
    import os

    return os.fsencode(name).decode("utf-8", "replace")


COMMANDS = [build_command]
