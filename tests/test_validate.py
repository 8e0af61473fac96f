"""``worldgen validate`` end to end: inputs, spawn sources, the simulator's checks, reports and exit codes."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import CliRunner
from lxml import etree

from conftest import EXAMPLES
from worldgen.cli import main
from worldgen.core.spawnpose import parse_spawn
from worldgen.check.validate import Options, plan, run_job

CLASS_WORLD = "worlds/Intro-Robotics-UChicago-Spring-2022__warmup_project__worlds_turtlebot3_in_enclosed_room.world"
CLASS_LAUNCH = "launch/Intro-Robotics-UChicago-Spring-2022__warmup_project__launch_turtlebot3_in_room.launch"


def box_link(name: str, start, end, thickness=0.15, height=0.5) -> str:
    (x0, y0), (x1, y1) = start, end
    yaw = math.atan2(y1 - y0, x1 - x0)
    length = math.dist(start, end)
    return f"""
      <link name='{name}'>
        <pose>{(x0 + x1) / 2} {(y0 + y1) / 2} 0 0 0 {yaw}</pose>
        <collision name='{name}_Collision'>
          <pose>0 0 {height / 2} 0 0 0</pose>
          <geometry><box><size>{length} {thickness} {height}</size></box></geometry>
        </collision>
      </link>"""


def write_world(path: Path, walls, size: float | None = None) -> Path:
    """A world with a ground plane and one static model of wall boxes (start, end) 0.5 m high."""
    links = "".join(box_link(f"Wall_{i}", a, b) for i, (a, b) in enumerate(walls))
    path.write_text(f"""<?xml version='1.0'?>
<sdf version='1.6'>
  <world name='default'>
    <model name='ground_plane'>
      <static>1</static>
      <link name='link'>
        <collision name='collision'><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        </collision>
      </link>
    </model>
    <model name='room'>
      <static>1</static>{links}
    </model>
  </world>
