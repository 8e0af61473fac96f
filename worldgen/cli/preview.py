"""``worldgen preview SPEC|WORLD|FOLDER``: a top-down PNG of walls, openings, obstacles, the spawn pose and LiDAR
rays; of a folder, a contact sheet of every world and spec in it, all to one scale."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import click

from ..core.errors import InputError
from ..core.fsio import check_free, write_file
from ..spec.model import ROBOT_MODELS
from .outputs import check_suffix


@click.command("preview")
@click.argument("source", type=click.Path(path_type=Path), metavar="SPEC|WORLD|FOLDER")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None, metavar="FILE.png",
              help="The picture to write (default: the input's name with .png, in the current folder).")
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="The robot's pose, metres and radians (default: the spec's robot; none for a world).")
@click.option("--robot", type=click.Choice(ROBOT_MODELS), default=None,
              help="The TurtleBot3 whose footprint is drawn (default: the spec's, else burger).")
@click.option("--lidar", is_flag=True, help="Simulate one LiDAR scan from the spawn pose and draw its rays.")
@click.option("--model-path", "model_paths", multiple=True, type=click.Path(path_type=Path), metavar="DIR",
              help="A folder of Gazebo models for a world's model:// includes (repeatable).")
@click.option("--force", is_flag=True, help="Overwrite the picture if it exists.")
def preview(source: Path, output: Path | None, spawn: str | None, robot: str | None, lidar: bool,
            model_paths: tuple[Path, ...], force: bool) -> None:
    """Draw SPEC (.yaml, .json, .txt grid) or WORLD (.world, .sdf) from above, to scale: what a TurtleBot3
    meets at its own height (walls, obstacles; doors and windows of a spec), and where it spawns. A FOLDER is
    drawn as one contact sheet: every world and spec in it side by side, all to one scale, each with its name and
    spawn (worldgen generate's sets, a class's worlds)."""
    check_suffix(output, "png", "-o")
    if source.is_dir():
        return _sheet(source, output, spawn, lidar, robot, model_paths, force)
    from ..view.preview import Spawn, picture, render
    from ..core.inputs import refuse_unread
    from ..core.spawnpose import parse_spawn

    refuse_unread(source, "a world or spec")   # before the output's name is taken from it
    output = output or Path(f"{source.stem}.png")
    check_free([output], force)   # before the work; write_file checks again
    pose = parse_spawn(spawn) if spawn is not None else None
    pic = picture(source, model_paths)
    model = robot or (pic.spawn.model if pic.spawn else "burger")
    if pose is not None:
        pic = dataclasses.replace(pic, spawn=Spawn(*pose, model))
    elif pic.spawn is not None:
        pic = dataclasses.replace(pic, spawn=dataclasses.replace(pic.spawn, model=model))
    rays = None
    if lidar:
        if pic.spawn is None:
            raise InputError("--lidar needs a spawn pose", hint="give --spawn X,Y[,YAW] or a robot: in the spec")
        from ..view.preview import lidar_rays

        rays = lidar_rays(pic, pic.spawn, model_paths)
    for finding in pic.scene.findings:
        if finding.severity != "info":
            click.echo(f"worldgen: {finding.severity}: {finding.message}", err=True)
    path = write_file(output, render(pic, rays), force=force)
    click.echo(f"wrote {path}")


def _sheet(folder: Path, output: Path | None, spawn: str | None, lidar: bool, robot: str | None,
           model_paths: tuple[Path, ...], force: bool) -> None:
    from ..view.sheet import sheet

    if spawn is not None or lidar:
        raise InputError(f"{'--spawn' if spawn is not None else '--lidar'} is for one world, and {folder} is a folder",
                         hint="leave it out to draw the folder's contact sheet, or give one file")
    output = output or Path(f"{folder.resolve().name or 'sheet'}.png")
    check_free([output], force)
    drawing = sheet(folder, model_paths, robot, failed=lambda bad, err: click.echo(f"worldgen: not drawn: {err}",
                                                                                  err=True))
    path = write_file(output, drawing, force=force)
    click.echo(f"wrote {path}")


COMMANDS = [preview]
