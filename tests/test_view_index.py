"""The index page of a folder's grades: a row per submission with its verdict, the numbers that matter for what
was graded, its findings and a link to its own page; escaped, deterministic, self-contained and sortable (the last
in headless chromium, when it and Playwright are installed: see browserpage.py)."""

from __future__ import annotations

import base64
import hashlib
import json
import re

import lxml.html
import pytest
from browserpage import open_page

from worldgen.check.report import Result
from worldgen.core.findings import Finding
from worldgen.view.index import index_page, index_rows

HOSTILE = "subs/<script>alert(1)</script>\"&'/x"

# ------------------------------------------------------------------------------------------------- results
# Shaped as `worldgen validate … --format json` and `worldgen run FOLDER --task …` give them (check/checks.py,
# check/validate.py, bridge/metrics.py, bridge/rubrics.py, bridge/grade.py).

VALIDATE_CHECKS = ["parse", "enclosed", "spawn-clear", "settle", "lidar", "spin", "stop-at-wall"]


def validate_metrics(clearance: float, **more) -> dict:
    metrics = {"sdf_version": "1.6", "shapes": 5, "shape_kinds": {"box": 4, "plane": 1}, "models": 2,
               "floor_height_m": 0.0, "floor": None, "enclosed": True, "slice_height_m": 0.182, "gaps": [],
               "enclosed_area_m2": 23.5128, "enclosed_bounds": [-2.4245, -2.4245, 2.4245, 2.4245],
               "nearest_wall_m": 2.425, "min_clearance_m": clearance,
               "nearest_obstacle": "enclosed_room/Wall_3/Wall_3_Collision", "turn_clearance_m": 2.3013,
               "settle_tilt_deg": 0.2978, "settle_height_m": 0.0, "settle_moved_m": 0.0, "lidar_beams": 360,
               "lidar_no_hit_beams": 0, "lidar_no_hit_value": "inf", "lidar_no_hit_reading": "inf",
               "lidar_nearest_m": 2.3922, "lidar_nearest_bearing_deg": 179.4987, "lidar_farthest_m": 3.424,
               "lidar_front_no_hit": False, "spin_drift_m": 0.0162, "spin_turned_rad": 6.285, "spin_touched": [],
               "stop_distance_m": 0.5202, "stop_touched": [], "stop_time_s": 23.6, "stop_target_m": 0.5,
               "stop_heading_deg": -0.1768, "sim_seconds": 29.3}
    metrics.update(more)
    return metrics


def validated(path: str, clearance: float = 2.323, findings=(), **more) -> Result:
    return Result(path=path, spawn=(0.0, 0.0, 0.0), spawn_source=f"from spec {path}", robot="burger",
                  robot_source=f"from spec {path}", findings=list(findings), metrics=validate_metrics(clearance, **more),
                  checks=list(VALIDATE_CHECKS))


OPEN_GAP = {"centre": [0.75, -2.5], "width": 0.5, "ends": [[0.5, -2.5], [1.0, -2.5]],
            "between": ["open_room/Wall_0/Wall_0_Collision_0", "open_room/Wall_0/Wall_0_Collision_2"],
            "robot_passes": True}
OPEN_FINDING = Finding("enclosed", "error", "the room is open: a 0.50 m gap at (0.75, -2.50) in room 'main'; the "
                                            "burger (0.178 m wide) can drive out through it",
                       where="gap from (0.50, -2.50) to (1.00, -2.50)",
                       fix="close the gap (join the walls there, or remove the opening), or move the spawn into a "
                           "closed room")
LIDAR_NOTE = Finding("lidar", "info", "10 of 360 beams see nothing within 3.5 m and read inf")
LIDAR_WARNING = Finding("lidar", "warning", "90 of 360 beams see nothing within 3.5 m and read inf",
                        fix="handle the readings that see nothing")


