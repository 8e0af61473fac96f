"""``worldgen doctor [NODE…|FOLDER]``: are the modules the nodes import installed; one apt line for the gaps."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from ..core.errors import EXIT_FAILED, EXIT_OK
from .ros import ros_option


@click.command("doctor")
@click.argument("paths", nargs=-1, type=click.Path(path_type=Path))
@click.option("--format", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@ros_option
def doctor(paths, fmt, ros):
    """Look up every module the rospy nodes in PATHS import (node files, or folders of them: a class's
    submissions, catkin packages' scripts/ and nodes/) for the Python that runs the nodes, without running
    them. Prints a table (module, needed by, provided by, state) and one `sudo apt-get install` line for every
    missing package. With no PATHS, checks the class runtime on this machine.

    With --ros humble|jazzy: rclpy nodes, for the Python that has rclpy (as `worldgen run --ros` finds it), with
    ROS 2's package names (ros-DISTRO-… from apt, or PyPI's ros-jazzy-… wheels in a venv).

    Exit 0: everything found; 1: something missing; 2: a path that does not exist.
    """
    from ..runtime.doctor import check_machine, check_nodes, to_json, to_text
    from ..runtime.naming import Naming

    if ros == "noetic":
        from ..ros1.transport import doctor_python, noetic

        python, naming = doctor_python(), Naming("noetic", noetic())
    else:
        from ..ros2.pyenv import doctor_python as rclpy_python

        python, naming = rclpy_python(), Naming(ros)
    found = check_nodes(paths, python, naming=naming) if paths else check_machine(python, naming=naming)
    click.echo(to_json(found) if fmt == "json" else to_text(found), nl=False)
    sys.exit(EXIT_OK if found.ok else EXIT_FAILED)


COMMANDS = [doctor]