</sdf>
""", encoding="utf-8")
    return path


def room_walls(size: float, gap: tuple[float, float] | None = None):
    """The four walls of a size × size room centred on the origin; ``gap`` = (x0, x1) cut from the bottom wall."""
    h = size / 2
    bottom = [((-h, -h), (h, -h))] if gap is None else [((-h, -h), (gap[0], -h)), ((gap[1], -h), (h, -h))]
    return bottom + [((h, -h), (h, h)), ((h, h), (-h, h)), ((-h, h), (-h, -h))]


def run_cli(*args):
    result = CliRunner().invoke(main, ["validate", *(str(a) for a in args)], catch_exceptions=False)
    return result


def as_json(*args):
    out = run_cli(*args, "--format", "json")
    return out.exit_code, json.loads(out.stdout)


# --------------------------------------------------------------------------------------------- the class room

def test_class_room_with_the_course_launch_file(corpus):
    code, doc = as_json(corpus / CLASS_WORLD, "--launch", corpus / CLASS_LAUNCH)
    assert code == 0 and doc["ok"] is True
    [r] = doc["results"]
    assert r["spawn"] == [-5.5, -1.0, 0.0]
    assert r["spawn_source"].startswith("from launch file") and CLASS_LAUNCH.split("/")[1] in r["spawn_source"]
    m = r["metrics"]
    assert m["enclosed"] is True
    # the <state> block moved the room: its inner faces are x -7.257 … -2.557, y -3.761 … 0.939
    assert m["enclosed_area_m2"] == pytest.approx(4.7 * 4.7, rel=0.01)
    assert m["min_clearance_m"] == pytest.approx(7.257 - 5.5 - 0.102, abs=0.005)   # the burger's back to Wall_1
    assert m["lidar_beams"] == 360 and 0 < m["lidar_no_hit_beams"] < 60           # only the far corners > 3.5 m
    assert m["lidar_nearest_m"] == pytest.approx(7.257 - 5.5 - 0.032, abs=0.03)
    assert abs(m["lidar_nearest_bearing_deg"] - 180) < 3
    assert m["spin_drift_m"] < 0.05 and m["spin_touched"] == []
    assert m["stop_distance_m"] == pytest.approx(0.5, abs=0.05) and m["stop_touched"] == []
    # the launch file's $(find warmup_project) does not resolve here: it says which world it validated instead
    said = [f for f in r["findings"] if f["check"] == "launch" and "given on the command line" in f["message"]]
    assert len(said) == 1


def test_class_launch_file_alone_cannot_find_its_world(corpus):
    code, doc = as_json(corpus / CLASS_LAUNCH, "--skip-sim")
    assert code == 1
    [r] = doc["results"]
    assert r["spawn"] == [-5.5, -1.0, 0.0]
    assert any(f["check"] == "launch" and f["severity"] == "error" and "cannot be found" in f["message"]
               for f in r["findings"])
    assert r["skipped"]["enclosed"] == "no world to read"


# ----------------------------------------------------------------------------------------- enclosure end to end

def test_room_with_half_metre_gap_fails_and_names_it(tmp_path):
    world = write_world(tmp_path / "gap.world", room_walls(5.0, gap=(0.5, 1.0)))
    code, doc = as_json(world, "--skip-sim")
    assert code == 1
    r = doc["results"][0]
    assert r["metrics"]["enclosed"] is False
    [gap] = r["metrics"]["gaps"]
    assert gap["centre"] == pytest.approx([0.75, -2.5], abs=1e-3) and gap["width"] == pytest.approx(0.5, abs=0.02)
    [finding] = [f for f in r["findings"] if f["check"] == "enclosed"]
    assert finding["severity"] == "error" and "0.50 m gap at (0.75, -2.5" in finding["message"]


def test_spawn_inside_a_wall_fails(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(5.0))
    code, doc = as_json(world, "--skip-sim", "--spawn", "2.5,0.3")
    assert code == 1
    found = {(f["check"], f["severity"]) for f in doc["results"][0]["findings"]}
    assert {("enclosed", "error"), ("spawn-clear", "error")} <= found
    assert doc["results"][0]["metrics"]["spawn_inside"] == "room/Wall_1/Wall_1_Collision"


# ------------------------------------------------------------------------------------------------ reports

def test_json_shape(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    code, doc = as_json(world, "--spawn", "0.5,0.2,1.57")
    assert code == 0 and set(doc) == {"ok", "results"}
    [r] = doc["results"]
    assert {"path", "ok", "spawn", "spawn_source", "findings", "metrics"} <= set(r)
    assert r["spawn"] == [0.5, 0.2, 1.57] and r["spawn_source"] == "from --spawn"
    assert r["checks"] == ["parse", "enclosed", "spawn-clear", "settle", "lidar", "spin", "stop-at-wall"]
    for key in ("enclosed", "min_clearance_m", "lidar_no_hit_beams"):
        assert key in r["metrics"]
    assert r["metrics"]["lidar_no_hit_beams"] == 0          # a 4 m room: every wall within 3.5 m
    for f in r["findings"]:
        assert set(f) <= {"check", "severity", "message", "where", "fix"}


def test_junit_has_a_testcase_per_file_and_check(tmp_path):
    good = write_world(tmp_path / "good.world", room_walls(4.0))
    bad = write_world(tmp_path / "bad.world", room_walls(4.0, gap=(0.0, 0.6)))
    report = tmp_path / "reports" / "validate.xml"
    out = run_cli(good, bad, "--skip-sim", "--junit", report)
    assert out.exit_code == 1
    root = etree.parse(str(report)).getroot()
    [suite] = root.findall("testsuite")
    cases = {(c.get("classname"), c.get("name")): c for c in suite.findall("testcase")}
    for path in (good, bad):
        for check in ("parse", "enclosed", "spawn-clear", "settle", "lidar", "spin", "stop-at-wall"):
            assert (str(path), check) in cases
    assert cases[str(bad), "enclosed"].find("failure") is not None
    assert "0.60 m gap" in cases[str(bad), "enclosed"].find("failure").get("message")
    assert cases[str(good), "enclosed"].find("failure") is None
    assert cases[str(good), "spin"].find("skipped") is not None
    assert suite.get("tests") == "14" and suite.get("failures") == "1" and suite.get("skipped") == "8"
    assert not list(report.parent.glob(".*.tmp"))   # written atomically: no temporary left behind


def test_junit_replaces_an_earlier_report_and_nothing_else(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    report = tmp_path / "report.xml"
    assert run_cli(world, "--skip-sim", "--junit", report).exit_code == 0
    first = report.read_bytes()
    report.write_bytes(first.replace(b'tests="', b'tests="9'))   # an earlier report, whatever it said
    assert run_cli(world, "--skip-sim", "--junit", report).exit_code == 0
    assert report.read_bytes() == first
    report.write_bytes(b"")   # an empty placeholder (touch report.xml) is taken too
    assert run_cli(world, "--skip-sim", "--junit", report).exit_code == 0 and report.read_bytes() == first
    manifest = tmp_path / "package.xml"   # named by mistake: kept, byte for byte
    manifest.write_text("<package format='2'><name>lab</name></package>\n")
    for kept in (manifest, tmp_path / "notes.xml"):
        if kept != manifest:
            kept.write_bytes(b"not xml at all")
        before = kept.read_bytes()
        out = run_cli(world, "--skip-sim", "--junit", kept)
        assert out.exit_code == 2 and kept.read_bytes() == before
        assert out.output == f"worldgen: error: {kept} exists and is not a JUnit report (give --junit another " \
                             "name: it replaces only an earlier report)\n"


def test_html_of_a_folder_is_refused_a_page_name(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    out = run_cli(world, "--skip-sim", "--html", tmp_path / "report.html")
    assert out.exit_code == 2 and "give a folder name such as report/" in out.output
    assert not (tmp_path / "report.html").exists()


def test_reports_hold_file_names_that_are_not_text(tmp_path):
    # a control character, and byte 0xff (not UTF-8), which Python keeps as the lone surrogate \udcff
    bad = write_world(tmp_path / "a\x01b\udcff.world", room_walls(4.0, gap=(0.0, 0.6)))
    code, doc = as_json(bad, "--skip-sim")
    assert code == 1 and doc["results"][0]["path"] == str(tmp_path / "a\x01b\ufffd.world")
    assert "a\x01b\ufffd.world" in run_cli(bad, "--skip-sim").output
    report = tmp_path / "validate.xml"
    assert run_cli(bad, "--skip-sim", "--junit", report).exit_code == 1
    cases = etree.parse(str(report)).getroot().findall("testsuite/testcase")
    assert {c.get("classname") for c in cases} == {str(tmp_path / "a\ufffdb\ufffd.world")}
    [failing] = [c for c in cases if c.find("failure") is not None]
    assert failing.get("name") == "enclosed" and "0.60 m gap" in failing.find("failure").get("message")


def test_a_launch_error_does_not_stop_a_spec_being_checked(tmp_path):
    launch = tmp_path / "bad_x.launch"
    launch.write_text('<launch><node pkg="gazebo_ros" type="spawn_model" name="spawn_urdf" '
                      'args="-urdf -model turtlebot3_burger -x abc -y 0 -param robot_description"/></launch>')
    code, doc = as_json(EXAMPLES / "enclosed_room.yaml", "--launch", launch, "--skip-sim")
    [r] = doc["results"]
    assert code == 1 and [f["check"] for f in r["findings"] if f["severity"] == "error"] == ["launch-spawn"]
    assert r["checks"] == ["launch", "parse", "enclosed", "spawn-clear"]
    assert r["metrics"]["enclosed"] is True and r["metrics"]["enclosed_area_m2"] > 10


def test_text_report_is_a_table_with_findings_errors_first(tmp_path):
    bad = write_world(tmp_path / "bad.world", room_walls(4.0, gap=(0.0, 0.6)))
    out = run_cli(bad, "--skip-sim")
    lines = out.stdout.splitlines()
    assert lines[0].split()[:3] == ["file", "verdict", "enclosed"]
    assert lines[1].split()[1:3] == ["FAIL", "NO"]
    severities = [line.split()[0] for line in lines[3:] if line.startswith("    ") and not line.startswith("     ")]
    assert severities and severities == sorted(severities, key=["error", "warning", "info"].index)
    assert lines[-1] == "1 file(s): 0 passed, 1 failed"


# --------------------------------------------------------------------------------------------------- LiDAR

@pytest.mark.parametrize("mode, reading", [("inf", "inf"), ("zero", 0.0)])
def test_lidar_no_hit_reads_inf_or_zero_in_a_big_room(tmp_path, mode, reading):
    world = write_world(tmp_path / "hall.world", room_walls(8.0))   # 8 m: from the middle no wall within 3.5 m
    code, doc = as_json(world, "--lidar-no-hit", mode)
    m = doc["results"][0]["metrics"]
    assert code == 0    # a warning, not a failure
    assert m["lidar_no_hit_beams"] == 360 and m["lidar_no_hit_value"] == mode
    assert m["lidar_no_hit_reading"] == reading
    [warning] = [f for f in doc["results"][0]["findings"] if f["check"] == "lidar"]
    assert ("read inf" if mode == "inf" else "read 0") in warning["message"]
    # nothing within range ahead or anywhere: stop-at-wall says so instead of failing
    stop = [f for f in doc["results"][0]["findings"] if f["check"] == "stop-at-wall"]
    assert stop and stop[0]["severity"] == "info"


def test_stop_at_wall_turns_to_face_the_nearest_wall(tmp_path):
    # a 6 m room, spawn 1.2 m from the left wall facing +x: nothing within 3.5 m ahead, the left wall behind
    world = write_world(tmp_path / "wide.world", room_walls(6.0))
    code, doc = as_json(world, "--spawn", "-1.8,0.4,0")
    m = doc["results"][0]["metrics"]
    assert code == 0
    assert m["stop_distance_m"] == pytest.approx(0.5, abs=0.05)
    assert abs(abs(m["stop_heading_deg"]) - 180) < 10


# ------------------------------------------------------------------------------------------------ exit codes

BAD_NUMBER_URDF = """<robot name="r">
  <link name="base_footprint"/>
  <link name="base_link"><collision><origin xyz="0 0 {z}"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="j" type="fixed"><parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 {jz}"/>
  </joint>
