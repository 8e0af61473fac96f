"""worldgen's DDS plumbing (``worldgen.ros2.participant``, ``.discovery``) against the real ROS 2: the rclpy of
PyPI's Jazzy wheels (Fast DDS) in a child process (``.ci/ros2-peer`` makes its venv; ``WORLDGEN_ROS2_PYTHON`` names
another). Each test holds a private ROS domain (the run's lock files), so parallel runs never cross, and ends every
child it started. Messages go both ways, rclpy's graph shows the nodes we announce with our endpoints' types, type
hashes and GIDs, and our graph shows the rclpy node and what it subscribes — under each discovery setting a
student's shell may hold."""

from __future__ import annotations

import json
import math
import os
import queue
import subprocess
import threading
import time
import uuid
from pathlib import Path

import pytest

from bridgetools import no_leftovers

pytest.importorskip("cyclonedds", reason="the ros2 extra (cyclonedds) is not installed for this Python")

from worldgen.interface.topics import DEFAULT, SENSOR_DATA, Qos  # noqa: E402
from worldgen.ros2 import msgs  # noqa: E402
from worldgen.ros2.discovery import Graph  # noqa: E402
from worldgen.ros2.participant import DdsError, Discovery, Participant, gid  # noqa: E402
from worldgen.ros2.run import private_domain  # noqa: E402
from worldgen.ros2.typehash import type_hash  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
SIDE = Path(__file__).resolve().parent / "ros2nodes" / "dds_side.py"
# The peer's discovery settings a student's shell may hold (Jazzy's two spellings of "this machine only").
SETTINGS = {"default": {}, "ROS_LOCALHOST_ONLY": {"ROS_LOCALHOST_ONLY": "1"},
            "RANGE_LOCALHOST": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}}
STRING, SCAN = "std_msgs/msg/String", "sensor_msgs/msg/LaserScan"


def peer_python() -> str:
    python = os.environ.get("WORLDGEN_ROS2_PYTHON") or str(REPO / ".venv-ros2" / "bin" / "python")
    ok = os.access(python, os.X_OK) and subprocess.run([python, "-c", "import rclpy"],
                                                       capture_output=True).returncode == 0
    if not ok:
        if os.environ.get("CI"):
            pytest.fail(f"no rclpy at {python}: .ci/run makes it with .ci/ros2-peer")
        pytest.skip(f"no rclpy at {python} (bash .ci/ros2-peer makes one)")
    return python


@pytest.fixture(scope="module")
def rclpy_python() -> str:
    return peer_python()


@pytest.fixture
def domain():
    with private_domain() as held:
        yield held


@pytest.fixture
def tag() -> str:
    """A marker in every child's environment, to find any left behind at the test's end."""
    marker = f"WORLDGEN_TEST_TAG={uuid.uuid4().hex}"
    yield marker
    no_leftovers(marker)