def run_metrics(front, path: float, contacts=(), **task) -> dict:
    metrics = {"cmd_vel_messages": 412, "first_cmd_vel_s": 0.1, "path_length_m": path, "rotation_rad": 0.01,
               "final_pose": [path, 0.0, 0.0], "final_speed_mps": 0.0, "final_front_distance_m": front,
               "min_clearance_m": 0.41, "contacts": list(contacts), "sim_time_s": 20.0, "real_time_factor": 3.2}
    metrics.update(task)
    metrics["node"] = "scripts/stop_at_wall.py"
    return metrics


def ran(path: str, front, path_m: float, findings=(), contacts=()) -> Result:
    return Result(path=path, spawn=(0.0, 0.0, 0.0), spawn_source="from spec enclosed_room.yaml", robot="burger",
                  findings=list(findings), checks=["node", "stop-at-wall"],
                  metrics=run_metrics(front, path_m, contacts, stop_error_m=None if front is None else front - 0.5))


CONTACT = {"link": "base_link", "shape": "enclosed_room/Wall_1/Wall_1_Collision", "time": 8.2}


def class_runs() -> list[Result]:
    return [
        ran("subs/alice", 0.52, 1.83),
        ran("subs/bob", 0.81, 1.54, findings=[Finding("stop-at-wall", "error", "stopped 0.81 m from the wall "
                                                      "ahead, 0.31 m short of the 0.5 m target (±0.1 m)")]),
        ran("subs/carol", None, 2.32, contacts=[CONTACT],
            findings=[Finding("stop-at-wall", "error", "the robot touched enclosed_room/Wall_1/Wall_1_Collision "
                                                       "with base_link at t = 8.2 s",
                              fix="slow down earlier, or keep more distance")]),
        Result(path="subs/dave", robot="burger", spawn=(0.0, 0.0, 0.0), checks=["runtime"],
               findings=[Finding("runtime", "error", "imports cv2, which is not installed",
                                 where="scripts/stop_at_wall.py:3", fix="pip install opencv-python")],
               skipped={"stop-at-wall": "the nodes could not start: modules they import are missing"},
               metrics={"node": "scripts/stop_at_wall.py"}),
        Result(path="subs/erin", robot="burger", spawn=(0.0, 0.0, 0.0), checks=["node"],
               findings=[Finding("node", "error", "cannot tell which node to run: no stop_at_wall.py, and 2 "
                                                  "Python files", where="subs/erin")],
               skipped={"stop-at-wall": "the node could not run"}),
    ]


def parse(page: bytes):
    return lxml.html.document_fromstring(page.decode("utf-8"))


def embedded(doc) -> list[dict]:
    return json.loads(doc.get_element_by_id("worldgen-index").text)


def header_labels(doc) -> list[str]:
    return [th.find("button").text_content() for th in doc.xpath("//table[@id='grades']/thead/tr/th")]


def cell(doc, name: str, label: str):
    """The cell of submission ``name`` in the column headed ``label``."""
    column = header_labels(doc).index(label)
    row = [tr for tr in doc.xpath("//tr[@data-name]") if tr.get("data-name") == name]
    assert len(row) == 1, name
    return row[0].findall("td")[column]


# -------------------------------------------------------------------------------------------------- rows

def test_a_row_per_result_in_order_with_its_verdict_and_counts():
    results = class_runs() + [validated("worlds/a.world"), validated("worlds/b.world", findings=[LIDAR_WARNING])]
    rows = index_rows(results)
    assert [r["name"] for r in rows] == [r.name for r in results]
    assert [r["verdict"] for r in rows] == ["ok", "FAIL", "FAIL", "FAIL", "FAIL", "ok", "warn"]
    assert [r["kind"] for r in rows] == ["run"] * 5 + ["validate"] * 2
    assert [r["task"] for r in rows] == ["stop-at-wall"] * 5 + [None] * 2
    assert [(r["errors"], r["warnings"], r["notes"]) for r in rows] == [
        (0, 0, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0), (0, 0, 0), (0, 1, 0)]
    assert rows[3]["skipped"] == {"stop-at-wall": "the nodes could not start: modules they import are missing"}
    json.dumps(rows)   # plain data


