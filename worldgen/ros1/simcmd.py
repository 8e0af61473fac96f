"""``worldgen sim`` as a library: join the master at ``ROS_MASTER_URI`` (or start one when none answers), set the
parameters the launch file sets (as roslaunch would), run the simulator node until Ctrl-C or the duration, and
stop whatever was started."""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable

from .master import checked_master_uri, is_this_machine, master_answers, running_node, set_param, start_master
from .gazebo_types import gazebo_msgs_path
from .ready import SIMULATOR
from ..bridge.supervise import Supervisor
from ..bridge.world import World, write_config
from ..core.errors import InputError

DEFAULT_URI = "http://localhost:11311"
TOPICS = ("/clock /scan /odom /tf /tf_static /joint_states /imu /gazebo/model_states; subscribes /cmd_vel; "
          "Gazebo's services (/gazebo/get_model_state, spawn_sdf_model, reset_world …)")


def sim(world: World, *, rate: float, duration: float | None, no_hit: str,
        say: Callable[[str], None] = lambda text: print(text, file=sys.stderr, flush=True)) -> int:
    """Run the simulator node on ``world`` (see the module docstring); returns its exit code (0 after Ctrl-C)."""
    from .rosenv import import_rospy

    import_rospy()   # InputError naming the package when rospy is missing
    cameras = check_cameras(world)   # InputError naming the packages when a camera cannot be drawn
    uri = os.environ.get("ROS_MASTER_URI") or DEFAULT_URI
    with tempfile.TemporaryDirectory(prefix="worldgen_sim_") as tmp, Supervisor() as supervisor:
        supervisor.remove_at_end(tmp)   # even when worldgen is killed
        try:
            return _serve(world, supervisor, Path(tmp), uri, cameras, say,
                          {"rate": rate, "duration": duration, "no_hit": no_hit})
        except KeyboardInterrupt:   # Ctrl-C, SIGTERM or SIGHUP at any moment once started: a stop asked for
            import signal

            signal.signal(signal.SIGINT, signal.SIG_IGN)   # a second Ctrl-C must not cut the stopping short
            say("worldgen sim: stopping")
            return 0


def _serve(world: World, supervisor: Supervisor, tmp: Path, uri: str, cameras: list, say: Callable[[str], None],
           settings: dict) -> int:
    """The master (joined or started), the launch file's parameters and the simulator node (``settings``: its
    ``rate``, ``duration`` and ``no_hit``), until the node ends (its exit code); a stop asked for interrupts it
    anywhere (KeyboardInterrupt: :func:`sim` says so, exit 0)."""
    env = dict(os.environ)
    uri, host, port = checked_master_uri(uri)
    if master_answers(uri):
        pid = running_node(uri, SIMULATOR)
        if pid is not None:   # a second /gazebo would make the master shut the first down, and its master
            raise InputError(f"a simulator ({SIMULATOR}, pid {pid}) already runs on the ROS master at {uri}",
                             hint="stop it (Ctrl-C where it runs) before starting another, or set ROS_MASTER_URI "
                                  "to another port for a second one")
        say(f"worldgen sim: joined the ROS master at {uri}")
    elif not is_this_machine(host):
        raise InputError(f"no ROS master answers at {uri} (ROS_MASTER_URI), and {host} is not this machine (or "
                         "cannot be found), so worldgen cannot start one there",
                         hint=f"start roscore on {host}, or unset ROS_MASTER_URI for a master here")
    else:
        _, uri = start_master(supervisor, port, env)
        say(f"worldgen sim: started a ROS master at {uri} (stopped on exit)")
    env["ROS_MASTER_URI"] = uri
    for name, value in world.params.items():   # what roslaunch of the launch file would set
        set_param(uri, name, value)
    if world.params:
        say(f"worldgen sim: set the launch file's {len(world.params)} parameter(s) ({', '.join(world.params)})")
    generated = gazebo_msgs_path()
    if generated is not None:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (generated, env.get("PYTHONPATH")) if p)
        say(f"worldgen sim: this system has no gazebo_msgs; for nodes that import it: "
            f"export PYTHONPATH={generated}:$PYTHONPATH")
    config = write_config(tmp, world, **settings, trace=None, set_sim_time=True)
    rate = settings["rate"]
    root = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
    child = supervisor.start("simulator", [sys.executable, "-m", "worldgen.ros1", str(config)], env,
                             show_errors=True)
    x, y, yaw = world.spawn
    robots = [f"{r['ns']}: {r['robot']} at ({r['spawn'][0]:g}, {r['spawn'][1]:g}, {r['spawn'][2]:g})"
              for r in world.robots] or [f"{world.robot} at ({x:g}, {y:g}, {yaw:g})"]
    say(f"worldgen sim: {'; '.join(robots)} in {world.path}, "
        f"{'as fast as it goes' if rate <= 0 else f'{rate:g}x real time'}; publishing {TOPICS}"
        f"{'; ' + ' '.join(cameras) + ' while subscribed' if cameras else ''}"
        f"{' in each namespace' if world.robots else ''}. Ctrl-C stops.")
    while child.running:
        time.sleep(0.1)
    code = child.proc.returncode
    if code not in (0, None) and code > 0:
        return code
    return 0


def check_cameras(world: World) -> list[str]:
    """The camera topics of the world's first robot (as in the global namespace), after making sure that an
    OpenGL context can be made when any robot has a camera: InputError naming the packages to install, before
    anything starts."""
    from ..robots import robot_urdf
    from ..robots.cameras import camera_topic
    from ..robots.profile import robot_profile

    entries = world.robots or [{"robot": world.robot, "mappings": None}]
    profiles = [robot_profile(robot_urdf(e["robot"], e.get("mappings"))) for e in entries]
    if not any(p.cameras for p in profiles):
        return []
    from ..sim.camera import open_context

    open_context().release()
    return [topic for c in profiles[0].cameras for topic in
            (camera_topic("/", c.camera_name, c.image_topic), camera_topic("/", c.camera_name, c.info_topic),
             camera_topic("/", c.camera_name, c.image_topic) + "/compressed")]
