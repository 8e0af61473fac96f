"""Nothing a run starts outlives it, and what a node prints is kept bounded (issue 25): a node's daemons (double
fork, setsid, SIGTERM ignored, even the environment cleared) are ended when the run ends and the report says so;
when `worldgen run` itself is killed with SIGKILL, its keeper ends every process of the run, a node ignoring SIGTERM
too; a node printing hundreds of megabytes leaves worldgen with its first lines and its last megabyte; a command
run in-process leaves the signal handlers as it found them.

Real processes throughout: worldgen's keeper, Debian's rosmaster and rospy for the runs (skipped without them).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from conftest import CliRunner

from bridgetools import NODES, REPO, ROOM, leftovers, no_leftovers, tag  # noqa: F401 (a fixture)
from rosstubs import SYSTEM_PYTHON, free_port
from worldgen.bridge.logtail import HEAD, TAIL, read_kept, trim
from worldgen.cli import main

DAEMON = r"""
import os, signal, sys, time
if os.fork() == 0:
    os.setsid()
    if os.fork():
        os._exit(0)
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, signal.SIG_IGN)
    open(sys.argv[1], "w").write(str(os.getpid()))
    while True:
        time.sleep(1)
time.sleep(600)
"""


def alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def wait_gone(pids, wait: float = 10.0) -> list[int]:
    """The pids still running after waiting up to ``wait`` s for them to go."""
    deadline = time.monotonic() + wait
    while any(alive(p) for p in pids) and time.monotonic() < deadline:
        time.sleep(0.1)
    return [p for p in pids if alive(p)]


def wait_for(predicate, wait: float = 60.0, what: str = "") -> None:
    deadline = time.monotonic() + wait
    while not predicate():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.1)


def test_a_supervisor_ends_a_daemon_ignoring_sigterm_and_names_its_owner(tmp_path):
    """The supervisor alone, no ROS: a child's grandchild in a session of its own, ignoring every stop signal, is
    ended by stop_all and recorded as that child's leftover; the signal handlers are back as they were."""
    from worldgen.bridge.supervise import Supervisor

    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    pid_file = tmp_path / "daemon.pid"
    with Supervisor() as supervisor:
        child = supervisor.start("node", [sys.executable, "-c", DAEMON, str(pid_file)], dict(os.environ),
                                 log=tmp_path / "node.log")
        wait_for(lambda: pid_file.is_file() and pid_file.read_text(), 20, "the daemon")
        daemon = int(pid_file.read_text())
        assert alive(daemon) and child.running
        supervisor.stop_all()
        assert not alive(daemon) and not child.running
        assert [(p.owner, p.pid) for p in supervisor.left] == [("node", daemon)]
    assert {s: signal.getsignal(s) for s in before} == before


KILLED_OWNER = r"""
import os, sys
sys.path.insert(0, sys.argv[1])
from worldgen.bridge.supervise import Supervisor
supervisor = Supervisor().__enter__()
supervisor.start("node", [sys.executable, "-c", sys.argv[2], sys.argv[3]], dict(os.environ))
print("started", flush=True)
import time
time.sleep(600)
"""


def test_a_supervisor_killed_with_sigkill_leaves_nothing(tmp_path):
    """SIGKILL of the process holding a supervisor: its keeper sees it go and ends the child and the daemon (which
    ignores SIGTERM and left the child's session) within seconds."""
    pid_file = tmp_path / "daemon.pid"
    owner = subprocess.Popen([sys.executable, "-c", KILLED_OWNER, str(REPO), DAEMON, str(pid_file)],
                             stdout=subprocess.PIPE, text=True)
    try:
        assert owner.stdout.readline().strip() == "started"
        wait_for(lambda: pid_file.is_file() and pid_file.read_text(), 20, "the daemon")
        daemon = int(pid_file.read_text())
        keeper = [int(p.name) for p in Path("/proc").iterdir() if p.name.isdigit() and
                  b"worldgen.bridge.keeper" in _read(p / "cmdline") and f"PPid:\t{owner.pid}\n" in
                  _read(p / "status").decode()]
        assert alive(daemon) and len(keeper) == 1
    finally:
        owner.kill()
        owner.wait()
    assert wait_gone([daemon, *keeper]) == []


