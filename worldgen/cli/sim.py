"""``worldgen sim WORLD``: the simulated TurtleBot3 on a ROS master, with the topics Gazebo's plugins publish."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from .drive import FiniteFloat
from .ros import cmd_vel_option, ros_option


@click.command("sim")
@click.argument("world", type=click.Path(path_type=Path))
@click.option("--spawn", default=None, metavar="X,Y[,YAW]",
              help="Spawn pose in metres and radians. Default: the launch file's, else the spec's, else 0,0,0.")
@click.option("--launch", "launch_file", type=click.Path(path_type=Path), default=None, metavar="FILE",
              help="Take the spawn pose and robot model from this launch file.")
@click.option("--robot", default=None, metavar="burger|waffle|waffle_pi|FILE",
              help="Robot model, or a .urdf/.urdf.xacro file. Default: the launch file's or spec's, else burger.")
@click.option("--rate", default="1", show_default=True, metavar="R|max",
              help="Simulated time at R x real time, or max: as fast as the nodes keep up.")
@click.option("--duration", type=FiniteFloat(min=0.0, min_open=True), default=None, metavar="S",
              help="Stop after S simulated seconds (default: run until Ctrl-C).")
@click.option("--lidar-no-hit", type=click.Choice(["inf", "zero"]), default="inf", show_default=True,
              help="What a beam that hits nothing reads: inf as in Gazebo, 0 as the real LDS-01 driver.")
@ros_option
@cmd_vel_option
def sim(world, spawn, launch_file, robot, rate, duration, lidar_no_hit, ros, cmd_vel):
    """Run the simulated TurtleBot3 in WORLD (a .world file, a floorplan spec or a launch file) as ROS nodes see
    Gazebo: /scan, /odom, /tf, /tf_static, /joint_states, /imu and /clock out, /cmd_vel in, and the
    /gazebo/reset_world and /gazebo/reset_simulation services.

    Joins the master at ROS_MASTER_URI, or starts one there when none answers (and stops it on exit). Sets
    /use_sim_time. Runs until Ctrl-C or --duration. With a launch file, first warns about modules its own
    nodes import that are not installed (see `worldgen doctor`).

    With --ros humble|jazzy: the same robot over ROS 2 (DDS) as Gazebo's plugins (humble) or ros_gz_bridge
    (jazzy) publish it, on ROS_DOMAIN_ID.
    """
    from ..core.spawnpose import parse_spawn
    from ..bridge.outcome import parse_rate
    from ..ros1.simcmd import sim as run_sim
    from ..bridge.world import load_world

    pace = parse_rate(rate)
    loaded = load_world(world, spawn=parse_spawn(spawn) if spawn is not None else None, robot=robot,
                        launch=launch_file)
    if ros != "noetic":
        from ..ros2.simcmd import sim as run_sim2   # the ROS 2 extra (cyclonedds), only when asked for

        sys.exit(run_sim2(loaded, stack=ros, cmd_vel=cmd_vel, rate=pace, duration=duration, no_hit=lidar_no_hit))
    _warn_about_launch_nodes(world, launch_file)
    sys.exit(run_sim(loaded, rate=pace, duration=duration, no_hit=lidar_no_hit))


def _warn_about_launch_nodes(world: Path, launch_file: Path | None) -> None:
    """A launch file (WORLD or --launch): a warning on stderr per module its own nodes import that is not
    installed (sim starts no node, so it starts anyway)."""
    from ..check.validate import input_kind
    from ..ros1.transport import launch_warnings

    launch = launch_file if launch_file is not None else world if input_kind(world) == "launch" else None
    if launch is not None:
        for line in launch_warnings(launch):
            click.echo(line, err=True)


COMMANDS = [sim]
