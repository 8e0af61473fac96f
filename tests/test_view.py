"""The 3D pages as files: what the data holds (the same geometry ``preview`` and ``validate`` read), that a page
is self-contained, deterministic and small, how a run is thinned for the replay, and the command lines that write
them (``view``, ``drive --html``, ``validate --html DIR``). The browser's side is tests/test_view_browser.py."""

from __future__ import annotations

import json
import math
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import html as lxml_html

from conftest import EXAMPLES, CliRunner
from worldgen.cli import main
from worldgen.view.page import world_page
from worldgen.view.replay import MAX_POSES, MAX_SCANS, run_replay, thin
from worldgen.view.scene_data import read_source, world_data


def page_data(page: bytes) -> dict:
    doc = lxml_html.fromstring(page)
    return json.loads(doc.get_element_by_id("worldgen-data").text)


def test_the_plan_is_preview_s_geometry_and_the_rooms_are_named():
    import shapely

    from worldgen.geometry.placement import SLICE_Z
    from worldgen.geometry.slices import footprints_between
    from worldgen.view.preview import picture

    data = world_data(read_source(EXAMPLES / "two_rooms.yaml"))
    pic = picture(EXAMPLES / "two_rooms.yaml")
    walls = shapely.union_all([p.geometry for p in footprints_between(pic.scene, *SLICE_Z) if p.label in pic.walls])
    drawn = shapely.union_all([shapely.Polygon(rings[0], rings[1:]) for rings in data["plan"]["walls"]])
    assert drawn.symmetric_difference(walls).area < 0.001 * walls.area
    rooms = sorted(r["n"] for r in data["plan"]["rooms"])
    assert rooms[0].startswith("room 'east': 2.85 × 3.85 m inside") and rooms[1].startswith("room 'west': 3.85 × 3.85 m")
    door, window = sorted(data["openings"], key=lambda o: o["type"])
    assert door["type"] == "door" and door["s"][0] == pytest.approx(0.9) and door["p"][:2] == [2.0, 0.0]
    assert window["s"][0] == pytest.approx(0.8) and window["p"][0] == 5.0 and "sill 0.50 m" in window["n"]
    robot = data["robot"]
    assert robot["model"] == "waffle" and robot["spawn"] == [-1.0, 0.0, 1.571]
    assert robot["lidar"]["n"] == 360 and robot["lidar"]["max"] == 3.5
    walls_drawn = [i for i in data["items"] if i["g"] == "wall"]
    assert walls_drawn and {i["c"] for i in walls_drawn} != {"#b2b2b2"}   # Gazebo/Bricks, not the default grey


def test_a_page_is_self_contained_deterministic_and_small():
    first = world_page(EXAMPLES / "enclosed_room.yaml")
    assert first == world_page(EXAMPLES / "enclosed_room.yaml")
    assert len(first) < 1.5e6
    doc = lxml_html.fromstring(first)
    assert not doc.xpath("//*[@src]") and not doc.xpath("//link")   # nothing is fetched: every script is inline
    policy = doc.xpath("//meta[@http-equiv='Content-Security-Policy']/@content")[0]
    assert "default-src 'none'" in policy and "http" not in policy
    scripts = {s.get("id"): s.get("type") for s in doc.xpath("//script")}
    assert scripts["lib-three"] == "text/x-worldgen-module" and scripts["worldgen-data"] == "application/json"
    assert b"three.js 0.170.0" in first and b"Permission is hereby granted" in first   # the licence travels along


def test_the_spawn_and_robot_come_from_a_launch_file(tmp_path):
    runner = CliRunner()
    world_dir = tmp_path / "worlds"
    assert runner.invoke(main, ["build", str(EXAMPLES / "enclosed_room.yaml"), "-o", str(world_dir)]).exit_code == 0
    world = next(world_dir.glob("*.world"))
    launch = tmp_path / "room.launch"   # as the class writes it by hand
    launch.write_text(f"""<launch>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="{world}"/>
  </include>
  <param name="robot_description"
         command="$(find xacro)/xacro $(find turtlebot3_description)/urdf/turtlebot3_waffle_pi.urdf.xacro"/>
  <node pkg="gazebo_ros" type="spawn_model" name="spawn_urdf"
        args="-urdf -model turtlebot3 -x 1.0 -y -0.5 -z 0.0 -Y 3.1416 -param robot_description"/>
</launch>
""", encoding="utf-8")
    data = page_data(world_page(launch))
    assert data["robot"]["spawn"] == [1.0, -0.5, 3.142] and data["robot"]["model"] == "waffle_pi"