def test_a_run_row_holds_the_tasks_measures_as_numbers():
    alice, bob, carol, dave, erin = index_rows(class_runs())
    labels = [m["label"] for m in alice["metrics"]]
    assert labels == ["front distance", "stop error", "contacts", "min clearance", "path", "sim time", "cmd_vel msgs",
                      "node"]
    by = {m["label"]: m for m in alice["metrics"]}
    assert by["front distance"] == {"key": "final_front_distance_m", "label": "front distance", "value": 0.52,
                                    "unit": "m", "text": "0.52 m"}
    assert by["stop error"]["value"] == pytest.approx(0.02) and by["stop error"]["text"] == "+0.02 m"
    assert by["contacts"]["value"] == 0 and by["sim time"]["text"] == "20.0 s"
    assert by["node"]["value"] == "scripts/stop_at_wall.py"
    carol_by = {m["label"]: m for m in carol["metrics"]}
    assert carol_by["contacts"]["value"] == 1
    assert carol_by["front distance"]["value"] is None and carol_by["front distance"]["text"] == "–"
    # a run that never started has what it has, and nothing made up
    assert [(m["label"], m["value"]) for m in dave["metrics"]] == [("node", "scripts/stop_at_wall.py")]
    assert erin["metrics"] == []


def test_other_tasks_show_their_own_measures():
    line = Result(path="subs/fay", checks=["node", "line-follow"],
                  metrics=run_metrics(1.2, 7.5, share_on_line=0.9312, laps=1.21, covered=1.0, worst_distance_m=0.14,
                                      tape_length_m=6.2, camera_floor_distance_m=0.3))
    spin = Result(path="subs/gus", checks=["node", "spin"],
                  metrics=run_metrics(2.0, 0.2, turns=2.5, centre_drift_m=0.03))
    square = Result(path="subs/hal", checks=["node", "drive-square"],
                    metrics=run_metrics(1.0, 4.0, sides_m=[1.0, 1.02, 0.98, 1.0], corners_deg=[90.0, 88.0, 91.0],
                                        closing_gap_m=0.05))
    follow = Result(path="subs/ida", checks=["node", "wall-follow"],
                    metrics=run_metrics(0.6, 6.0, share_in_band=0.85, travelled_m=5.1, room_side_m=4.2))
    rows = index_rows([line, spin, square, follow])
    values = [{m["label"]: m["value"] for m in r["metrics"]} for r in rows]
    texts = [{m["label"]: m["text"] for m in r["metrics"]} for r in rows]
    assert values[0]["on line"] == pytest.approx(93.12) and texts[0]["on line"] == "93%"
    assert values[0]["laps"] == 1.21 and values[0]["covered"] == 100.0 and values[0]["worst off line"] == 0.14
    assert values[1]["turns"] == 2.5 and values[1]["centre drift"] == 0.03
    assert values[2]["sides"] == 4 and values[2]["closing gap"] == 0.05
    assert values[3]["in band"] == pytest.approx(85.0) and values[3]["travelled"] == 5.1
    assert [r["task"] for r in rows] == ["line-follow", "spin", "drive-square", "wall-follow"]
    assert "on line" not in values[1] and "turns" not in values[0]


def test_a_validate_row_holds_spawn_robot_enclosure_and_gaps():
    ok = validated("worlds/enclosed_room.yaml")
    open_room = validated("worlds/broken/open_room.yaml", findings=[OPEN_FINDING, LIDAR_NOTE], enclosed=False,
                          gaps=[OPEN_GAP], robot_enclosed=False, enclosed_area_m2=None)
    waffle = validated("worlds/w.world")
    waffle.robot, waffle.spawn = "robots/my_waffle.urdf.xacro", (2.5, -1.25, 1.5708)
    rows = index_rows([ok, open_room, waffle])
    values = [{m["label"]: m["value"] for m in r["metrics"]} for r in rows]
    assert [m["label"] for m in rows[1]["metrics"]] == ["spawn", "robot", "enclosed", "gaps", "widest gap",
                                                       "clearance", "no-hit beams", "spin drift", "stopped at",
                                                       "sim time"]
    assert values[0]["spawn"] == "(0, 0, 0)" and values[0]["robot"] == "burger" and values[0]["enclosed"] == "yes"
    assert values[0]["gaps"] == 0 and "widest gap" not in values[0]
    assert values[1]["enclosed"] == "NO" and values[1]["gaps"] == 1 and values[1]["widest gap"] == 0.5
    assert values[1]["clearance"] == 2.323 and values[1]["spin drift"] == 1.62 and values[1]["stopped at"] == 0.5202
    assert values[2]["spawn"] == "(2.5, -1.25, 1.571)" and values[2]["robot"] == "my_waffle.urdf.xacro"
    assert rows[1]["findings"][0] == {"severity": "error", "check": "enclosed", "message": OPEN_FINDING.message,
                                      "where": OPEN_FINDING.where, "fix": OPEN_FINDING.fix}
    assert rows[1]["findings"][1]["where"] is None


