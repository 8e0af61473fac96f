"""The 3D pages in a real headless browser (Debian's chromium through Playwright): they load from the file alone,
without a console error; the top view has wall pixels exactly where ``preview``'s geometry puts walls and the robot
where it spawns; hovering names what is under the pointer; pressing play moves the robot along the recorded path.

With ``WORLDGEN_DOCS=1`` the world page's test also writes the README's screenshot into docs/ (the replay's is
written by tests/test_bridge_view.py, from a real run).
"""

from __future__ import annotations

import math
import os
import types
from pathlib import Path

import numpy as np
import pytest

from browserpage import open_page
from conftest import EXAMPLES, REPO
from viewpixels import (DOOR, ROBOT, WALL_CUT, WINDOW, canvas_pixels, colour_mask, geometry_mask, pixel_centres, ring_share,
                        top_view, wait_ready, world_to_pixel)

DOCS = REPO / "docs"


def _docs_shot(page, name: str) -> None:
    if os.environ.get("WORLDGEN_DOCS") == "1":
        page.screenshot(path=str(DOCS / name))


def _preview_walls(path: Path, model_paths=()):
    """The walls' footprint as ``worldgen preview`` fills it (its picture's wall shapes, cut in the robot's band)."""
    import shapely

    from worldgen.geometry.placement import SLICE_Z
    from worldgen.geometry.slices import footprints_between
    from worldgen.view.preview import picture

    pic = picture(path, model_paths)
    prints = [p.geometry for p in footprints_between(pic.scene, *SLICE_Z) if p.label in pic.walls]
    return shapely.union_all(prints)


def _assert_walls_match(pixels, frame, walls, exclude=None) -> None:
    """Every pixel well inside a wall is wall-coloured (but where a window is drawn over it, as preview does), and
    every wall-coloured pixel is at a wall (1.5 px of anti-aliasing allowed at the edges)."""
    xs, ys = pixel_centres(pixels.shape, frame)
    px = frame["perPixel"]
    drawn = colour_mask(pixels, WALL_CUT)
    if exclude is not None:
        drawn &= ~exclude
    openings = colour_mask(pixels, DOOR, 20) | colour_mask(pixels, WINDOW, 20)
    inside = geometry_mask(walls.buffer(-1.5 * px), xs, ys) & ~openings
    near = geometry_mask(walls.buffer(1.5 * px), xs, ys)
    assert inside.sum() > 500, "the walls should cover some of the picture"
    assert drawn[inside].mean() > 0.99, f"{(~drawn[inside]).sum()} of {inside.sum()} wall pixels are not drawn"
    assert near[drawn].mean() > 0.99, f"{(~near[drawn]).sum()} wall-coloured pixels are not at a wall"


def _assert_robot_at(pixels, frame, x: float, y: float, yaw: float, radius: float) -> None:
    """The red ring is round the pose, and its arrow points along the yaw."""
    xs, ys = pixel_centres(pixels.shape, frame)
    red = colour_mask(pixels, ROBOT, tolerance=24)
    assert red.sum() > 100, "no robot drawn"
    assert ring_share(red, xs, ys, (x, y), radius) > 0.7
    d = np.hypot(xs - x, ys - y)
    arrow = red & (d > radius + 0.06)
    heading = math.atan2(np.sin(np.arctan2(ys[arrow] - y, xs[arrow] - x)).mean(),
                         np.cos(np.arctan2(ys[arrow] - y, xs[arrow] - x)).mean())
    assert abs(math.remainder(heading - yaw, 2 * math.pi)) < math.radians(12), (heading, yaw)


def _write_world_page(tmp_path, source: Path, **kwargs) -> Path:
    from worldgen.view.page import world_page

    out = tmp_path / f"{source.stem}.html"
    out.write_bytes(world_page(source, **kwargs))
    return out