def _read(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except OSError:
        return b""


def test_a_kept_log_is_its_first_lines_and_its_last_megabyte(tmp_path):
    """A 40 MB log is read back as at most HEAD + TAIL bytes (whole lines, one line saying what was left out), and
    trimming frees its middle on disk while its length and its ends stay."""
    log = tmp_path / "node.log"
    with open(log, "wb") as handle:
        handle.write(b"FIRST\n")
        for i in range(400_000):
            handle.write(b"%099d\n" % i)
        handle.write(b"LAST\n")
    size = log.stat().st_size
    kept = read_kept(log)
    assert kept.written == size and kept.cut > size - HEAD - TAIL
    assert len(kept.text.encode()) <= HEAD + TAIL + 200
    first, marker, *rest = kept.text.split("\n", 2)
    assert first == "FIRST" and kept.text.endswith("\nLAST\n")
    assert "left out here" in kept.text and "MB" in kept.text
    with open(log, "r+b") as handle:
        done = trim(handle.fileno(), 0)
    if done < 0:
        pytest.skip("this file system cannot punch holes")
    assert log.stat().st_size == size and log.stat().st_blocks * 512 < HEAD + TAIL + 2 * 1024 * 1024
    assert read_kept(log).text == kept.text


def test_a_daemonising_node_leaves_nothing_and_the_report_says_so(tag, tmp_path):
    """Two daemons of a node — one ignoring SIGTERM, one with its environment cleared — are ended with the run;
    the report names the node, both pids, and says they were ended."""
    pid_file = tmp_path / "pids"
    result = CliRunner().invoke(main, ["run", str(ROOM), str(NODES / "daemonising.py"), f"pids:={pid_file}",
                                       "--rate", "max", "--duration", "2", "--format", "json"])
    assert "Traceback" not in result.output, result.output
    daemons = [int(p) for p in pid_file.read_text().split()]
    assert len(daemons) == 2 and wait_gone(daemons, 0.5) == []
    messages = [f["message"] for f in json.loads(result.stdout)["findings"] if f["severity"] == "warning"]
    left = [m for m in messages if " left " in m]
    assert len(left) == 1, messages
    assert left[0].startswith("node daemonising left 2 processes running after the run")
    assert all(f"pid {p}:" in left[0] for p in daemons) and left[0].endswith("worldgen ended them")


@pytest.mark.parametrize("node, args", [("ignores_sigterm.py", []), ("daemonising.py", ["pids:={tmp}/pids"])])
def test_a_run_killed_with_sigkill_leaves_nothing(tag, tmp_path, node, args):
    """`kill -9` of `worldgen run` while its node runs: the master, the simulator, a node ignoring SIGTERM, a node's
    daemons — all gone within seconds (the ``tag`` fixture checks every process marked with the run's tag), and the
    run's temporary folder with them."""
    temp = tmp_path / "temp"
    temp.mkdir()
    env = dict(os.environ, PYTHONPATH=str(REPO), TMPDIR=str(temp))
    argv = [sys.executable, "-m", "worldgen", "run", str(ROOM), str(NODES / node),
            *[a.format(tmp=tmp_path) for a in args], "--duration", "60"]
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for(lambda: any(p.split(" ", 1)[1].startswith(f"{SYSTEM_PYTHON} ") and node in p for p in leftovers(tag))
             or proc.poll() is not None, 60, "the node")
    assert proc.poll() is None, "worldgen run ended before its node ran"
    time.sleep(1.0)   # the node up and, for the daemons, detached
    running = " ".join(leftovers(tag))
    assert "rosmaster" in running and "-m worldgen.ros1 " in running and "worldgen.bridge.keeper" in running
    daemons = [int(p) for p in (tmp_path / "pids").read_text().split()] if args else []
    assert all(alive(p) for p in daemons)
    assert [p.name for p in temp.glob("worldgen_run_*")]
    proc.kill()
    assert proc.wait() == -signal.SIGKILL
    no_leftovers(tag, wait=10)
    assert wait_gone(daemons, 1.0) == []   # the one with its environment cleared too
    wait_for(lambda: not list(temp.glob("worldgen_run_*")), 10, "the run's folder removed")


def test_a_node_printing_hundreds_of_megabytes_is_kept_bounded(tag):
    """A node printing 200 MB: worldgen keeps its first lines and its last megabyte (the run's log of it is at most
    HEAD + TAIL bytes and one line), and the report says the output was cut."""
    from worldgen.bridge.outcome import RunOptions
    from worldgen.bridge.world import load_world
    from worldgen.ros1.transport import ROS1

    nodes = ROS1.resolve_nodes([str(NODES / "prints_a_lot.py"), "mb:=200"], ROS1.node_python())
    outcome = ROS1.run_nodes(load_world(ROOM), nodes, RunOptions(duration=1.0, rate=0.0))
    log = outcome.logs[nodes[0].name]
    assert len(log.encode()) <= HEAD + TAIL + 200
    assert log.startswith("FIRST LINE\n") and "left out here" in log and "LAST LINE\n" in log
    cut = [f.message for f in outcome.findings if "printed" in f.message]
    assert cut == [f"node {nodes[0].name} printed 200 MB: worldgen kept its first lines and its last 1.0 MB"]


def test_a_command_run_in_process_can_still_be_stopped_after(tag, monkeypatch):
    """`worldgen sim` run in this process and stopped with Ctrl-C (which it ignores while stopping): afterwards
    SIGINT, SIGTERM and SIGHUP have the handlers they had, and Ctrl-C stops this process again."""
    monkeypatch.setenv("ROS_MASTER_URI", f"http://127.0.0.1:{free_port()}")
    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}

    def interrupt():
        wait_for(lambda: any("-m worldgen.ros1 " in p for p in leftovers(tag)), 60, "the simulator")
        time.sleep(2.0)   # its loop reached
        os.kill(os.getpid(), signal.SIGINT)

    thread = threading.Thread(target=interrupt, daemon=True)
    thread.start()
    result = CliRunner().invoke(main, ["sim", str(ROOM), "--duration", "120"])
    thread.join(timeout=10)
    assert result.exit_code == 0 and "stopping" in result.output, result.output
    assert {s: signal.getsignal(s) for s in before} == before
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(5)