def test_view_writes_the_page_and_refuses_bad_input_in_one_line(tmp_path):
    runner = CliRunner()
    out = tmp_path / "room.html"
    result = runner.invoke(main, ["view", str(EXAMPLES / "room_with_window.yaml"), "-o", str(out)])
    assert result.exit_code == 0 and out.stat().st_size > 100_000
    again = runner.invoke(main, ["view", str(EXAMPLES / "room_with_window.yaml"), "-o", str(out)])
    assert again.exit_code == 2 and "--force" in again.output
    for args, words in ((["view", str(tmp_path / "nope.yaml")], "no such file"),
                        (["view", str(EXAMPLES)], "not a world"),
                        (["view", str(EXAMPLES / "enclosed_room.yaml"), "--spawn", "1,2,3,4"], "spawn")):
        bad = runner.invoke(main, args + ["-o", str(tmp_path / "bad.html")])
        assert bad.exit_code == 2 and words in bad.output and "Traceback" not in bad.output, bad.output
        assert len(bad.output.strip().splitlines()) == 1
    assert not (tmp_path / "bad.html").exists()


# ----------------------------------------------------------------------------------------------- the replay
def trace_of(seconds: float, hz: float = 30.0) -> dict:
    """A robot circling at 30 Hz odometry, with a full 360-beam scan at 5 Hz and a contact at a third of the way."""
    odom, ranges = [], []
    for i in range(int(seconds * hz) + 1):
        t = i / hz
        a = 0.1 * t
        odom.append([t, math.cos(a), math.sin(a), a + math.pi / 2, 0.1, 0.1, 0.1, 0.1])
        if i % int(hz / 5) == 0:
            ranges.append([round(t, 3), round(math.cos(a), 4), round(math.sin(a), 4), round(a, 4),
                           [1234 + b if b % 7 else -1 for b in range(360)]])
    return {"odom": odom, "scans": [[r[0], 1.2, 1.5, 0.9, 0.8] for r in ranges],
            "contacts": [{"link": "base_link", "shape": "Wall_1", "time": seconds / 3, "depth": 0.001}],
            "lidar": {"angle_min": 0.0, "angle_increment": 0.0175, "range_min": 0.12, "range_max": 3.5, "count": 360},
            "ranges": ranges}


def test_a_run_is_thinned_to_what_the_eye_needs():
    replay = run_replay(trace_of(60.0))
    assert len(replay["t"]) == 601 and replay["t"][:3] == [0.0, 0.1, 0.2] and replay["t"][-1] == 60.0
    assert replay["d"][1] == 1.5 and replay["v"][5] == 0.1
    scans = replay["scans"]
    assert len(scans["t"]) == 301 and scans["r"][0][1] == 124 and scans["r"][0][0] == -1   # cm; no hit stays -1
    contact = replay["contacts"][0]
    assert contact["t"] == 20.0 and (contact["x"], contact["y"]) == pytest.approx((math.cos(2), math.sin(2)), abs=2e-3)
    assert contact["n"] == "Wall_1"
    hour = run_replay(trace_of(3600.0))
    assert len(hour["t"]) == MAX_POSES and len(hour["scans"]["t"]) == MAX_SCANS


def test_a_replay_page_of_a_minute_is_under_three_megabytes():
    import types

    from worldgen.check.report import Result
    from worldgen.check.sources import load_scene
    from worldgen.view.grades import run_page

    scene, _ = load_scene(EXAMPLES / "enclosed_room.yaml", "spec")
    world = types.SimpleNamespace(path=EXAMPLES / "enclosed_room.yaml", scene=scene, spawn=(1.0, 0.0, 0.0),
                                  robot="burger")
    page = run_page(Result(path="ada", checks=["node", "spin"]), world, trace_of(60.0))
    assert len(page) < 3e6
    data = page_data(page)
    assert data["robot"]["spawn"] == [1.0, 0.0, 1.5708] and len(data["replay"]["scans"]["r"]) == 301


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(0, 1000, allow_nan=False), min_size=1, max_size=400), st.floats(0.5, 50),
       st.integers(2, 100))
def test_thinning_keeps_the_ends_and_the_limit(times, rate, limit):
    times = sorted(times)
    kept = thin(times, rate, limit)
    assert kept[0] == 0 and kept[-1] == len(times) - 1 and kept == sorted(set(kept))
    assert len(kept) <= limit
    step = max(1 / rate, (times[-1] - times[0]) / (limit - 1))
    ticks = [math.floor((times[i] - times[0]) / step + 0.5) for i in kept[:-1]]
    assert ticks == sorted(set(ticks))   # at most one sample a tick (the last sample aside)


