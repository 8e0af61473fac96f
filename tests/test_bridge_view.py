"""``run --html``: a real student node on the simulated robot (a real rosmaster, real rospy), the run replayed in a
page that a real headless chromium plays; and a class graded with ``run FOLDER --html DIR``, whose index lists
every submission with its verdict and links to each one's replay."""

from __future__ import annotations

import json
import os
import shutil
import uuid

import pytest
from lxml import html as lxml_html

from bridgetools import NODES, need_ros, no_leftovers
from browserpage import open_page
from conftest import EXAMPLES, REPO, CliRunner
from viewpixels import wait_ready
from worldgen.cli import main
from worldgen.packages.course_ros1 import write_course


def _data(page_file) -> dict:
    return json.loads(lxml_html.fromstring(page_file.read_bytes()).get_element_by_id("worldgen-data").text)


@pytest.fixture()
def course(tmp_path, monkeypatch):
    """The class's packages, in a test whose ROS processes carry a tag of their own (none may be left over)."""
    need_ros()
    tag = f"WORLDGEN_TEST_TAG={uuid.uuid4().hex}"
    monkeypatch.setenv(*tag.split("="))
    monkeypatch.setenv("ROS_HOME", str(tmp_path / "ros_home"))
    yield write_course(tmp_path / "course")
    no_leftovers(tag)


def test_a_real_run_is_replayed_where_the_robot_went(chromium, tmp_path, course):
    node = course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py"
    page_file = tmp_path / "run.html"
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "enclosed_room.yaml"), str(node), "--task",
                                       "stop-at-wall", "--rate", "max", "--duration", "15", "--format", "json",
                                       "--html", str(page_file)])
    assert result.exit_code == 0, result.output
    report = json.loads(result.stdout)
    replay = _data(page_file)["replay"]
    final = report["metrics"]["final_pose"]
    assert (replay["x"][-1], replay["y"][-1]) == pytest.approx(tuple(final[:2]), abs=0.01)
    assert replay["t"][-1] == pytest.approx(15.0, abs=0.1) and len(replay["scans"]["t"]) >= 70
    front = report["metrics"]["final_front_distance_m"]
    assert replay["d"][-1] == pytest.approx(front, abs=0.01)
    with open_page(chromium, page_file) as probe:
        page = probe.page
        wait_ready(page)
        assert "stop-at-wall: pass" in page.inner_text("#side")
        if os.environ.get("WORLDGEN_DOCS") == "1":   # the README's screenshot: the robot half-way to the wall
            page.evaluate("window.worldgen.seek(5.5)")
            page.screenshot(path=str(REPO / "docs" / "view_replay.png"))
        page.select_option("#speed", "16")
        page.click("#btn-play")
        page.wait_for_function("() => !window.worldgen.playing()", timeout=15000)
        end = page.evaluate("window.worldgen.robot()")
        assert (end["x"], end["y"]) == pytest.approx(tuple(final[:2]), abs=0.01)
        assert probe.console_errors == [] and probe.left_file == []


def test_a_graded_class_has_an_index_with_every_verdict(chromium, tmp_path, course):
    subs = tmp_path / "submissions"
    runner = CliRunner()
    for name in ("alice", "bob", "carol"):
        result = runner.invoke(main, ["scaffold", f"{name}_lab", "rospy", "geometry_msgs", "sensor_msgs", "-p",
                                      str(subs)])
        assert result.exit_code == 0, result.output
    shutil.copy(course / "lab_a_stop_at_wall" / "scripts" / "stop_at_wall.py", subs / "alice_lab" / "scripts")
    shutil.copy(NODES / "drive_into_wall.py", subs / "bob_lab" / "scripts" / "stop_at_wall.py")
    report = tmp_path / "report"
    result = runner.invoke(main, ["run", str(subs), "--task", "stop-at-wall", "-j", "2", "--rate", "max",
                                  "--duration", "15", "--format", "json", "--html", str(report)])
    assert result.exit_code == 1 and "Traceback" not in result.output, result.output
    verdicts = {r["path"].rstrip("/").rsplit("/", 1)[-1]: "ok" if r["ok"] else "FAIL"
                for r in json.loads(result.stdout)["results"]}
    assert verdicts == {"alice_lab": "ok", "bob_lab": "FAIL", "carol_lab": "FAIL"}
    with open_page(chromium, report / "index.html") as probe:
        page = probe.page
        rows = page.eval_on_selector_all("tr[data-name]", "rows => rows.map(r => [r.dataset.name, r.dataset.verdict])")
        assert {name.rstrip("/").rsplit("/", 1)[-1]: v for name, v in rows} == verdicts
        links = page.eval_on_selector_all("tr[data-name] a[href]", "links => links.map(a => a.getAttribute('href'))")
        assert len(links) == 2   # carol's node never ran: a row without a replay
        assert probe.console_errors == [] and probe.left_file == []
    bob = next(report / link for link in links if "bob" in link)
    replay = _data(bob)["replay"]
    assert replay["contacts"], "bob's robot drove into the wall: the replay marks the contact"
    with open_page(chromium, bob) as probe:
        wait_ready(probe.page)
        assert "touched" in probe.page.inner_text("#side")
        probe.page.click("a.back")   # back to the class
        probe.page.wait_for_selector("tr[data-name]")
        assert probe.console_errors == [] and probe.left_file == []