def test_rooms_and_links():
    first = validated("worlds/maze.world")
    first.room = 1
    second = validated("worlds/maze.world")
    second.room = 2
    hrefs = {"worlds/maze.world": "pages/maze.world.html", "odd:name?#1": "pages/odd:name?#1 x.html"}
    rows = index_rows([first, second, validated("odd:name?#1"), validated("worlds/none.world")], hrefs)
    assert [r["name"] for r in rows][:2] == ["worlds/maze.world [room 1]", "worlds/maze.world [room 2]"]
    assert [r["href"] for r in rows] == ["pages/maze.world.html", "pages/maze.world.html",
                                         "pages/odd%3Aname%3F%231%20x.html", None]
    doc = parse(index_page(rows, "maze"))
    links = {tr.get("data-name"): [a.get("href") for a in tr.iter("a")] for tr in doc.xpath("//tr[@data-name]")}
    assert links == {"worlds/maze.world [room 1]": ["pages/maze.world.html"],
                     "worlds/maze.world [room 2]": ["pages/maze.world.html"],
                     "odd:name?#1": ["pages/odd%3Aname%3F%231%20x.html"], "worlds/none.world": []}


# -------------------------------------------------------------------------------------------------- page

def test_the_page_shows_the_rows_in_their_order_with_badges_and_a_summary():
    results = class_runs() + [validated("worlds/b.world", findings=[LIDAR_WARNING])]
    doc = parse(index_page(index_rows(results), "stop-at-wall", "world enclosed_room.yaml"))
    assert doc.findtext(".//title") == "stop-at-wall" and doc.findtext(".//h1") == "stop-at-wall"
    assert doc.get_element_by_id("summary").text_content() == "6 submissions: 1 pass, 1 warn, 4 fail"
    assert "world enclosed_room.yaml" in doc.text_content()
    trs = doc.xpath("//tr[@data-name]")
    assert [tr.get("data-name") for tr in trs] == [r.name for r in results]
    assert [tr.get("data-verdict") for tr in trs] == ["ok", "FAIL", "FAIL", "FAIL", "FAIL", "warn"]
    badges = [tr.find("td/span").get("class") for tr in trs]
    assert badges[:2] == ["badge badge-ok", "badge badge-FAIL"] and badges[-1] == "badge badge-warn"
    assert [tb.get("data-index") for tb in doc.xpath("//table[@id='grades']/tbody")] == [str(i) for i in range(6)]


def test_metric_columns_are_the_union_of_the_rows_labels_and_blank_where_missing():
    results = class_runs()
    results.append(Result(path="subs/fay", checks=["node", "line-follow"],
                          metrics=run_metrics(1.2, 7.5, share_on_line=0.93, laps=1.2, covered=1.0)))
    doc = parse(index_page(index_rows(results), "t"))
    labels = header_labels(doc)
    assert labels == ["verdict", "submission", "front distance", "stop error", "on line", "laps", "covered",
                      "contacts", "min clearance", "path", "sim time", "cmd_vel msgs", "node", "errors", "warnings"]
    heads = doc.xpath("//table[@id='grades']/thead/tr/th")
    types = dict(zip(labels, (th.get("data-type") for th in heads)))
    assert types["front distance"] == types["contacts"] == types["errors"] == types["verdict"] == "num"
    assert types["node"] == types["submission"] == "text"
    assert "(m)" in heads[labels.index("front distance")].text_content()
    assert cell(doc, "subs/alice", "on line").text_content() == ""           # alice's task has no such measure
    assert cell(doc, "subs/fay", "on line").text_content() == "93%"
    assert cell(doc, "subs/erin", "front distance").text_content() == ""
    assert cell(doc, "subs/carol", "front distance").text_content() == "–"  # measured: nothing in range
    assert cell(doc, "subs/carol", "front distance").get("data-sort") is None
    for tr in doc.xpath("//tr[@data-name]"):
        assert len(tr.findall("td")) == len(labels)


