"""One ``worldgen run --ros humble|jazzy``: a private DDS domain on loopback, the simulator (:mod:`.node`), the
students' rclpy nodes, the duration, then everything stopped and what the robot did measured.

Order: a domain id no other run of this machine holds (a lock file per id, so ``-j`` runs and other users' runs
never cross); the simulator and the nodes started together (the nodes with ``ROS_DOMAIN_ID`` and discovery kept on
localhost, as the simulator's participant is); simulated time held at 0 until every node's participant has come and
its endpoints match the robot's as the task needs (see :func:`.node.wait_for_start`; or a node has exited, or 15 s
have passed), as Gazebo started paused and then unpaused would be; the run ends after ``duration`` simulated
seconds. Every process is in a group of its own, stopped on any exit, and ended at once when the simulator has
written its result (:mod:`worldgen.bridge.supervise`, :func:`worldgen.bridge.outcome.finish_run`)."""

from __future__ import annotations

import fcntl
import json
import os
import sys
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

from ..bridge.outcome import NodeSpec, Outcome, RunOptions, check_simulator, finish_run, outcome_of
from ..bridge.supervise import Child, Supervisor, check_stopping
from ..bridge.world import World, write_config
from ..core.errors import WorldgenError

DOMAINS = range(42, 102)   # 0-101 are safe on every machine; below 42 are the ones people pick by hand
LOCKS = Path(tempfile.gettempdir()) / "worldgen-dds"
UP_TIMEOUT = 15.0          # s of real time for the nodes to come
SIM_START_TIMEOUT = 30.0


@contextmanager
def private_domain():
    """A ROS domain id held by this run alone (an exclusive lock on its file) until the block ends."""
    LOCKS.mkdir(mode=0o1777, exist_ok=True)
    start = os.getpid() % len(DOMAINS)
    for k in range(len(DOMAINS)):
        domain = DOMAINS[(start + k) % len(DOMAINS)]
        handle = open(LOCKS / f"domain-{domain}.lock", "a+")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        try:
            yield domain
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
            handle.close()
        return
    raise WorldgenError(f"every private DDS domain ({DOMAINS.start}-{DOMAINS.stop - 1}) is in use by other runs",
                        hint="run fewer at once (-j)")


def node_env(base: dict[str, str], stack: str, domain: int) -> dict[str, str]:
    """A node's environment: the run's domain, discovery on localhost only (Humble's and Jazzy's spelling)."""
    env = {k: v for k, v in base.items() if k not in ("ROS_LOCALHOST_ONLY", "ROS_AUTOMATIC_DISCOVERY_RANGE",
                                                       "ROS_STATIC_PEERS")}
    env["ROS_DOMAIN_ID"] = str(domain)
    if stack == "humble":
        env["ROS_LOCALHOST_ONLY"] = "1"
    else:
        env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env.setdefault("PYTHONUNBUFFERED", "1")
    return env


def _simulator_env(env: dict[str, str]) -> dict[str, str]:
    root = str(Path(__file__).resolve().parents[2])
    parts = [root] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p and p != root]
    return dict(env, PYTHONPATH=os.pathsep.join(parts))


def run_nodes(world: World, nodes: list[NodeSpec], options: RunOptions, stack: str, cmd_vel: str | None = None,
              base_env: dict[str, str] | None = None) -> Outcome:
    """Run ``nodes`` on the simulated robot in ``world`` on ``stack`` (see the module docstring)."""
    base = dict(base_env or os.environ)
    with tempfile.TemporaryDirectory(prefix="worldgen_run2_") as tmp_name, Supervisor() as supervisor, \
            private_domain() as domain:
        tmp = Path(tmp_name)
        supervisor.remove_at_end(tmp)   # even when worldgen is killed
        env = node_env(base, stack, domain)
        trace_file, start_file = tmp / "trace.json", tmp / "start"
        config = write_config(tmp, world, rate=options.rate, duration=options.duration, no_hit=options.no_hit,
                              trace=str(trace_file), start_file=str(start_file), person=options.person,
                              graded=options.robot_ns, record_scans=options.record_scans, stack=stack, domain=domain,
                              discovery={"range": "localhost", "peers": []}, expect=len(nodes), cmd_vel=cmd_vel,
                              pids_file=str(tmp / "pids.json"), task=options.task)
        simulator = supervisor.start("simulator", [sys.executable, "-m", "worldgen.ros2", str(config)],
                                     _simulator_env(env), log=tmp / "simulator.log")
        children = [supervisor.start(n.name, n.argv, dict(env, **n.env), log=tmp / f"node_{i}.log")
                    for i, n in enumerate(nodes)]
        (tmp / "pids.json").write_text(json.dumps([c.proc.pid for c in children]), encoding="utf-8")
        _wait_for_start(simulator, children, start_file)
        trace, alive, ended_by = finish_run(simulator, children, nodes, options, supervisor, trace_file)
        cmd_type = "geometry_msgs/msg/TwistStamped" if stack == "jazzy" and cmd_vel != "twist" else \
            "geometry_msgs/msg/Twist"
        return outcome_of(trace, nodes, children, alive, ended_by, options, cmd_type, left=supervisor.left)


def _wait_for_start(simulator: Child, children: list[Child], start_file: Path) -> None:
    """Until the simulator runs (it starts when the nodes have come); a node that exits first, or
    :data:`UP_TIMEOUT`, starts it anyway (by the start file)."""
    started = time.monotonic()
    while not simulator.says("worldgen-sim: running"):
        check_simulator(simulator)
        waited = time.monotonic() - started
        if waited > SIM_START_TIMEOUT:
            raise WorldgenError(f"the simulator did not come up within {SIM_START_TIMEOUT:g} s")
        if waited > UP_TIMEOUT or any(not c.running for c in children):
            start_file.touch()
        check_stopping()
        time.sleep(0.01)
