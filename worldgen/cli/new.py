"""``worldgen new NAME``: a commented starter floorplan spec to edit."""

from __future__ import annotations

from pathlib import Path

import click



@click.command("new")
@click.argument("name")
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="The spec file to write (default: NAME.yaml in the current folder).")
@click.option("--force", is_flag=True, help="Overwrite the file if it exists.")
def new(name: str, output: Path | None, force: bool) -> None:
    """Write a starter floorplan spec NAME.yaml: a closed 5 m x 5 m room with a window, an obstacle and the
    robot in the middle (a door offered, commented out), every key commented. Build it with
    `worldgen build NAME.yaml`."""
    from ..core.fsio import write_file
    from ..spec.load import starter_spec

    text = starter_spec(name)
    path = write_file(output or Path(f"{name}.yaml"), text, force=force)
    click.echo(f"wrote {path}")


COMMANDS = [new]