def test_a_spec_page_draws_its_walls_and_robot_where_preview_does(chromium, tmp_path):
    from worldgen.geometry.placement import robot_radius

    page_file = _write_world_page(tmp_path, EXAMPLES / "two_rooms.yaml")
    with open_page(chromium, page_file, viewport=(1100, 800)) as probe:
        wait_ready(probe.page)
        _docs_shot(probe.page, "view_world.png")
        pixels, frame = top_view(probe.page)
        _assert_walls_match(pixels, frame, _preview_walls(EXAMPLES / "two_rooms.yaml"))
        _assert_robot_at(pixels, frame, -1.0, 0.0, math.pi / 2, robot_radius("waffle"))
        # hovering: the door in the shared wall (x = 2), then the west room's floor
        box = probe.page.locator("#view canvas").bounding_box()
        for (x, y), expected in (((2.0, 0.0), "door 0.90 m wide"), ((0.5, 1.2), "room 'west'")):
            left, top = world_to_pixel(x, y, pixels.shape, frame)
            probe.page.mouse.move(box["x"] + left, box["y"] + top)
            assert expected in probe.page.inner_text("#tooltip")
        assert probe.console_errors == [] and probe.left_file == []


def test_a_real_world_with_meshes_opens_offline(chromium, tmp_path, corpus):
    world = corpus / "worlds" / "ROBOTIS-GIT__turtlebot3_simulations@noetic-devel__turtlebot3_gazebo_worlds_turtlebot3_world.world"
    models = (corpus / "models", corpus / "gazebo_models")
    page_file = _write_world_page(tmp_path, world, spawn=(-2.0, -0.5, 0.0), model_paths=models)
    assert b'"k":"mesh"' in page_file.read_bytes()   # its meshes go through glTF
    with open_page(chromium, page_file) as probe:
        wait_ready(probe.page)
        pixels, frame = top_view(probe.page)
        _assert_walls_match(pixels, frame, _preview_walls(world, models))
        _assert_robot_at(pixels, frame, -2.0, -0.5, 0.0, 0.148)
        assert probe.console_errors == [] and probe.left_file == []


# ---------------------------------------------------------------------------------------------- the replay
def _trace() -> dict:
    """10 s at 30 Hz: 6 s straight along +x at 0.15 m/s from (−1, 0), then a quarter turn in place in 4 s; a
    scan every 0.2 s whose beams all read 1 m; a contact at 5 s."""
    odom, ranges = [], []
    for i in range(301):
        t = i / 30
        x = -1.0 + 0.15 * min(t, 6.0)
        yaw = 0.0 if t <= 6.0 else (t - 6.0) / 4.0 * (math.pi / 2)
        odom.append([t, x, 0.0, yaw, 0.15 if t < 6 else 0.0, 0.0 if t < 6 else math.pi / 8,
                     0.15 if t < 6 else 0.0, 0.0 if t < 6 else math.pi / 8])
        if i % 6 == 0:
            ranges.append([round(t, 3), round(x - 0.032, 4), 0.0, round(yaw, 4), [1000] * 360])
    scans = [[r[0], 1.0, 1.0, 1.0, 0.8] for r in ranges]
    return {"odom": odom, "scans": scans, "contacts": [{"link": "base_link", "shape": "wall", "time": 5.0,
                                                        "depth": 0.001}],
            "lidar": {"angle_min": 0.0, "angle_increment": 2 * math.pi / 360, "range_min": 0.12, "range_max": 3.5,
                      "count": 360}, "ranges": ranges}


def _pose_at(trace: dict, t: float) -> tuple[float, float, float]:
    odom = trace["odom"]
    i = max(k for k in range(len(odom)) if odom[k][0] <= t)
    j = min(i + 1, len(odom) - 1)
    f = 0.0 if j == i else (t - odom[i][0]) / (odom[j][0] - odom[i][0])
    return tuple(odom[i][k] + f * (odom[j][k] - odom[i][k]) for k in (1, 2, 3))


