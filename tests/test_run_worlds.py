"""Grading across worlds (worldgen.bridge.worlds), transport aside: the worlds of a folder or of KIND:COUNT[@SEED],
a runner called in each (here validate's own checks stand in for a node's run: no ROS needed), the pass rate
against --min-pass, the failing worlds each with the command that runs it again, JSON and JUnit.

The same across ROS 1 nodes (the course's stop_at_wall.py and an over-tuned one) is in
tests/test_bridge_worlds.py."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from worldgen.bridge.worlds import (across_worlds, check_min_pass, parse_source, rerun_maker, tallies, world_items,
                                    worlds_json, worlds_junit, worlds_ok, worlds_text)
from worldgen.check.validate import Options, validate
from worldgen.core.errors import InputError
from worldgen.generate.worlds import generate


def checked(item):
    """A runner: validate's geometric checks of the world, as the one result a node's run would give."""
    return validate([item.path], Options(skip_sim=True))


def test_sources_are_folders_or_generated_sets(tmp_path):
    assert parse_source("rooms:10") == ("rooms", 10, 0) and parse_source("maze:3@17") == ("maze", 3, 17)
    assert parse_source("some/folder") is None
    with pytest.raises(InputError, match="no kind of world called 'castle'"):
        parse_source("castle:3")
    with world_items("arena:3@5") as items:
        assert [i.name for i in items] == ["arena_5", "arena_6", "arena_7"]
        assert [i.source for i in items] == ["arena:1@5", "arena:1@6", "arena:1@7"]
        texts = [i.path.read_text() for i in items]
        folder = items[0].path.parent
    assert not folder.exists()   # the generated set lives as long as the grading
    assert texts == [w.text for w in generate("arena", 5, 3)]   # the worlds `worldgen generate` makes
    (tmp_path / "set").mkdir()
    for w in generate("maze", 1, 2):
        (tmp_path / "set" / w.file_name).write_text(w.text)
    with world_items(str(tmp_path / "set")) as items:
        assert [i.name for i in items] == ["maze_1", "maze_2"] and items[0].source.endswith("maze_1.yaml")
    with pytest.raises(InputError, match="neither a folder"):
        with world_items(str(tmp_path / "nothing")):
            pass


def test_one_line_per_world_the_pass_rate_and_the_failing_worlds(tmp_path):
    folder = tmp_path / "set"
    folder.mkdir()
    for w in generate("clutter", 3, 3):
        (folder / w.file_name).write_text(w.text)
    broken = generate("clutter", 9)[0].text.replace("robot: {model: waffle_pi, at: [", "robot: {model: waffle_pi, "
                                                    "at: [9")   # the spawn far outside the room
    (folder / "clutter_9.yaml").write_text(broken)
    seen = []
    with world_items(str(folder)) as items:
        runs = across_worlds(items, checked, jobs=2, progress=lambda run: seen.append(run.world.name))
    assert [r.world.name for r in runs] == ["clutter_3", "clutter_4", "clutter_5", "clutter_9"]
    assert sorted(seen) == sorted(r.world.name for r in runs)
    (tally,) = tallies(runs)
    assert (tally.passed, tally.total) == (3, 4) and tally.rate == 0.75
    assert worlds_ok(runs, 0.75) and not worlds_ok(runs, check_min_pass(0.8))
    rerun = rerun_maker(["stop_at_wall.py"], ["--task", "stop-at-wall", "--rate", "max"])
    text = worlds_text(runs, 0.8, rerun, "stop-at-wall")
    lines = text.splitlines()
    assert sum(line.startswith("clutter_") for line in lines) == 4   # a line per world
    assert "stop-at-wall passed in 3 of 4 worlds (75%); --min-pass 0.8: FAIL" in text
    assert f"clutter_9: worldgen run {folder / 'clutter_9.yaml'} stop_at_wall.py --task stop-at-wall --rate max" \
        in text
    doc = json.loads(worlds_json(runs, 0.8, rerun))
    assert (doc["ok"], doc["passed"], doc["total"], doc["min_pass"]) == (False, 3, 4, 0.8)
    assert [w["world"] for w in doc["worlds"] if not w["ok"]] == ["clutter_9"]
    assert doc["worlds"][3]["rerun"].startswith("worldgen run ") and doc["worlds"][0]["rerun"] is None
    junit = worlds_junit(runs).decode()
    assert 'classname="clutter_9"' in junit and 'name="worldgen run --worlds"' in junit
    with pytest.raises(InputError):
        check_min_pass(1.5)


def test_a_generated_world_is_rerun_from_its_kind_and_seed():
    rerun = rerun_maker(["n.py"], ["--task", "spin"])
    with world_items("maze:1@42") as items:
        runs = across_worlds(items, checked)
    assert rerun(items[0], runs[0].results[0]) == "worldgen run --worlds maze:1@42 n.py --task spin"


def test_every_submission_meets_the_same_worlds(tmp_path):
    """A runner giving a result per submission: a pass rate for each, each failing world named per submission."""
    from worldgen.check.report import Result
    from worldgen.core.findings import Finding

    def two_students(item):
        node = {"node": "scripts/stop_at_wall.py"}
        return [Result("subs/ann", metrics=dict(node)),
                Result("subs/ben", metrics=dict(node), findings=[Finding("run", "error", "touched a wall")])]

    with world_items("arena:2@1") as items:
        runs = across_worlds(items, two_students)
    marks = tallies(runs)
    assert [(t.who, t.passed, t.total) for t in marks] == [("subs/ann", 2, 2), ("subs/ben", 0, 2)]
    rerun = rerun_maker([], ["--task", "stop-at-wall"])
    text = worlds_text(runs, 1.0, rerun, "stop-at-wall")
    header, first = text.splitlines()[:2]   # each submission in a column of its own, under its own heading
    assert header.split() == ["world", "submission", "verdict", "front", "path", "turned", "contacts"]
    assert first.split()[:3] == ["arena_1", "subs/ann", "ok"] and first.index("subs/ann") == header.index("submission")
    assert "subs/ann: stop-at-wall passed in 2 of 2 worlds (100%); --min-pass 1: PASS" in text
    assert "arena_1: worldgen run --worlds arena:1@1 subs/ben/scripts/stop_at_wall.py --task stop-at-wall" in text
    doc = json.loads(worlds_json(runs, 1.0, rerun))
    assert doc["submissions"] == [{"path": "subs/ann", "ok": True, "passed": 2, "total": 2},
                                  {"path": "subs/ben", "ok": False, "passed": 0, "total": 2}]
    assert not doc["ok"] and Path(doc["worlds"][1]["result"]["path"]) == Path("subs/ben")