class Side:
    """The rclpy child (tests/ros2nodes/dds_side.py): its JSON lines read in a thread; ended at the block's end."""

    def __init__(self, python: str, args: list[str], domain: int, tag: str, setting: dict[str, str]) -> None:
        env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "RMW_", "_ROS_WHEELS"))}
        key, _, value = tag.partition("=")
        env.update(setting, ROS_DOMAIN_ID=str(domain), **{key: value})
        self.proc = subprocess.Popen([python, str(SIDE), *args], env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            self.lines.put(json.loads(line))
        self.lines.put(None)

    def report(self, step, timeout: float = 25.0) -> tuple[list[dict], dict]:
        """Call ``step()`` (our side's publishing) until the listener's graph line comes: (messages, graph)."""
        got, deadline = [], time.monotonic() + timeout
        while time.monotonic() < deadline:
            step()
            try:
                line = self.lines.get(timeout=0.05)
            except queue.Empty:
                continue
            if line is None:
                break
            if "graph" in line:
                return [m["msg"] for m in got], line["graph"]
            got.append(line)
        why = self.proc.stderr.read() if self.proc.poll() is not None else "still running"
        raise AssertionError(f"the rclpy side reported no graph: {why}")

    def __enter__(self) -> Side:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(5)


def until(predicate, step, timeout: float = 20.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        step()
        if predicate():
            return True
        time.sleep(0.05)
    return False


@pytest.mark.parametrize("setting", sorted(SETTINGS))
def test_our_string_reaches_rclpy_which_sees_our_nodes_types_and_hashes(setting, rclpy_python, domain, tag):
    with Participant(domain, Discovery("localhost")) as dp, \
            Side(rclpy_python, ["listen", "/chatter", "string", "--node", "/ros_gz_bridge",
                                "--node", "/robot_state_publisher"], domain, tag, SETTINGS[setting]) as side:
        writer = dp.writer("/chatter", msgs.TYPES[STRING], DEFAULT, type_hash(STRING))
        graph = Graph(dp)
        graph.add("/ros_gz_bridge", writers=[writer])
        graph.add("/robot_state_publisher")
        graph.publish()
        sent = iter(range(10**6))
        received, seen = side.report(lambda: (writer.write(msgs.TYPES[STRING](data=f"hello {next(sent)}")),
                                              time.sleep(0.05), graph.look()))
        assert len(received) == 3 and all(m["data"].startswith("hello ") for m in received)
        assert ["ros_gz_bridge", "/"] in seen["nodes"] and ["robot_state_publisher", "/"] in seen["nodes"]
        assert seen["publishers"] == [{"node": "ros_gz_bridge", "namespace": "/", "type": STRING,
                                       "hash": type_hash(STRING), "gid": gid(writer).hex()}]
        # and our side of the graph: the rclpy node, what it subscribes (the readiness check of a run); its
        # ros_discovery_info comes with Fast DDS's next heartbeat (3 s apart) to a reader that joins late
        assert until(lambda: graph.subscribers("/chatter") == ["/listener"], graph.look, timeout=10)
        assert "/listener" in graph.node_names()
        assert ("/chatter", STRING) in graph.topics_of("/listener")["subscriptions"]


@pytest.mark.parametrize("setting", sorted(SETTINGS))
def test_rclpy_string_reaches_our_reader_and_our_graph_names_its_node(setting, rclpy_python, domain, tag):
    with Participant(domain, Discovery("localhost")) as dp, \
            Side(rclpy_python, ["talk", "/chatter", "string"], domain, tag, SETTINGS[setting]):
        reader = dp.reader("/chatter", msgs.TYPES[STRING], DEFAULT, type_hash(STRING))
        graph = Graph(dp)
        graph.add("/gazebo", readers=[reader])
        graph.publish()
        got: list = []
        assert until(lambda: len(got) >= 3 and graph.publishers("/chatter") == ["/talker"],
                     lambda: (got.extend(s.data for s in reader.take(N=50)), graph.look()))
        assert all(text.startswith("from rclpy ") for text in got)
        assert ("/chatter", STRING) in graph.topics_of("/talker")["publications"]


def test_a_laserscan_goes_both_ways_byte_for_byte_with_gazebos_qos(rclpy_python, domain, tag):
    """Humble's ray sensor publishes SensorDataQoS().reliable(): a qos_profile_sensor_data (best effort) subscriber
    receives it; rclpy's scan (default QoS) reaches our best-effort reader. Values, inf included, are kept."""
    ranges = [math.inf if k % 7 == 0 else 0.5 + k / 100 for k in range(360)]
    scan = msgs.TYPES[SCAN](header=msgs.TYPES["std_msgs/msg/Header"](stamp=msgs.stamp(12.25), frame_id="base_scan"),
                            angle_min=0.0, angle_max=6.2657, angle_increment=0.0174533, range_min=0.12,
                            range_max=3.5, ranges=ranges, intensities=[float(k % 3) for k in range(360)])
    with Participant(domain, Discovery("localhost")) as dp:
        writer = dp.writer("/scan", msgs.TYPES[SCAN], Qos(reliable=True, depth=5), type_hash(SCAN))
        with Side(rclpy_python, ["listen", "/scan", "scan", "--best-effort", "--count", "2"], domain, tag, {}) as side:
            received, _ = side.report(lambda: (writer.write(scan), time.sleep(0.05)))
        assert len(received) == 2
        for msg in received:
            assert msg["ranges"] == ["inf" if math.isinf(r) else pytest.approx(r, abs=1e-6) for r in ranges]
            assert msg["stamp"] == [12, 250_000_000] and msg["frame_id"] == "base_scan"
            assert msg["intensities"] == [float(k % 3) for k in range(360)]

        reader = dp.reader("/scan_back", msgs.TYPES[SCAN], SENSOR_DATA, type_hash(SCAN))
        with Side(rclpy_python, ["talk", "/scan_back", "scan"], domain, tag, {}):
            got: list = []
            assert until(lambda: len(got) >= 2, lambda: got.extend(reader.take(N=10)))
        assert got[0].header.frame_id == "base_scan" and got[0].header.stamp.nanosec == 250_000_000
        assert [math.isinf(r) for r in got[0].ranges] == [k % 7 == 0 for k in range(360)]


def test_a_subnet_participant_meets_a_default_peer(rclpy_python, domain, tag):
    """``worldgen sim`` in a shell with no discovery setting: the machine's interface beside loopback."""
    with Participant(domain, Discovery("subnet")) as dp, \
            Side(rclpy_python, ["listen", "/chatter", "string", "--node", "/gazebo"], domain, tag, {}) as side:
        writer = dp.writer("/chatter", msgs.TYPES[STRING], DEFAULT, type_hash(STRING))
        graph = Graph(dp, "jazzy")
        graph.add("/gazebo", writers=[writer])
        graph.publish()
        received, seen = side.report(lambda: (writer.write(msgs.TYPES[STRING](data="hi")), time.sleep(0.05)))
        assert received == [{"data": "hi"}] * 3 and ["gazebo", "/"] in seen["nodes"]


def test_discovery_reads_the_environment_as_rcl_does():
    assert Discovery.from_env({}) == Discovery("subnet")
    assert Discovery.from_env({"ROS_LOCALHOST_ONLY": "1", "ROS_STATIC_PEERS": "10.0.0.2",
                               "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}) == Discovery("localhost")
    assert Discovery.from_env({"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                               "ROS_STATIC_PEERS": "10.0.0.2; robot.local"}) == \
        Discovery("localhost", ("10.0.0.2", "robot.local"))
    assert Discovery.from_env({"ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF", "ROS_STATIC_PEERS": "10.0.0.2"}) == \
        Discovery("off")
    assert Discovery.from_env({"ROS_AUTOMATIC_DISCOVERY_RANGE": "nonsense"}).range == "localhost"


def test_participants_share_a_domain_with_one_setting_and_a_second_setting_is_refused(domain):
    with Participant(domain, Discovery("localhost")) as first, Participant(domain, Discovery("localhost")) as second:
        assert first.gid != second.gid
        with pytest.raises(DdsError, match=f"domain {domain} is already open"):
            Participant(domain, Discovery("subnet"))
    with Participant(domain, Discovery("subnet")):   # free again once both are closed
        pass
    with pytest.raises(DdsError, match="0-232"):
        Participant(233)