</robot>
"""


def test_exit_code_2_for_bad_input_with_one_line(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    (tmp_path / "collision.urdf").write_text(BAD_NUMBER_URDF.format(z="oops", jz="0.1"))
    (tmp_path / "joint.urdf").write_text(BAD_NUMBER_URDF.format(z="0", jz="zz"))
    for args in ([tmp_path / "missing.world"], [world, "--spawn", "1,x"], [world, "--robot", "roomba"],
                 [world, "--model-path", tmp_path / "nope"], [world, "--launch", tmp_path / "no.launch"],
                 [world, "--robot", tmp_path / "collision.urdf"], [world, "--robot", tmp_path / "joint.urdf"],
                 [world, "--skip-sim", "--junit", world / "report.xml"]):   # a folder that is a file
        proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", *map(str, args)],
                              capture_output=True, text=True)
        assert proc.returncode == 2, args
        assert proc.stdout == "" and len(proc.stderr.strip().splitlines()) == 1, proc.stderr
        assert "Traceback" not in proc.stderr


@pytest.mark.parametrize("name, what", [("stop_at_wall.py", "a Python file"), ("room.html", "a page"),
                                        ("room.png", "a picture"), ("map.pgm", "a map image"),
                                        ("gains.csv", "a table")])
def test_a_file_worldgen_writes_but_no_command_reads_says_what_it_is(tmp_path, name, what):
    """Not 'not well-formed XML, fix the tag': what the file is, and what to do with it instead."""
    path = tmp_path / name
    path.write_bytes(b"\x89PNG\r\n" if name.endswith("png") else b"print('hi')\n")
    result = run_cli(path)
    assert result.exit_code == 2
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"worldgen: error: {path}: is {what}") and "not a world, spec or launch file" in line


def test_a_bridge_parameter_file_is_named_as_one(tmp_path):
    params = tmp_path / "turtlebot3_bridge.yaml"
    params.write_text("- ros_topic_name: /scan\n  gz_topic_name: /scan\n  ros_type_name: sensor_msgs/msg/LaserScan\n")
    code, doc = as_json(params, "--skip-sim")
    [finding] = [f for f in doc["results"][0]["findings"] if f["severity"] == "error"]
    assert code == 1 and "ros_gz_bridge parameter file" in finding["message"]
    assert "validate the package that holds it" in finding["fix"]


def test_exit_codes_0_and_1(tmp_path):
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    assert run_cli(world, "--skip-sim").exit_code == 0
    assert run_cli(world, "--skip-sim", "--spawn", "9,9").exit_code == 1


def test_parse_spawn_forms():
    assert parse_spawn("1,2") == (1.0, 2.0, 0.0)
    assert parse_spawn(" -5.5, -1.0 , 1.57") == (-5.5, -1.0, 1.57)


# ------------------------------------------------------------------------------------ inputs and -j N

def test_results_keep_input_order_with_two_workers(tmp_path):
    worlds = [write_world(tmp_path / f"room{i}.world", room_walls(3.0 + i, gap=(0.0, 0.4) if i == 1 else None))
              for i in range(3)]
    code, doc = as_json(*worlds, "-j", "2")
    assert [r["path"] for r in doc["results"]] == [str(w) for w in worlds]
    assert [r["ok"] for r in doc["results"]] == [True, False, True]
    assert code == 1


def test_crashed_simulator_becomes_a_finding(tmp_path, monkeypatch):
    helper = tmp_path / "crashing_job.py"
    helper.write_text("import os\n\ndef simulate(stage_file=None, **kwargs):\n"
                      "    open(stage_file, 'w').write('spinning in place')\n    os.abort()\n")
    monkeypatch.setenv("PYTHONPATH", str(tmp_path))
    monkeypatch.setattr("worldgen.check.validate.SIM_JOB", "crashing_job:simulate")
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    [job] = plan([world], Options())
    [result] = run_job(job, Options())
    [crash] = [f for f in result.findings if f.severity == "error"]
    assert crash.message == "pybullet crashed (killed by SIGABRT) while spinning in place"
    assert result.skipped["spin"] == "the simulation did not run to the end"
    assert result.metrics["enclosed"] is True   # the geometric checks still report


def test_package_folder_validates_each_launch_file(tmp_path):
    pkg = tmp_path / "ws" / "src" / "my_room"
    (pkg / "launch").mkdir(parents=True)
    (pkg / "worlds").mkdir()
    write_world(pkg / "worlds" / "room.world", room_walls(4.0))
    (pkg / "package.xml").write_text("""<?xml version="1.0"?>