@pytest.fixture
def ros2_tag(monkeypatch) -> str:
    """ROS 2's peer (rclpy) and the ``tag`` marker, for a ROS 2 run (skipped without the ros2 extra or rclpy)."""
    import uuid

    pytest.importorskip("cyclonedds", reason="the ros2 extra (cyclonedds) is not installed for this Python")
    from worldgen.ros2.pyenv import ENV_PYTHON, PEER_VENV

    python = os.environ.get(ENV_PYTHON) or str(PEER_VENV / "bin" / "python")
    if subprocess.run([python, "-c", "import rclpy"], capture_output=True).returncode != 0:
        pytest.skip(f"no rclpy at {python}")
    monkeypatch.setenv(ENV_PYTHON, python)
    value = uuid.uuid4().hex
    monkeypatch.setenv("WORLDGEN_TEST_TAG", value)
    yield f"WORLDGEN_TEST_TAG={value}"
    no_leftovers(f"WORLDGEN_TEST_TAG={value}")


ROS2_NODES = Path(__file__).resolve().parent / "ros2nodes"


def test_a_daemonising_rclpy_node_leaves_nothing(ros2_tag, tmp_path):
    """ROS 2 runs go through the same keeper: the daemon is ended with the run and the report says so; and a
    second run killed with SIGKILL leaves nothing either."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    pids = tmp_path / "pids"
    argv = [sys.executable, "-m", "worldgen", "run", str(ROOM), str(ROS2_NODES / "daemonising.py"), f"_pids:={pids}",
            "--ros", "humble"]
    done = subprocess.run([*argv, "--rate", "max", "--duration", "2", "--format", "json"], env=env,
                          capture_output=True, text=True, timeout=180)
    daemon = int(pids.read_text())
    assert wait_gone([daemon], 0.5) == []
    left = [f["message"] for f in json.loads(done.stdout)["findings"] if " left " in f["message"]]
    assert len(left) == 1 and left[0].startswith("node daemonising left 1 process running") and \
        f"pid {daemon}:" in left[0], done.stdout

    pids.unlink()
    proc = subprocess.Popen([*argv, "--duration", "60"], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    wait_for(lambda: pids.is_file() and pids.read_text() or proc.poll() is not None, 60, "the daemon")
    assert proc.poll() is None
    daemon = int(pids.read_text())
    time.sleep(1.0)
    proc.kill()
    proc.wait()
    no_leftovers(ros2_tag, wait=10)
    assert wait_gone([daemon], 1.0) == []