def _replay_file(tmp_path, trace: dict) -> Path:
    from worldgen.check.report import Result
    from worldgen.check.sources import load_scene
    from worldgen.core.findings import Finding
    from worldgen.view.grades import run_page

    spec = EXAMPLES / "enclosed_room.yaml"
    scene, _ = load_scene(spec, "spec")
    world = types.SimpleNamespace(path=spec, scene=scene, spawn=(-1.0, 0.0, 0.0), robot="burger")
    result = Result(path="submissions/ada", checks=["node", "stop-at-wall"],
                    findings=[Finding("stop-at-wall", "error", "the robot touched the wall at 5.0 s")],
                    metrics={"final_front_distance_m": 0.31, "contacts": 1, "sim_seconds": 10.0})
    out = tmp_path / "replay.html"
    out.write_bytes(run_page(result, world, trace))
    return out


def test_play_moves_the_robot_along_the_recorded_path(chromium, tmp_path):
    trace = _trace()
    page_file = _replay_file(tmp_path, trace)
    with open_page(chromium, page_file, viewport=(1100, 850)) as probe:
        page = probe.page
        wait_ready(page)
        start = page.evaluate("window.worldgen.robot()")
        assert (start["x"], start["y"]) == pytest.approx((-1.0, 0.0), abs=1e-6)
        assert "the robot touched the wall" in page.inner_text("#side")
        page.select_option("#speed", "4")
        page.click("#btn-play")
        page.wait_for_function("() => window.worldgen.time() > 2.5")
        page.click("#btn-play")   # pause
        t = page.evaluate("window.worldgen.time()")
        assert not page.evaluate("window.worldgen.playing()")
        at = page.evaluate("window.worldgen.robot()")
        x, y, yaw = _pose_at(trace, t)
        assert (at["x"], at["y"], at["yaw"]) == pytest.approx((x, y, yaw), abs=0.01)
        assert at["x"] - start["x"] > 0.3
        page.select_option("#speed", "16")
        page.click("#btn-play")
        page.wait_for_function("() => !window.worldgen.playing()", timeout=10000)
        end = page.evaluate("window.worldgen.robot()")
        assert (end["x"], end["y"], end["yaw"]) == pytest.approx(tuple(trace["odom"][-1][1:4]), abs=0.01)
        page.click("#btn-rays")   # the scan's rays off: they are drawn over the robot's ring
        pixels, frame = top_view(page)   # the picture agrees: the ring is round the last pose
        _assert_robot_at(pixels, frame, end["x"], end["y"], end["yaw"], 0.148)
        assert probe.console_errors == [] and probe.left_file == []


def test_the_slider_seeks_and_the_scan_follows(chromium, tmp_path):
    trace = _trace()
    page_file = _replay_file(tmp_path, trace)
    with open_page(chromium, page_file) as probe:
        page = probe.page
        wait_ready(page)
        page.evaluate("(() => { const s = document.getElementById('slider'); s.value = '3';"
                      " s.dispatchEvent(new Event('input')); })()")
        at = page.evaluate("window.worldgen.robot()")
        assert at["x"] == pytest.approx(_pose_at(trace, 3.0)[0], abs=0.005)
        assert "3.00 s" in page.inner_text("#clock")
        pixels, frame = top_view(page)
        green = colour_mask(pixels, (0x2C, 0xA0, 0x2C), tolerance=60) & ~colour_mask(pixels, (0xA0, 0xA0, 0xA0), 30)
        xs, ys = pixel_centres(pixels.shape, frame)
        d = np.hypot(xs[green] - (at["x"] - 0.032), ys[green] - at["y"])
        assert green.sum() > 200 and d.max() < 1.05   # every beam read 1 m: the rays end on a 1 m circle
        assert probe.console_errors == []