<package format="2">
  <name>my_room</name><version>0.0.0</version><description>room</description>
  <maintainer email="student@example.com">student</maintainer><license>MIT</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>gazebo_ros</exec_depend>
</package>
""", encoding="utf-8")
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.0.2)\nproject(my_room)\nfind_package(catkin REQUIRED)\ncatkin_package()\n"
        "install(DIRECTORY launch worlds DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})\n")
    (pkg / "launch" / "room.launch").write_text("""<launch>
  <arg name="x_pos" default="0.8"/>
  <arg name="y_pos" default="-0.6"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="$(find my_room)/worlds/room.world"/>
  </include>
  <node pkg="gazebo_ros" type="spawn_model" name="spawn_urdf"
        args="-urdf -model turtlebot3_burger -x $(arg x_pos) -y $(arg y_pos) -z 0 -param robot_description"/>
</launch>
""", encoding="utf-8")
    code, doc = as_json(pkg, "--skip-sim")
    paths = [r["path"] for r in doc["results"]]
    assert paths == [str(pkg), str(pkg / "launch" / "room.launch")]
    package_row, launch_row = doc["results"]
    assert package_row["checks"] == ["package"]
    assert launch_row["spawn"] == [0.8, -0.6, 0.0] and launch_row["metrics"]["enclosed"] is True
    assert all(f["severity"] != "error" for r in doc["results"] for f in r["findings"]), json.dumps(doc, indent=1)
    assert code == 0 and doc["ok"] is True
    # the package check's own findings land on the package's row, under the package test case
    (pkg / "CMakeLists.txt").unlink()
    report = tmp_path / "junit.xml"
    code, doc = as_json(pkg, "--skip-sim", "--junit", report)
    assert code == 1 and doc["results"][0]["ok"] is False and doc["results"][1]["ok"] is True
    assert [f["check"] for f in doc["results"][0]["findings"]] == ["package-cmake"]
    failing = etree.parse(str(report)).getroot().xpath("//testcase[failure]")
    assert [(c.get("classname"), c.get("name")) for c in failing] == [(str(pkg), "package")]


# ------------------------------------------------------------------------------------------- our examples

EXAMPLE_SPECS = sorted(EXAMPLES.glob("*.yaml"))


@pytest.mark.skipif(not EXAMPLE_SPECS, reason="no examples/*.yaml yet")
def test_our_examples_pass():
    pytest.importorskip("worldgen.sdf.writer")
    code, doc = as_json(*EXAMPLE_SPECS, "-j", "2")
    failures = {r["path"]: [f["message"] for f in r["findings"] if f["severity"] == "error"]
                for r in doc["results"] if not r["ok"]}
    assert failures == {} and code == 0
    for r in doc["results"]:
        assert r["spawn_source"].startswith("from spec") and r["metrics"]["enclosed"] is True


def test_progress_in_a_log_is_one_line_per_file_on_stderr(tmp_path):
    worlds = [write_world(tmp_path / f"r{i}.world", room_walls(4.0, gap=(0.0, 0.6) if i else None))
              for i in range(3)]
    proc = subprocess.run([sys.executable, "-m", "worldgen", "validate", "--skip-sim", "-j", "2", "--format", "json",
                           *map(str, worlds)], capture_output=True, text=True, env=dict(os.environ))
    assert proc.returncode == 1
    assert len(json.loads(proc.stdout)["results"]) == 3   # stdout holds the report alone
    lines = proc.stderr.splitlines()
    assert sorted(line.split(" ", 1)[0] for line in lines) == ["[1/3]", "[2/3]", "[3/3]"]
    verdicts = {line.split(" ", 2)[2]: line.split(" ", 2)[1] for line in lines}
    assert verdicts == {str(worlds[0]): "ok", str(worlds[1]): "FAIL", str(worlds[2]): "FAIL"}


def test_progress_bar_on_a_terminal():
    import io

    from worldgen.check.progress import progress_for

    class Tty(io.StringIO):
        def isatty(self):
            return True

    stream = Tty()
    with progress_for(2, stream) as step:
        step(None, [])
        step(None, [])
    assert "validating" in stream.getvalue() and "100%" in stream.getvalue()


def test_unreadable_files_are_failed_checks_not_tracebacks(tmp_path):
    (tmp_path / "broken.world").write_text("<sdf version='1.6'><world name='w'>", encoding="utf-8")
    (tmp_path / "broken.launch").write_text("<launch><arg name='x'</launch>", encoding="utf-8")
    (tmp_path / "bad.yaml").write_text("name: bad\nrooms: [{name: r, rect: {center: [0, 0], size: [-5, 5]}}]\n",
                                       encoding="utf-8")
    report = tmp_path / "junit.xml"
    code, doc = as_json(tmp_path / "broken.world", tmp_path / "broken.launch", tmp_path / "bad.yaml",
                        "--junit", report)
    assert code == 1
    world, launch, spec = doc["results"]
    assert [(f["check"], f["severity"]) for f in world["findings"]] == [("parse", "error")]
    assert world["findings"][0]["where"].startswith(str(tmp_path / "broken.world"))
    assert world["skipped"]["enclosed"] == "the world cannot be read"
    assert [(f["check"], f["severity"]) for f in launch["findings"]] == [("launch", "error")]
    assert spec["findings"][0]["where"] == f"{tmp_path / 'bad.yaml'}:2"
    failing = etree.parse(str(report)).getroot().xpath("//testcase[failure]")
    assert [(c.get("classname").rsplit("/", 1)[-1], c.get("name")) for c in failing] == [
        ("broken.world", "parse"), ("broken.launch", "launch"), ("bad.yaml", "parse")]


# ------------------------------------------------------------------------------------- --sdformat (libsdformat)

@pytest.fixture(scope="module")
def libsdformat():
    """libsdformat is there (skips without it, except under CI, where a missing library fails the run)."""
    from worldgen.check.sdformat import sdformat_check

    if sdformat_check(Path(__file__)) is None:
        if os.environ.get("CI"):
            pytest.fail("libsdformat (libsdformat12.so.12) is missing under CI: install libsdformat-dev")
        pytest.skip("libsdformat is not installed")


@pytest.fixture
def no_model_path(monkeypatch):
    """No GAZEBO_MODEL_PATH or SDF_PATH from the environment: only the stand-ins can provide stock models."""
    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    monkeypatch.delenv("SDF_PATH", raising=False)


def room_world(path: Path, *, head: str = "", extra: str = "", links=None) -> Path:
    """A 4 m room (one static model of wall links, 0.5 m high) after ``head`` (includes, a ground plane) and
    before ``extra`` (more models); ``links`` replaces the walls' link texts."""
    if links is None:
        links = [box_link(f"Wall_{i}", a, b) for i, (a, b) in enumerate(room_walls(4.0))]
    path.write_text(f"""<?xml version='1.0'?>
<sdf version='1.6'>
  <world name='default'>{head}
    <model name='room'>
      <static>1</static>{''.join(links)}
    </model>{extra}
  </world>
</sdf>
""", encoding="utf-8")
    return path