def test_numbers_carry_their_raw_value_for_sorting():
    results = class_runs()
    results[0].metrics["path_length_m"] = float("inf")
    doc = parse(index_page(index_rows(results), "t"))
    assert cell(doc, "subs/alice", "front distance").get("data-sort") == "0.52"
    assert cell(doc, "subs/bob", "stop error").get("data-sort") == repr(0.81 - 0.5)
    assert cell(doc, "subs/carol", "contacts").get("data-sort") == "1"
    assert cell(doc, "subs/alice", "path").get("data-sort") == "Infinity"
    assert cell(doc, "subs/alice", "path").text_content() == "inf"
    assert cell(doc, "subs/bob", "errors").get("data-sort") == "1"
    assert [cell(doc, r.name, "verdict").get("data-sort") for r in results] == ["2", "0", "0", "0", "0"]
    data = embedded(doc)
    assert data[0]["metrics"][4] == {"key": "path_length_m", "label": "path", "value": "inf", "unit": "m",
                                     "text": "inf"}
    assert data[1]["metrics"][0]["value"] == 0.81


def test_findings_sit_under_their_row_with_where_fix_and_skipped_checks():
    results = [validated("worlds/broken/open_room.yaml", findings=[LIDAR_NOTE, OPEN_FINDING], enclosed=False,
                         gaps=[OPEN_GAP]), validated("worlds/fine.world")] + class_runs()[3:4]
    doc = parse(index_page(index_rows(results), "t"))
    bodies = doc.xpath("//table[@id='grades']/tbody")
    details = bodies[0].find(".//details")
    assert details.findtext("summary") == "1 error, 1 note"
    items = [li.text_content() for li in details.iter("li")]
    assert items[0].startswith("error enclosed: the room is open")          # errors first
    assert "where: gap from (0.50, -2.50) to (1.00, -2.50)" in items[0] and "fix: close the gap" in items[0]
    assert items[1].startswith("info lidar: 10 of 360 beams")
    assert bodies[1].find(".//details") is None                              # nothing to say
    dave = bodies[2].find(".//details")
    assert dave.findtext("summary") == "1 error, 1 check not run"
    assert "skipped stop-at-wall: the nodes could not start" in dave.text_content()
    assert "pip install opencv-python" in dave.text_content()


def test_what_students_control_stays_text():
    evil = validated(HOSTILE, findings=[Finding("enclosed", "error", "wall <img src=x onerror=alert(2)> & </script>",
                                                where="<b>here</b>", fix="\"quote\" 'it' &amp;")])
    evil.robot = "robots/<i>bot&amp;.urdf"
    page = index_page(index_rows([evil], {HOSTILE: "pages/x.html"}), "<title> & \"co\"", "<b>sub</b>")
    doc = parse(page)
    assert [s.get("type") for s in doc.iter("script")] == ["application/json", None]
    assert not doc.xpath("//img | //b | //i | //script[contains(., 'alert')][not(@type)]")
    assert doc.findtext(".//title") == "<title> & \"co\"" and doc.findtext(".//h1") == "<title> & \"co\""
    tr = doc.xpath("//tr[@data-name]")[0]
    assert tr.get("data-name") == HOSTILE
    assert tr.find("td/a").text_content() == HOSTILE
    assert {e.tag for e in tr.find("td/a").iter()} == {"a", "wbr"}   # places to wrap the name, nothing else
    assert "wall <img src=x onerror=alert(2)> & </script>" in doc.text_content()
    assert "\"quote\" 'it' &amp;" in doc.text_content() and "<b>here</b>" in doc.text_content()
    assert "<i>bot&amp;.urdf" in doc.text_content()
    raw = page.decode("utf-8")
    head, data = raw.split('id="worldgen-index">', 1)
    data, tail = data.split("</script>", 1)
    assert "<script>alert" not in head + tail and "<img" not in head + tail
    assert "<\\/script>" in data and "</" not in data and "<!--" not in data   # the JSON cannot end its element
    assert embedded(doc)[0]["name"] == HOSTILE
    assert embedded(doc)[0]["findings"][0]["message"] == "wall <img src=x onerror=alert(2)> & </script>"