@settings(max_examples=50, deadline=None)
@given(st.lists(st.floats(-0.004, 0.004), min_size=50, max_size=400))
def test_thinning_keeps_a_sensors_own_rate_through_its_jitter(jitter):
    """Scans 0.2 s apart, each up to 4 ms early or late, thinned to 5 a second: every one is kept."""
    times = [k * 0.2 + (j if k else 0.0) for k, j in enumerate(jitter)]
    assert thin(times, 5.0, 10_000) == list(range(len(times)))
    ten_minutes = [k / 30 for k in range(30 * 600 + 1)]
    assert len(thin(ten_minutes, 10.0, MAX_POSES)) == 6001


# ------------------------------------------------------------------------------------------- command lines
def test_drive_html_replays_the_stop(tmp_path):
    out = tmp_path / "drive.html"
    result = CliRunner().invoke(main, ["drive", str(EXAMPLES / "enclosed_room.yaml"), "--html", str(out)])
    assert result.exit_code == 0, result.output
    final = float(re.search(r"kp=0.5 ki=0 kd=0\s+([0-9.]+)", result.output).group(1))
    replay = page_data(out.read_bytes())["replay"]
    assert (replay["x"][0], replay["y"][0]) == pytest.approx((0.0, 0.0), abs=0.01)
    # the spec's room is 5 m wide: the wall's inner face at x = 2.425; the sensor 32 mm behind base_footprint
    assert replay["x"][-1] == pytest.approx(2.425 - final + 0.032, abs=0.02)
    assert max(replay["v"]) == pytest.approx(0.22) and replay["scans"]["r"][-1][0] == pytest.approx(final * 100, abs=3)


def test_validate_html_writes_an_index_of_every_file(tmp_path):
    folder = tmp_path / "class"
    folder.mkdir()
    for name in ("enclosed_room.yaml", "two_rooms.yaml", "maze.yaml"):
        (folder / name).write_bytes((EXAMPLES / name).read_bytes())
    (folder / "broken.world").write_text("<sdf version='1.6'><world name='w'><model", encoding="utf-8")
    report = tmp_path / "report"
    result = CliRunner().invoke(main, ["validate", str(folder), "--skip-sim", "--format", "json", "--html", str(report)])
    results = json.loads(result.stdout)
    assert result.exit_code == 1   # the broken world fails
    rows = json.loads(lxml_html.fromstring((report / "index.html").read_bytes()).get_element_by_id("worldgen-index").text)
    assert [(r["path"], r["verdict"]) for r in rows] == [(r["path"], "FAIL" if not r["ok"] else
                                                          ("warn" if any(f["severity"] == "warning"
                                                                         for f in r["findings"]) else "ok"))
                                                         for r in results["results"]]
    linked = {r["path"]: r["href"] for r in rows}
    assert linked[str(folder / "broken.world")] is None   # nothing to draw
    page = report / linked[str(folder / "two_rooms.yaml")]
    assert page_data(page.read_bytes())["robot"]["model"] == "waffle"
    back = lxml_html.fromstring(page.read_bytes()).xpath("//a[@class='back']/@href")[0]
    assert (page.parent / back).resolve() == (report / "index.html").resolve()
    # a folder of someone else's is never replaced; ours is
    other = tmp_path / "photos"
    other.mkdir()
    (other / "cat.jpg").write_bytes(b"\xff\xd8")
    refused = CliRunner().invoke(main, ["validate", str(folder / "maze.yaml"), "--skip-sim", "--html", str(other)])
    assert refused.exit_code == 2 and "not a worldgen report (cat.jpg" in refused.output and (other / "cat.jpg").exists()
    again = CliRunner().invoke(main, ["validate", str(folder / "maze.yaml"), "--skip-sim", "--html", str(report)])
    assert again.exit_code == 0 and sorted(f.suffix for f in (report / "pages").iterdir()) == [".html", ".js"]


