"""``worldgen sim WORLD --ros humble|jazzy`` as a library: the simulator on the ROS 2 domain of the environment
(``ROS_DOMAIN_ID``, default 0) with discovery as the environment sets it (``ROS_LOCALHOST_ONLY``,
``ROS_AUTOMATIC_DISCOVERY_RANGE``, ``ROS_STATIC_PEERS``), until Ctrl-C or the duration."""

from __future__ import annotations

import os
import signal
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable

from ..bridge.supervise import Supervisor
from ..bridge.world import World, write_config
from ..core.errors import InputError
from ..interface.topics import topics
from .participant import Discovery
from .pyenv import require_cyclonedds


def domain_id(env=None) -> int:
    """``ROS_DOMAIN_ID`` as rcl reads it (unset: 0); InputError for anything else than 0-232."""
    text = (os.environ if env is None else env).get("ROS_DOMAIN_ID", "").strip() or "0"
    if not text.isdigit() or int(text) > 232:
        raise InputError(f"ROS_DOMAIN_ID={text!r} is not a ROS 2 domain", hint="set it to a number from 0 to 101")
    return int(text)


def sim(world: World, *, stack: str, cmd_vel: str | None, rate: float, duration: float | None, no_hit: str,
        say: Callable[[str], None] = lambda text: print(text, file=sys.stderr, flush=True)) -> int:
    """Run the ROS 2 simulator on ``world`` (see the module docstring); its exit code (0 after Ctrl-C)."""
    require_cyclonedds()
    domain = domain_id()
    discovery = Discovery.from_env()
    if discovery.range == "off":
        say("worldgen sim: warning: ROS_AUTOMATIC_DISCOVERY_RANGE=OFF: nodes in this shell reach no other "
            "process, the simulator included; unset it or set LOCALHOST")
    with tempfile.TemporaryDirectory(prefix="worldgen_sim2_") as tmp, Supervisor() as supervisor:
        supervisor.remove_at_end(tmp)   # even when worldgen is killed
        try:   # a stop asked for (Ctrl-C, SIGTERM, SIGHUP) at any moment once started: exit 0
            config = write_config(Path(tmp), world, rate=rate, duration=duration, no_hit=no_hit, trace=None,
                                  stack=stack, domain=domain, cmd_vel=cmd_vel, start_file=None, expect=0,
                                  discovery={"range": discovery.range, "peers": list(discovery.static_peers)})
            root = str(Path(__file__).resolve().parents[2])
            env = dict(os.environ,
                       PYTHONPATH=os.pathsep.join(p for p in (root, os.environ.get("PYTHONPATH")) if p))
            child = supervisor.start("simulator", [sys.executable, "-m", "worldgen.ros2", str(config)], env,
                                     show_errors=True)
            table = topics(stack)
            names = " ".join(t.full_name() for t in table.values() if t.direction == "out")
            x, y, yaw = world.spawn
            pace = "as fast as it goes" if rate <= 0 else f"{rate:g}x real time"
            say(f"worldgen sim: {world.robot} at ({x:g}, {y:g}, {yaw:g}) in {world.path} as ROS 2 {stack} on "
                f"ROS_DOMAIN_ID={domain}, {pace}; publishing {names}; subscribes /cmd_vel "
                f"({table['cmd_vel'].type}). Ctrl-C stops.")
            say(f"worldgen sim: in another shell with ROS 2 {stack}: ROS_DOMAIN_ID={domain} ros2 topic list, or "
                f"python3 your_node.py --ros-args -p use_sim_time:=true")
            while child.running:
                time.sleep(0.1)
        except KeyboardInterrupt:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            say("worldgen sim: stopping")
            return 0
        code = child.proc.returncode
        return code if code not in (0, None) and code > 0 else 0