STOCK_INCLUDES = """
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>"""


def sdformat_findings(result: dict) -> list[tuple[str, str]]:
    return [(f["severity"], f["message"]) for f in result["findings"] if f["check"] == "sdformat"]


@pytest.mark.skipif(not EXAMPLE_SPECS, reason="no examples/*.yaml yet")
def test_our_examples_pass_libsdformat(libsdformat):
    code, doc = as_json(*EXAMPLE_SPECS, "--sdformat", "--skip-sim", "-j", "2")
    assert code == 0
    for r in doc["results"]:
        assert "sdformat" in r["checks"] and r["metrics"]["sdformat_valid"] is True, r["path"]
        assert sdformat_findings(r) == []


def test_wrong_box_arity_fails_libsdformat_at_its_line(libsdformat, tmp_path, no_model_path):
    crate = """
    <model name='crate'>
      <static>1</static>
      <pose>1 1 0 0 0 0</pose>
      <link name='body'>
        <collision name='body_collision'>
          <geometry><box><size>1 2</size></box></geometry>
        </collision>
      </link>
    </model>"""
    world = room_world(tmp_path / "crate.world", head=STOCK_INCLUDES, extra=crate)
    line = world.read_text().splitlines().index("          <geometry><box><size>1 2</size></box></geometry>") + 1
    code, doc = as_json(world, "--skip-sim")
    assert code == 0   # our own reader only warns (it reads the box as 1 × 1 × 1)
    code, doc = as_json(world, "--skip-sim", "--sdformat")
    [r] = doc["results"]
    assert code == 1 and r["metrics"]["sdformat_valid"] is False
    [error] = [f for f in r["findings"] if f["check"] == "sdformat"]   # one finding, not the cascade to <sdf>
    assert error["severity"] == "error" and "[1 2 ]" in error["message"] and "key[size]" in error["message"]
    assert error["where"] == (f"{world}:{line} "
                              "(world[default]/model[crate]/link[body]/collision[body_collision]/geometry/box/size)")


