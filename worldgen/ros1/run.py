"""One ``worldgen run``: a private master on a free port, the simulator node, the students' nodes, the
duration, then everything stopped and what the robot did measured (and judged, with a task).

Order: the master; ``/use_sim_time`` and the launch files' parameters set (what ``roslaunch`` would set, so
``rosparam get`` and the nodes' ``~`` parameters see them); the simulator node, paused at time 0; the nodes, each
with its launch file's environment; once every node is up
(registered with the master, or already exited) the simulator is unpaused, as Gazebo started paused and then
unpaused would be; the run ends after ``duration`` simulated seconds, or when a node the launch file marks
``required`` exits (roslaunch then stops everything). Every process is in a group of its own,
stopped on any exit (see :mod:`.supervise`); nodes' output goes to files, whose last line a finding quotes when a
node crashes.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

from ..bridge.outcome import (NodeSpec, Outcome, RunOptions, check_simulator, finish_run, launch_params,
                               outcome_of)
from ..bridge.supervise import Child, Supervisor
from ..bridge.world import World, write_config
from ..core.errors import WorldgenError
from .gazebo_types import gazebo_msgs_path
from .master import node_names, ros_env, set_param, start_master
from .rosenv import import_rospy

START_PARAM = "/worldgen/start"
UP_TIMEOUT = 15.0      # s of real time for the nodes to register
SETTLE = 0.3           # s after that for their topics to connect
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


def run_nodes(world: World, nodes: list[NodeSpec], options: RunOptions, base_env: dict[str, str] | None = None
              ) -> Outcome:
    """Run ``nodes`` on the simulated robot in ``world`` (see the module docstring). Raises WorldgenError when the
    simulation itself cannot run (rospy missing, the world or robot cannot be loaded); a node's failure is a
    finding."""
    import_rospy()
    with tempfile.TemporaryDirectory(prefix="worldgen_run_") as tmp_name, Supervisor() as supervisor:
        tmp = Path(tmp_name)
        _, uri = start_master(supervisor, None, dict(base_env or os.environ), log=tmp / "master.log")
        env = with_gazebo_msgs(ros_env(base_env, uri, tmp / "ros_home"))
        set_param(uri, "/use_sim_time", True)
        for name, value in dict(world.params, **launch_params(nodes)).items():
            set_param(uri, name, value)
        trace_file = tmp / "trace.json"
        config = write_config(tmp, world, rate=options.rate, duration=options.duration, no_hit=options.no_hit,
                              trace=str(trace_file), bag=str(options.bag) if options.bag else None,
                              start_param=START_PARAM, person=options.person, set_sim_time=False,
                              graded=options.robot_ns, record_scans=options.record_scans)
        simulator = supervisor.start("simulator", [sys.executable, "-m", "worldgen.ros1", str(config)],
                                     _bridge_env(env), log=tmp / "simulator.log")
        _wait_for_simulator(simulator, uri)
        children = [supervisor.start(n.name, n.argv, dict(env, **n.env), log=tmp / f"node_{i}.log")
                    for i, n in enumerate(nodes)]
        _wait_for_nodes(children, uri)
        set_param(uri, "/worldgen/pids", [c.proc.pid for c in children])
        set_param(uri, START_PARAM, True)
        trace, alive, ended_by = finish_run(simulator, children, nodes, options, supervisor, trace_file)
        return outcome_of(trace, nodes, children, alive, ended_by, options, left=supervisor.left)


def _wait_for_simulator(simulator: Child, uri: str) -> None:
    deadline = time.monotonic() + SIM_START_TIMEOUT
    while "/gazebo" not in node_names(uri):
        check_simulator(simulator)
        if time.monotonic() > deadline:
            raise WorldgenError(f"the simulator did not come up within {SIM_START_TIMEOUT:g} s")
        time.sleep(0.05)


def _wait_for_nodes(children: list[Child], uri: str) -> None:
    """Until as many nodes as processes have registered (besides the simulator and rosout), or every process
    that has not has exited, or :data:`UP_TIMEOUT`; then :data:`SETTLE` for their topics to connect."""
    deadline = time.monotonic() + UP_TIMEOUT
    while time.monotonic() < deadline:
        others = node_names(uri) - {"/gazebo", "/rosout"}
        if len(others) >= sum(c.running for c in children):
            break
        time.sleep(0.05)
    time.sleep(SETTLE)



