"""One ``worldgen run``: a private master on a free port, the simulator node, the students' nodes, the
duration, then everything stopped and what the robot did measured (and judged, with a task).

Order: the master and the simulator node start together (the simulator loads its world while the master comes
up, and joins it once ``/use_sim_time`` and the launch files' parameters are set — what ``roslaunch`` would set,
so ``rosparam get`` and the nodes' ``~`` parameters see them — which :data:`UP_PARAM` says, holding this run's own
token); the simulator registers, paused at time 0; the nodes start, each with its launch file's environment; once
every node is ready (:mod:`.ready`: joined the master, its links with the simulator made, doing what the task
needs — or exited) the simulator is unpaused, as Gazebo started paused and then unpaused would be; the run ends
after ``duration`` simulated seconds, or when a node the launch file marks ``required`` exits (roslaunch then stops
everything). Every process is in a group of its own, stopped on any exit (see :mod:`worldgen.bridge.supervise`),
and ended at once when the simulator has written its result (:func:`worldgen.bridge.outcome.finish_run`); nodes'
output goes to files, whose last line a finding quotes when a node crashes.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator

from ..bridge.outcome import (NodeSpec, Outcome, RunOptions, check_simulator, finish_run, launch_params,
                               outcome_of)
from ..bridge.supervise import Child, Supervisor, check_stopping
from ..bridge.world import World, write_config
from ..core.errors import WorldgenError
from .gazebo_types import gazebo_msgs_path
from .master import await_master, launch_master, ros_env, set_param
from .ready import Readiness, wait_until_ready
from .rosenv import find_rospy

UP_PARAM = "/worldgen/up"   # the parameters are set: the simulator may join (its value: the run's token)
UP_TIMEOUT = 15.0      # s of real time for the nodes to be ready
SIM_START_TIMEOUT = 30.0


def with_gazebo_msgs(env: dict[str, str]) -> dict[str, str]:
    """``env`` with worldgen's generated gazebo_msgs on ``PYTHONPATH`` when the system has none (the simulator
    and the students' nodes both import it; see :mod:`.gazebo_types`)."""
    folder = gazebo_msgs_path()
    if folder is None:
        return env
    parts = [folder] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p and p != folder]
    return dict(env, PYTHONPATH=os.pathsep.join(parts))


def _bridge_env(env: dict[str, str]) -> dict[str, str]:
    root = str(Path(__file__).resolve().parents[2])
    parts = [root] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p and p != root]
    return dict(env, PYTHONPATH=os.pathsep.join(parts))


@dataclass
class HeadStart:
    """What a run starts before it knows its world and nodes (:func:`head_start`): its folder and supervisor, the
    master (started, maybe not answering yet) and the simulator's process (importing, then waiting for ``config``,
    which the run writes whole). ``used`` once a run has taken it."""

    tmp: Path
    supervisor: Supervisor
    master: Child
    uri: str
    env: dict
    simulator: Child
    config: Path
    used: bool = False


@contextmanager
def head_start(base_env: dict[str, str] | None = None, strict: bool = False) -> Iterator[HeadStart | None]:
    """A run's master and simulator started while the command still reads the world and checks the nodes (their
    Python starts and imports take longer than that). When they cannot start (rospy or rosmaster missing), the
    error, with ``strict``; else None, and :func:`run_nodes` says so in its turn. Ended at the block's end: at
    once when no run took them."""
    with tempfile.TemporaryDirectory(prefix="worldgen_run_") as tmp_name, Supervisor() as supervisor:
        tmp = Path(tmp_name)
        supervisor.remove_at_end(tmp)   # even when worldgen is killed
        try:
            find_rospy()
            master, uri = launch_master(supervisor, None, dict(base_env or os.environ), log=tmp / "master.log")
            env = with_gazebo_msgs(ros_env(base_env, uri, tmp / "ros_home"))
            config = tmp / "sim.json"
            simulator = supervisor.start("simulator", [sys.executable, "-m", "worldgen.ros1", str(config)],
                                         _bridge_env(env), log=tmp / "simulator.log")
        except (WorldgenError, OSError):
            if strict:
                raise
            supervisor.end_all()
            yield None
            return
        head = HeadStart(tmp, supervisor, master, uri, env, simulator, config)
        try:
            yield head
        finally:
            if not head.used:   # no run began (an error, a run refused): nothing to stop in order
                supervisor.end_all()


def run_nodes(world: World, nodes: list[NodeSpec], options: RunOptions, base_env: dict[str, str] | None = None,
              head: HeadStart | None = None) -> Outcome:
    """Run ``nodes`` on the simulated robot in ``world`` (see the module docstring), in ``head`` (see
    :func:`head_start`) or in a head start of its own. Raises WorldgenError when the simulation itself cannot run
    (rospy missing, the world or robot cannot be loaded); a node's failure is a finding."""
    if head is None:
        with head_start(base_env, strict=True) as own:
            return _run(world, nodes, options, own)
    return _run(world, nodes, options, head)


def _run(world: World, nodes: list[NodeSpec], options: RunOptions, head: HeadStart) -> Outcome:
    if head.used:
        raise AssertionError("a head start serves one run")
    head.used = True
    tmp, supervisor, simulator, uri = head.tmp, head.supervisor, head.simulator, head.uri
    trace_file = tmp / "trace.json"
    (tmp / "run").mkdir()
    config = write_config(tmp / "run", world, rate=options.rate, duration=options.duration, no_hit=options.no_hit,
                          trace=str(trace_file), bag=str(options.bag) if options.bag else None,
                          start_file=str(tmp / "start"), up_param=[UP_PARAM, str(tmp)], person=options.person,
                          set_sim_time=False, graded=options.robot_ns, record_scans=options.record_scans,
                          joined_file=str(tmp / "joined"))
    os.replace(config, head.config)   # whole, where the simulator waits for it
    await_master(supervisor, head.master, uri)
    set_param(uri, "/use_sim_time", True)
    for name, value in dict(world.params, **launch_params(nodes)).items():
        set_param(uri, name, value)
    set_param(uri, UP_PARAM, str(tmp))
    _wait_for_simulator(simulator, tmp / "joined")
    children = [supervisor.start(n.name, n.argv, dict(head.env, **n.env), log=tmp / f"node_{i}.log")
                for i, n in enumerate(nodes)]
    wait_until_ready(Readiness(uri, options.task), children, UP_TIMEOUT)
    set_param(uri, "/worldgen/pids", [c.proc.pid for c in children])
    (tmp / "start").touch()
    trace, alive, ended_by = finish_run(simulator, children, nodes, options, supervisor, trace_file)
    return outcome_of(trace, nodes, children, alive, ended_by, options, left=supervisor.left)


def _wait_for_simulator(simulator: Child, joined: Path) -> None:
    """Until the simulator has joined the master (it makes the file ``joined``)."""
    deadline = time.monotonic() + SIM_START_TIMEOUT
    while not joined.exists():
        check_simulator(simulator)
        if time.monotonic() > deadline:
            raise WorldgenError(f"the simulator did not come up within {SIM_START_TIMEOUT:g} s")
        check_stopping()
        time.sleep(0.01)