def test_duplicate_link_name_fails_libsdformat_naming_it(libsdformat, tmp_path, no_model_path):
    walls = room_walls(4.0)
    links = [box_link("Wall_0" if i == 1 else f"Wall_{i}", a, b) for i, (a, b) in enumerate(walls)]
    world = room_world(tmp_path / "dup.world", head=STOCK_INCLUDES, links=links)
    code, doc = as_json(world, "--skip-sim", "--sdformat")
    [r] = doc["results"]
    assert code == 1
    [error] = [f for f in r["findings"] if f["check"] == "sdformat" and f["severity"] == "error"]
    assert error["message"] == "link with name[Wall_0] already exists." and error["where"] == "model room"


def test_class_room_passes_libsdformat(libsdformat, corpus, no_model_path):
    code, doc = as_json(corpus / CLASS_WORLD, "--skip-sim", "--sdformat", "--spawn", "-5.5,-1")
    [r] = doc["results"]
    assert code == 0 and r["checks"] == ["parse", "sdformat", "enclosed", "spawn-clear"]
    assert r["metrics"]["sdformat_valid"] is True and sdformat_findings(r) == []


def test_stock_includes_pass_libsdformat_thanks_to_the_stand_ins(libsdformat, tmp_path, no_model_path):
    world = room_world(tmp_path / "stock.world", head=STOCK_INCLUDES)
    code, doc = as_json(world, "--skip-sim", "--sdformat")
    [r] = doc["results"]
    assert code == 0 and r["metrics"]["sdformat_valid"] is True and sdformat_findings(r) == []


