"""The ``worldgen`` command: a thin click layer over the library.

Every command lives in a module of this package, named for its job, exposing ``COMMANDS``. Domain errors become
one line on stderr and exit code 2 (click's own usage errors exit 2 as well); 1 is reserved for "checks ran and
failed".
"""

from __future__ import annotations

import codecs
import sys

import click

from .. import __version__
from ..core.errors import EXIT_BAD_INPUT, WorldgenError


def _lenient(err: UnicodeError):
    """Encoding error handler for stdout/stderr: a file name that is not UTF-8 (PEP 383 stand-ins) goes out as
    its own bytes, anything else the terminal cannot show as '?' — never a crash while printing a path."""
    if not isinstance(err, UnicodeEncodeError):
        raise err
    chunk = err.object[err.start:err.end]
    if all(0xDC80 <= ord(c) <= 0xDCFF for c in chunk):
        return bytes(ord(c) - 0xDC00 for c in chunk), err.end
    return "?" * len(chunk), err.end


codecs.register_error("worldgen-lenient", _lenient)


def _lenient_streams() -> None:
    for stream in (sys.stdout, sys.stderr):
        if getattr(stream, "errors", None) == "strict" and hasattr(stream, "reconfigure"):
            try:
                stream.reconfigure(errors="worldgen-lenient")
            except (ValueError, OSError):   # a detached or closed stream: leave it
                pass


class _Group(click.Group):
    def main(self, *args, **kwargs):
        _lenient_streams()
        return super().main(*args, **kwargs)

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


from . import build, doctor, drive, generate, new, preview, ros, run, sim, validate, view  # noqa: E402  (each registers its commands)

for _module in (new, build, generate, preview, view, ros, validate, drive, sim, run, doctor):
    for _command in _module.COMMANDS:
        main.add_command(_command)
