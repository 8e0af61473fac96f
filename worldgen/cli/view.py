"""``worldgen view WORLD|SPEC|LAUNCH -o FILE.html``: one self-contained 3D page of a world, to open in any browser."""

from __future__ import annotations

from pathlib import Path

import click

from ..spec.model import ROBOT_MODELS


@click.command("view")
@click.argument("source", type=click.Path(path_type=Path), metavar="WORLD|SPEC|LAUNCH")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None, metavar="FILE.html",
              help="The page to write (default: the input's name with .html, in the current folder).")
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="The robot's pose, metres and radians (default: the launch file's or the spec's; none for a world).")
@click.option("--robot", type=click.Choice(ROBOT_MODELS), default=None,
              help="The TurtleBot3 drawn at the spawn pose (default: the launch file's or the spec's, else burger).")
@click.option("--lidar", is_flag=True, help="Simulate one LiDAR scan from the spawn pose and draw its rays.")
@click.option("--model-path", "model_paths", multiple=True, type=click.Path(path_type=Path), metavar="DIR",
              help="A folder of Gazebo models for a world's model:// includes (repeatable).")
@click.option("--force", is_flag=True, help="Overwrite the page if it exists.")
def view(source: Path, output: Path | None, spawn: str | None, robot: str | None, lidar: bool,
         model_paths: tuple[Path, ...], force: bool) -> None:
    """Write WORLD (.world, .sdf), SPEC (.yaml, .json, .txt grid) or LAUNCH (.launch: its world, robot and spawn
    pose) as one HTML file that shows it in 3D as Gazebo draws it: walls, obstacles, meshes, floor markings, the
    TurtleBot3 at its spawn pose. Orbit, pan and zoom; a top view cut at the robot's height; names and sizes of
    rooms, doors and windows on hover. The page needs no network and no Gazebo."""
    from ..core.fsio import check_free, write_file
    from ..core.spawnpose import parse_spawn
    from ..view.page import world_page

    from .outputs import check_suffix

    output = output or Path(f"{source.stem}.html")
    check_suffix(output, "html", "-o")
    check_free([output], force)   # before the work; write_file checks again
    pose = parse_spawn(spawn) if spawn is not None else None
    page = world_page(source, spawn=pose, robot=robot, lidar=lidar, model_paths=model_paths)
    path = write_file(output, page, force=force)
    click.echo(f"wrote {path} ({len(page) / 1e6:.2f} MB)")


COMMANDS = [view]
