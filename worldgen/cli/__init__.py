"""The ``worldgen`` command: a thin click layer over the library.

Every command lives in a module of this package, named for its job, exposing ``COMMANDS``. Domain errors and
click's usage errors (an unknown option or command, a missing argument, a bad value) become one line on stderr and
exit code 2; 1 is reserved for "checks ran and failed".
"""

from __future__ import annotations

import atexit
import codecs
import importlib
import os
import sys
import threading
from typing import NoReturn

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


# click 8.2+: bare `worldgen` (or `worldgen generate`) raises this to show the help, as an error; worldgen shows it
# as click 8.1 does, on stdout with exit 0: asking what there is is no mistake
_HELP_SHOWN = getattr(click.exceptions, "NoArgsIsHelpError", ())


def _usage_line(err: click.UsageError) -> str:
    """A click usage error as the one line every worldgen error is: what is wrong, and where the help is."""
    message = " ".join(line.strip() for line in err.format_message().splitlines() if line.strip())
    command = "worldgen"
    if err.ctx is not None:
        root = err.ctx.find_root().info_name or ""
        command = "worldgen" + err.ctx.command_path[len(root):]
    return f"worldgen: error: {message} (see '{command} --help')"


# command name → the module of this package that defines it (in its COMMANDS): a module is imported only when one
# of its commands runs (or the group's --help lists them), so `worldgen validate` loads no ROS, view or generator
COMMAND_MODULES = {"new": "new", "build": "build", "generate": "generate", "preview": "preview", "view": "view",
                   "launch": "ros", "scaffold": "ros", "course": "ros", "validate": "validate", "drive": "drive",
                   "sim": "sim", "run": "run", "doctor": "doctor"}


class SuggestingGroup(click.Group):
    """A group that answers a command it does not have with the nearest one it has (``valdate``: did you mean
    validate?), or else the list of them."""

    def resolve_command(self, ctx: click.Context, args: list[str]):
        name = args[0] if args else ""
        if name and not name.startswith("-") and self.get_command(ctx, name) is None:
            import difflib

            names = self.list_commands(ctx)
            near = difflib.get_close_matches(name, names, n=1)
            ctx.fail(f"No such command {name!r}. " + (f"Did you mean {near[0]!r}?" if near else
                                                      f"Choose one of: {', '.join(names)}."))
        return super().resolve_command(ctx, args)


class _Group(SuggestingGroup):
    """The command group: domain errors and click's usage errors (a bad option, a missing argument, an unknown
    command: click would print its four-line usage block) both become one line on stderr and exit code 2."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(self.commands) | set(COMMAND_MODULES))

    def get_command(self, ctx: click.Context, name: str):
        if name not in self.commands and name in COMMAND_MODULES:
            for command in importlib.import_module(f"{__name__}.{COMMAND_MODULES[name]}").COMMANDS:
                self.add_command(command)
        return self.commands.get(name)

    def main(self, *args, **kwargs):
        _lenient_streams()
        return super().main(*args, **kwargs)

    def make_context(self, *args, **kwargs):
        try:
            return super().make_context(*args, **kwargs)
        except click.UsageError as err:
            _usage_exit(err)

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except WorldgenError as err:
            click.echo(f"worldgen: error: {err}", err=True)
            sys.exit(EXIT_BAD_INPUT)
        except click.UsageError as err:
            _usage_exit(err)


def _usage_exit(err: click.UsageError):
    if isinstance(err, _HELP_SHOWN):
        click.echo(err.ctx.get_help())
        sys.exit(0)
    click.echo(_usage_line(err), err=True)
    sys.exit(EXIT_BAD_INPUT)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(__version__, prog_name="worldgen")
def main() -> None:
    """Gazebo worlds for TurtleBot3 classes: build them from text, launch them, check them headless."""


def run() -> None:
    """The program (``worldgen``, ``python -m worldgen``): :func:`main`, then out without the interpreter's
    teardown (:func:`leave`)."""
    leave(outcome())


def outcome():
    """:func:`main` run: its exit status (what it passed to ``sys.exit``; None for 0)."""
    try:
        main()
        return 0
    except SystemExit as done:
        return done.code


def leave(code) -> NoReturn:
    """Out with exit status ``code`` without the interpreter's teardown. Once the command has returned, its files
    are closed and its processes ended; what is left is freeing every module (numpy, pybullet, shapely, lxml …)
    one object at a time, 50–100 ms that change nothing. The exit handlers still run (a TemporaryDirectory's
    finalizer, logging's flush) and the output is flushed; a command that left a thread of its own running gets
    the orderly exit, which waits for it. An exception other than an exit goes out as Python shows it."""
    if any(t.is_alive() and not t.daemon for t in threading.enumerate() if t is not threading.main_thread()):
        sys.exit(code)
    if code is None:
        code = 0
    elif not isinstance(code, int):   # sys.exit("message"): printed, status 1, as Python does
        print(code, file=sys.stderr)
        code = 1
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):   # a reader that went away, a closed stream: nothing more can be said
            pass
    os._exit(code)