def test_undecodable_file_names_and_control_characters_do_not_break_the_page():
    odd = validated("subs/caf\udce9\x07.world", findings=[Finding("parse", "error", "bad\x00byte")])
    page = index_page(index_rows([odd]), "t")
    doc = parse(page)
    assert doc.xpath("//tr[@data-name]")[0].get("data-name") == "subs/caf\ufffd\ufffd.world"
    assert embedded(doc)[0]["name"] == "subs/caf\ufffd\x07.world"   # JSON escapes the control character


def test_the_same_rows_give_the_same_bytes():
    first = index_page(index_rows(class_runs(), {"subs/alice": "a.html"}), "t", "s")
    again = index_page(index_rows(class_runs(), {"subs/alice": "a.html"}), "t", "s")
    assert first == again
    assert not re.search(rb"20\d\d-\d\d-\d\d", first)


def test_the_page_loads_nothing_from_outside():
    doc = parse(index_page(index_rows(class_runs() + [validated(HOSTILE)], {"subs/alice": "alice/index.html"}), "t"))
    for element in doc.iter():
        for attribute in ("src", "href", "action", "data", "poster", "srcset"):
            value = (element.get(attribute) or "").strip().lower()
            assert not value.startswith(("http:", "https:", "//", "javascript:")), (element.tag, value)
    assert not doc.xpath("//link[@rel='stylesheet'] | //script[@src] | //img | //iframe | //object | //embed")
    assert not re.search(r"url\(|@import", "".join(s.text or "" for s in doc.iter("style")))
    policy = doc.xpath("//meta[@http-equiv='Content-Security-Policy']")[0].get("content")
    assert "default-src 'none'" in policy
    # the policy lets the page's own script run, and only it
    script = [s for s in doc.iter("script") if s.get("type") is None][0].text
    digest = base64.b64encode(hashlib.sha256(script.encode("utf-8")).digest()).decode("ascii")
    assert f"script-src 'sha256-{digest}'" in policy


def test_forty_rows_make_a_page_of_reasonable_size():
    results = []
    for i in range(40):
        if i % 3 == 0:
            results.append(ran(f"submissions/student_{i:02d}", 0.5 + i / 100, 1.8, findings=[
                Finding("stop-at-wall", "error", f"stopped {0.5 + i / 100:.2f} m from the wall ahead, past the "
                                                 "0.5 m target (±0.1 m)",
                        fix="check the front distance (nearest valid beam ahead) and the stop condition"),
                Finding("node", "warning", "the node printed 12 warnings", where="scripts/stop_at_wall.py")]))
        else:
            results.append(ran(f"submissions/student_{i:02d}", 0.5 + i / 1000, 1.8))
    hrefs = {r.path: f"{r.path}/index.html" for r in results}
    page = index_page(index_rows(results, hrefs), "stop-at-wall: 40 submissions")
    print(f"\n40-row index page: {len(page)} bytes ({len(page) / 1024:.1f} KiB)")
    assert len(page) < 150_000
    assert len(parse(page).xpath("//tr[@data-name]")) == 40


# ----------------------------------------------------------------------------------------------- browser