def test_every_robot_of_a_launch_file_is_drawn(tmp_path):
    runner = CliRunner()
    assert runner.invoke(main, ["build", str(EXAMPLES / "enclosed_room.yaml"), "-o", str(tmp_path)]).exit_code == 0
    text = (EXAMPLES / "two_robots.launch").read_text(encoding="utf-8")
    text = text.replace("$(find class_meeting_02_custom_gazebo_world)/worlds/enclosed_room.world",
                        str(tmp_path / "enclosed_room.world"))
    launch = tmp_path / "two.launch"
    launch.write_text(text, encoding="utf-8")
    data = page_data(world_page(launch))
    assert data["robot"]["spawn"] == [-1.0, 0.0, 3.142]
    assert [(o["ns"], o["model"], o["spawn"]) for o in data["others"]] == [("/tb3_1", "burger", [1.0, 0.0, 0.0])]


def test_a_drive_replay_puts_contacts_at_the_exercise_s_time():
    """The exercise's series count from its start, the session's contacts from before the settling: the replay
    puts a contact where the robot was when it happened."""
    from worldgen.view.replay import drive_replay

    times = [i / 5 for i in range(51)]
    run = {"series": {"t": times, "x": [min(t, 4.0) * 0.2 for t in times], "y": [0.0] * 51, "yaw": [0.0] * 51,
                      "true": [1.0] * 51, "v_cmd": [0.2] * 51, "w_cmd": [0.0] * 51},
           "contacts": [{"link": "base_link", "shape": "Wall_1", "time": 4.5, "depth": 0.001}], "start_t": 0.5}
    replay = drive_replay({"behaviour": "stop-at-wall", "runs": [run]})
    contact = replay["contacts"][0]
    assert contact["t"] == 4.0 and contact["x"] == pytest.approx(0.8)


def test_a_spin_replay_shows_the_stop_it_commanded(tmp_path):
    from worldgen.check.drive_targets import drive_one
    from worldgen.sim.exercise import Exercise
    from worldgen.view.replay import drive_replay

    exercise = Exercise(behaviour="spin", duration=2.0, omega=1.5, record_scans=True)
    result = drive_one(EXAMPLES / "enclosed_room.yaml", "spec", exercise, ())
    replay = drive_replay(result)
    turning = [w for t, w in zip(replay["t"], replay["w"]) if t < 1.9]
    stopping = [w for t, w in zip(replay["t"], replay["w"]) if t > 2.05]
    assert set(turning) == {1.5} and stopping and set(stopping) == {0.0}
    assert replay["scans"]["o"][-1][2] != replay["scans"]["o"][0][2]   # the scans turn with the robot


def test_html_needs_three_js_before_anything_runs(tmp_path, monkeypatch):
    import worldgen.view.vendor as vendor

    monkeypatch.setattr(vendor, "FOLDER", tmp_path / "no-three")
    runner = CliRunner()
    for args in (["validate", str(EXAMPLES / "maze.yaml"), "--html", str(tmp_path / "r")],
                 ["drive", str(EXAMPLES / "maze.yaml"), "--html", str(tmp_path / "d.html")],
                 ["view", str(EXAMPLES / "maze.yaml"), "-o", str(tmp_path / "v.html")]):
        result = runner.invoke(main, args)
        assert result.exit_code == 2 and "three.js is missing" in result.output, result.output
        assert "Traceback" not in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_a_report_never_replaces_other_files_and_links_each_row_to_its_own_page(tmp_path):
    runner = CliRunner()
    site = tmp_path / "site"
    assert runner.invoke(main, ["view", str(EXAMPLES / "maze.yaml"), "-o", str(site / "index.html")]).exit_code == 0
    (site / "notes.txt").write_text("mine", encoding="utf-8")
    refused = runner.invoke(main, ["validate", str(EXAMPLES / "maze.yaml"), "--skip-sim", "--html", str(site)])
    assert refused.exit_code == 2 and "not a worldgen report" in refused.output
    assert sorted(p.name for p in site.iterdir()) == ["index.html", "notes.txt"]
    report = tmp_path / "report"
    twice = [str(EXAMPLES / "maze.yaml"), str(EXAMPLES / "maze.yaml")]
    assert runner.invoke(main, ["validate", *twice, "--skip-sim", "--html", str(report)]).exit_code == 0
    rows = json.loads(lxml_html.fromstring((report / "index.html").read_bytes()).get_element_by_id("worldgen-index").text)
    assert len({r["href"] for r in rows}) == 2 and all((report / r["href"]).is_file() for r in rows)
    (report / "pages" / "stray.txt").write_text("x", encoding="utf-8")
    again = runner.invoke(main, ["validate", str(EXAMPLES / "maze.yaml"), "--skip-sim", "--html", str(report)])
    assert again.exit_code == 2 and "stray.txt" in again.output