@pytest.mark.parametrize("how", ["--model-path", "GAZEBO_MODEL_PATH"])
def test_libsdformat_checks_included_models_from_the_model_path(libsdformat, tmp_path, no_model_path,
                                                                  monkeypatch, how):
    crate = tmp_path / "models" / "crate"
    crate.mkdir(parents=True)
    (crate / "model.config").write_text("<model><name>crate</name><sdf version='1.6'>model.sdf</sdf></model>")
    (crate / "model.sdf").write_text("""<sdf version='1.6'>
  <model name='crate'>
    <static>1</static>
    <link name='body'>
      <collision name='c'><geometry><box><size>0.4 0.4</size></box></geometry></collision>
    </link>
  </model>
</sdf>
""")
    world = room_world(tmp_path / "crate.world", head=STOCK_INCLUDES,
                       extra="\n    <include><uri>model://crate</uri><pose>1 1 0 0 0 0</pose></include>")
    args = [world, "--skip-sim", "--sdformat"]
    if how == "--model-path":
        args += ["--model-path", tmp_path / "models"]
    else:
        monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    code, doc = as_json(*args)
    [error] = [f for f in doc["results"][0]["findings"] if f["check"] == "sdformat"]
    assert code == 1 and "[0.4 0.4 ]" in error["message"]
    assert error["where"].startswith(f"{(crate / 'model.sdf').resolve()}:5 (model[crate]/link[body]/collision[c]")


