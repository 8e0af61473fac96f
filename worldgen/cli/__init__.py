"""The ``worldgen`` command: a thin click layer over the library.

Every command lives in a module of this package, named for its job, exposing ``COMMANDS``. Domain errors become
one line on stderr and exit code 2 (click's own usage errors exit 2 as well); 1 is reserved for "checks ran and
failed".
"""

from __future__ import annotations

import sys

import click

from .. import __version__
from ..core.errors import EXIT_BAD_INPUT, WorldgenError


class _Group(click.Group):
    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except WorldgenError as err:
            click.echo(f"worldgen: error: {err}", err=True)
            sys.exit(EXIT_BAD_INPUT)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(__version__, prog_name="worldgen")
def main() -> None:
    """Gazebo worlds for TurtleBot3 classes: build them from text, launch them, check them headless."""


from . import build, drive, new, preview, ros, run, sim, validate  # noqa: E402  (each module registers its commands)

for _module in (new, build, preview, ros, validate, drive, sim, run):
    for _command in _module.COMMANDS:
        main.add_command(_command)
