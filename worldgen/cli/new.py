"""``worldgen new [--template room|line-track] NAME``: a commented starter floorplan spec to edit."""

from __future__ import annotations

from pathlib import Path

import click


TEMPLATES = ("room", "line-track")   # = worldgen.spec.load.STARTERS, without importing it at start-up


@click.command("new")
@click.argument("name")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="The spec file to write (default: NAME.yaml in the current folder).")
@click.option("--template", type=click.Choice(TEMPLATES), default="room", show_default=True,
              help="room: a 5 m x 5 m room with a window and an obstacle; line-track: a 4 x 3 m room with a loop "
                   "of yellow tape on the floor and a Waffle Pi on it, for line following with its camera.")
@click.option("--force", is_flag=True, help="Overwrite the file if it exists.")
def new(name: str, output: Path | None, template: str, force: bool) -> None:
    """Write a starter floorplan spec NAME.yaml, every key commented: by default a closed 5 m x 5 m room with a
    window, an obstacle and the robot in the middle (a door offered, commented out); --template line-track a
    closed room with a yellow tape loop on its floor. Build it with `worldgen build NAME.yaml`."""
    from ..core.fsio import write_file
    from ..spec.load import starter_spec

    from .outputs import check_suffix

    check_suffix(output, "yaml", "-o")
    if name.lower().endswith((".yaml", ".yml")) and output is None:   # `new my_room.yaml`: the file to write
        output, name = Path(name), Path(name).stem
    text = starter_spec(name, template)
    path = write_file(output or Path(f"{name}.yaml"), text, force=force)
    click.echo(f"wrote {path}")


COMMANDS = [new]