def test_missing_include_is_a_libsdformat_warning(libsdformat, tmp_path, no_model_path):
    nowhere = "\n    <include><uri>model://nowhere</uri></include>"
    world = room_world(tmp_path / "w.world", head=STOCK_INCLUDES + nowhere)
    code, doc = as_json(world, "--skip-sim", "--sdformat")
    [r] = doc["results"]
    assert code == 0 and r["metrics"]["sdformat_valid"] is False   # Gazebo Classic loads the rest all the same
    assert sdformat_findings(r) == [("warning", "Unable to find uri[model://nowhere]")]


def test_a_spec_is_checked_as_the_world_it_builds(libsdformat, tmp_path, monkeypatch):
    import re

    import worldgen.sdf.writer as writer

    spec = tmp_path / "room.yaml"
    spec.write_text((EXAMPLES / "enclosed_room.yaml").read_text(encoding="utf-8"), encoding="utf-8")
    built = writer.world_sdf   # validate builds the spec's geometry once, and its world text from that
    monkeypatch.setattr(writer, "world_sdf",   # a wall box of two numbers
                        lambda b: re.sub(r"<box>\s*<size>[^<]*</size>", "<box><size>1 2</size>", built(b), count=1))
    [job] = plan([spec], Options(sdformat=True, skip_sim=True))
    [result] = run_job(job, Options(sdformat=True, skip_sim=True))
    [error] = [f for f in result.findings if f.check == "sdformat"]
    assert error.severity == "error" and error.where.startswith(f"{tmp_path / 'room.world'}:")
    assert "key[size]" in error.message and "/box/size)" in error.where
    assert "worldgen_validate_" not in error.message + error.where   # the temporary file is not named


def test_without_libsdformat_the_check_is_skipped_with_a_note(tmp_path, monkeypatch):
    monkeypatch.setattr("worldgen.check.checks.sdformat_check", lambda *args, **kwargs: None)
    world = write_world(tmp_path / "room.world", room_walls(4.0))
    report = tmp_path / "junit.xml"
    code, doc = as_json(world, "--skip-sim", "--sdformat", "--junit", report)
    [r] = doc["results"]
    assert code == 0 and "sdformat" not in r["checks"]
    assert r["skipped"]["sdformat"] == "libsdformat is not installed"
    assert [(f["severity"], f["message"]) for f in r["findings"] if f["check"] == "sdformat"] == [
        ("info", "libsdformat is not installed; check skipped")]
    [case] = etree.parse(str(report)).getroot().xpath("//testcase[@name='sdformat']")
    assert case.find("skipped").get("message") == "libsdformat is not installed"


def test_sdformat_is_skipped_with_the_rest_when_there_is_no_world(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nrooms: [{name: r, rect: {center: [0, 0], size: [-5, 5]}}]\n", encoding="utf-8")
    code, doc = as_json(bad, "--sdformat")
    assert code == 1 and doc["results"][0]["skipped"]["sdformat"] == "the spec cannot be read"