def test_pages_work_without_the_page_data_reaching_outside(chromium, tmp_path):
    """A hostile world name cannot run script in the page: the data is inert JSON."""
    world = tmp_path / "evil.world"
    world.write_text(
        '<sdf version="1.6"><world name="x&lt;/script&gt;&lt;script&gt;window.pwned=1&lt;/script&gt;">'
        '<model name="&lt;img src=x onerror=window.pwned=2&gt;"><static>true</static><link name="l">'
        '<collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>'
        '<visual name="v"><geometry><box><size>1 1 1</size></box></geometry></visual></link></model>'
        '</world></sdf>', encoding="utf-8")
    page_file = _write_world_page(tmp_path, world)
    with open_page(chromium, page_file) as probe:
        wait_ready(probe.page)
        assert probe.page.evaluate("window.pwned === undefined")
        assert "</script><script>" in probe.page.inner_text("h1")
        assert probe.console_errors == [] and probe.left_file == []


def test_a_run_that_never_moved_shows_the_robot_at_its_spawn(chromium, tmp_path):
    """A node that never started leaves a trace without odometry: the page stands the robot at its spawn."""
    page_file = _replay_file(tmp_path, {"odom": [], "scans": [], "contacts": []})
    with open_page(chromium, page_file) as probe:
        wait_ready(probe.page)
        at = probe.page.evaluate("window.worldgen.robot()")
        assert (at["x"], at["y"], at["yaw"]) == pytest.approx((-1.0, 0.0, 0.0))
        probe.page.click("#btn-play")
        assert probe.console_errors == [] and probe.left_file == []


# ------------------------------------------------------------------------------ what the campaign found (issue 25)
PATH = (0x1F, 0x77, 0xB4)   # the replay's path (templates/view/page.js)


def _lap_of_the_track() -> dict:
    """One lap of examples/line_track.yaml's tape from the robot's spawn at 0.15 m/s, odometry at 30 Hz."""
    import yaml

    tape = yaml.safe_load((EXAMPLES / "line_track.yaml").read_text(encoding="utf-8"))["lines"][0]["points"]
    points = [(0.0, -0.85), *map(tuple, tape), (0.0, -0.85)]
    odom, t = [], 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        steps = max(1, round(math.hypot(x1 - x0, y1 - y0) / 0.15 * 30))
        yaw = math.atan2(y1 - y0, x1 - x0)
        for k in range(steps):
            f = k / steps
            odom.append([t, x0 + f * (x1 - x0), y0 + f * (y1 - y0), yaw, 0.15, 0.0, 0.15, 0.0])
            t += 1 / 30
    return {"odom": odom, "scans": [], "contacts": []}


def _shares_round(mask) -> list:
    """The shares of ``mask``'s pixels left, right, above and below their centroid."""
    rows, cols = np.nonzero(mask)
    return [float(np.mean(cols < cols.mean())), float(np.mean(cols > cols.mean())),
            float(np.mean(rows < rows.mean())), float(np.mean(rows > rows.mean()))]


@pytest.mark.parametrize("viewport", [(1000, 800), (1400, 900)])
def test_a_line_track_replay_opens_with_the_robot_and_its_path_in_sight(chromium, tmp_path, viewport):
    """The line track's walls are taller than the robot is far from them: from the default side the near wall hid
    the robot and the tape (no red pixel at all); the page picks a side and a height from which they are seen."""
    from worldgen.check.report import Result
    from worldgen.check.sources import load_scene
    from worldgen.view.grades import run_page

    spec = EXAMPLES / "line_track.yaml"
    scene, _ = load_scene(spec, "spec")
    world = types.SimpleNamespace(path=spec, scene=scene, spawn=(0.0, -0.85, 0.0), robot="waffle_pi")
    page_file = tmp_path / "line.html"
    page_file.write_bytes(run_page(Result(path="subs/ada", checks=["node", "line-follow"]), world,
                                   _lap_of_the_track()))
    with open_page(chromium, page_file, viewport=viewport) as probe:
        wait_ready(probe.page)
        assert not probe.page.evaluate("window.worldgen.frame().top")   # the first frame: the 3D view
        pixels = canvas_pixels(probe.page)
        ring = colour_mask(pixels, ROBOT, tolerance=24)
        path = colour_mask(pixels, PATH, tolerance=30)
        print(f"\n{viewport}: {ring.sum()} robot pixels, {path.sum()} path pixels")
        assert ring.sum() > 100 and min(_shares_round(ring)) > 0.2   # the ring, all round
        assert path.sum() > 100 and min(_shares_round(path)) > 0.2    # the lap, all round
        assert probe.console_errors == [] and probe.left_file == []