def test_in_a_browser_headers_sort_numerically_and_the_switches_filter(chromium, tmp_path):
    results = [ran("subs/alice", 0.52, 1.8), ran("subs/bob", 10.5, 1.8), ran("subs/carol", None, 1.8),
               ran("subs/dan", 2.0, 1.8, findings=[Finding("stop-at-wall", "error", "stopped 2.00 m from the wall")]),
               ran("subs/eve", 0.3, 1.8, findings=[LIDAR_WARNING]), ran("subs/fay", 2.0, 1.8), ran(HOSTILE, 0.4, 1.8)]
    path = tmp_path / "index.html"
    path.write_bytes(index_page(index_rows(results, {"subs/alice": "alice/index.html"}), "stop-at-wall"))
    (tmp_path / "alice").mkdir()
    (tmp_path / "alice" / "index.html").write_text("<!doctype html><title>alice</title>", encoding="utf-8")
    with open_page(chromium, path) as probe:
        page = probe.page
        assert page.evaluate("document.documentElement.dataset.ready") == "1"   # the policy let the script run

        def order(visible_only: bool = False) -> list:
            return page.eval_on_selector_all(
                "tr[data-name]", "(rows, visible) => rows.filter(r => !visible || !r.parentNode.hidden)"
                                 ".map(r => r.dataset.name.split('/').pop())", visible_only)

        assert order() == ["alice", "bob", "carol", "dan", "eve", "fay", "x"]
        header = page.locator("thead th", has_text="front distance")
        header.click()   # by value (10.5 after 2.0, as text it would not be); ties keep their order; none last
        assert order() == ["eve", "x", "alice", "dan", "fay", "bob", "carol"]
        assert header.locator(".arrow").text_content() == "\u25b2" and header.get_attribute("aria-sort") == "ascending"
        header.click()
        assert order() == ["bob", "dan", "fay", "alice", "x", "eve", "carol"]
        assert header.locator(".arrow").text_content() == "\u25bc"
        page.locator("thead th", has_text="verdict").click()   # failures first, then warnings; ties as they were
        assert order() == ["dan", "eve", "bob", "fay", "alice", "x", "carol"]
        assert header.locator(".arrow").text_content() == ""
        page.check("#failures-only")
        assert order(visible_only=True) == ["dan"]
        assert page.locator("tr[data-verdict='ok']").first.is_hidden()
        assert page.locator("#shown").text_content() == "showing 1 of 7"
        page.uncheck("#failures-only")
        page.fill("#filter", "LIDAR")   # findings' text too, in any case
        assert order(visible_only=True) == ["eve"]
        page.fill("#filter", "")
        assert len(order(visible_only=True)) == 7
        assert probe.console_errors == [] and probe.left_file == []
        page.locator("tr[data-name='subs/alice'] a").click()
        page.wait_for_url("**/alice/index.html")
        assert page.title() == "alice"


# --------------------------------------------------------------------------------- what the campaign found
# A first-time user's report (issue 25): the index was wider than a 1000 px window, wrapped names mid-word, showed
# "-0.00 m" and gave the count twice.

def line_runs() -> list[Result]:
    """A line-follow class (the task with the most columns: 15) under names as students give them."""
    names = ["alice_anderson", "bob_brown_lab_a_stop_at_wall", "carol", "d", "evelyn_montgomery-smith_2024",
             "Frederick.Williamson", "grace-hopper-the-second"]
    return [Result(path=f"submissions/{name}", spawn=(0.0, -0.85, 0.0), robot="waffle_pi",
                   checks=["node", "line-follow"],
                   findings=[Finding("line-follow", "error", "left the line for 4.2 s at "
                                     "/home/student/catkin_ws/src/line_follower_package/scripts/follow.py:42")]
                   if i % 2 else [],
                   metrics=run_metrics(1.2, 7.5 + i, share_on_line=0.93, laps=1.2, covered=1.0,
                                       worst_distance_m=0.12))
            for i, name in enumerate(names)]


def test_no_number_reads_minus_zero():
    stopped = ran("subs/alice", 0.4999, 1.8)            # stop error −0.0001 m
    stopped.metrics["min_clearance_m"] = -0.0001        # a measure rounding to zero from below
    stopped.spawn = (-0.0001, 0.0, -0.0)
    texts = {m["label"]: m["text"] for m in index_rows([stopped, validated("w.world")])[0]["metrics"]}
    assert texts["stop error"] == "0.00 m" and texts["min clearance"] == "0.00 m"
    validate_row = index_rows([Result(path="w.world", spawn=(-0.0001, 1.0, -0.0), robot="burger")])[0]
    assert validate_row["metrics"][0]["text"] == "(0, 1, 0)"
    shown = [td.text_content() for td in parse(index_page(index_rows([stopped]), "t")).xpath("//tr[@data-name]/td")]
    assert "0.00 m" in shown and not [text for text in shown if text.startswith("-0")]