def _policy(page_bytes: bytes) -> str:
    from lxml import html as lxml_html

    return lxml_html.fromstring(page_bytes).xpath("//meta[@http-equiv='Content-Security-Policy']/@content")[0]


def test_a_report_folder_shares_one_three_js_and_its_pages_open_offline(chromium, tmp_path):
    """A folder report writes three.js once, beside its pages, and each page loads it from there (opened from
    file://, every request off the disk refused); a page taken out of its folder says why it cannot start; a single
    page (view -o, run --html FILE) still holds its own copy."""
    from worldgen.check.report import Result
    from worldgen.check.sources import load_scene
    from worldgen.view.grades import BACK, LIBRARY, PAGES, run_page, validate_page, write_report
    from worldgen.view.page import world_page

    spec = EXAMPLES / "enclosed_room.yaml"
    scene, _ = load_scene(spec, "spec")
    world = types.SimpleNamespace(path=spec, scene=scene, spawn=(-1.0, 0.0, 0.0), robot="burger")
    trace = _trace()
    results = [Result(path=str(EXAMPLES / "two_rooms.yaml"), robot="waffle"), Result(path=str(spec)),
               Result(path="subs/ada", checks=["node", "stop-at-wall"])]
    report = write_report(tmp_path / "report", results, lambda r: (
        run_page(r, world, trace, back=BACK) if r.path == "subs/ada" else validate_page(r)), "a class")
    pages = sorted((report / PAGES).glob("*.html"))
    shared = report / PAGES / LIBRARY
    assert len(pages) == 3 and sorted(p.name for p in (report / PAGES).iterdir() if p.suffix != ".html") == [LIBRARY]
    assert shared.stat().st_size > 800_000 and max(p.stat().st_size for p in pages) < 200_000
    for page in pages:
        text = page.read_bytes()
        assert b'<script src="three.js"></script>' in text and b'id="lib-three"' not in text
        sources = _policy(text).split("script-src ", 1)[1].split(";")[0].split()
        assert len(sources) == 3 and sources[0].startswith("'sha256-") and sources[1:] == ["'self'", "blob:"]
    world_file = next(p for p in pages if "two_rooms" in p.name)
    with open_page(chromium, world_file, viewport=(1100, 800)) as probe:
        wait_ready(probe.page)
        pixels, frame = top_view(probe.page)
        _assert_walls_match(pixels, frame, _preview_walls(EXAMPLES / "two_rooms.yaml"))
        assert probe.console_errors == [] and probe.left_file == []
    with open_page(chromium, next(p for p in pages if "ada" in p.name)) as probe:
        wait_ready(probe.page)
        assert probe.page.evaluate("window.worldgen.robot()")["x"] == pytest.approx(-1.0, abs=1e-6)
        assert probe.console_errors == [] and probe.left_file == []
    alone = tmp_path / "alone.html"   # a page mailed without its folder
    alone.write_bytes(world_file.read_bytes())
    with open_page(chromium, alone) as probe:
        probe.page.wait_for_function("document.getElementById('status').textContent.includes('could not start')")
        assert "keep this page in its folder" in probe.page.inner_text("#status") and probe.left_file == []
    for single in (world_page(EXAMPLES / "two_rooms.yaml"), run_page(results[2], world, trace)):
        assert b'id="lib-three"' in single and b"<script src=" not in single and "'self'" not in _policy(single)