def test_the_report_gives_the_count_once(tmp_path):
    from worldgen.view.grades import write_report

    write_report(tmp_path / "report", class_runs(), lambda result: None, "worldgen run subs")
    doc = parse((tmp_path / "report" / "index.html").read_bytes())
    above = "".join(e.text_content() for e in doc.body if e.tag not in ("table", "script"))
    assert len(re.findall(r"\bpass\b", above)) == 1, above
    assert doc.get_element_by_id("summary").text_content() == "5 submissions: 1 pass, 0 warn, 4 fail"


def test_names_may_wrap_between_their_words_and_numbers_never():
    result = validated("submissions/evelyn_montgomery-smith_2024/my_world.world")
    result.spawn, result.robot = (3.5, -1.0, 1.5708), "waffle_pi"
    page = index_page(index_rows([result], {result.path: "pages/x.html"}), "t")
    doc = parse(page)
    link = re.search(r'<a href="pages/x.html">(.*?)</a>', page.decode("utf-8")).group(1)
    assert link.split("<wbr>") == ["submissions/", "evelyn_", "montgomery-", "smith_2024/", "my_", "world.", "world"]
    assert cell(doc, result.name, "submission").text_content() == result.name
    assert cell(doc, result.name, "spawn").text_content() == "(3.5, -1, 1.571)"
    assert not cell(doc, result.name, "spawn").findall(".//wbr") and not cell(doc, result.name, "robot").findall(".//wbr")


# JavaScript: each word (letters and digits; a number with its decimals) of a row's cell whose characters are not all
# on one line
SPLIT_WORDS = """() => {
  const split = [];
  for (const cell of document.querySelectorAll('tr[data-name] td')) {
    const walker = document.createTreeWalker(cell, NodeFilter.SHOW_TEXT);
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
      for (const word of node.data.matchAll(/[0-9]+(\\.[0-9]+)?|[A-Za-z0-9]+/g)) {
        const range = document.createRange();
        range.setStart(node, word.index);
        range.setEnd(node, word.index + word[0].length);
        const tops = new Set(Array.from(range.getClientRects()).map(r => Math.round(r.top)));
        if (tops.size > 1) split.push(word[0]);
      }
    }
  }
  return split;
}"""


@pytest.mark.parametrize("kind", ["line-follow", "validate"])
def test_in_a_browser_a_class_fits_a_1000_px_window_and_names_wrap_between_words(chromium, tmp_path, kind):
    if kind == "line-follow":
        results = line_runs()
    else:
        results = [validated(f"submissions/{r.path.rsplit('/', 1)[1]}/worlds/my_world.world",
                             findings=[OPEN_FINDING, LIDAR_WARNING]) for r in line_runs()]
        for result in results:
            result.spawn, result.robot = (3.5, -1.0, 1.5708), "waffle_pi"
    path = tmp_path / "index.html"
    path.write_bytes(index_page(index_rows(results, {r.path: "pages/x.html" for r in results}), "worldgen run"))
    with open_page(chromium, path, viewport=(1000, 800)) as probe:
        page = probe.page
        page.evaluate("document.querySelectorAll('details').forEach(d => { d.open = true; })")
        width = page.evaluate("document.documentElement.scrollWidth")
        print(f"\n{kind}: {len(header_labels(parse(path.read_bytes())))} columns, {width} px wide at 1000 px")
        assert width <= 1000
        assert page.evaluate(SPLIT_WORDS) == []
        assert page.evaluate("document.querySelector('td.name').offsetHeight") > 0
        page.locator("thead th", has_text="submission").click()   # the sort arrow, shown, still fits
        assert page.evaluate("document.documentElement.scrollWidth") <= 1000
        assert probe.console_errors == [] and probe.left_file == []
