"""Findings a student can act on: a world built from a spec is reported in the spec's rooms and walls, an opening
of any width is located, and overlapping rooms and obstacles standing in walls are warned about."""

from __future__ import annotations

import json

import pytest

from conftest import CliRunner
from worldgen.cli import main

FLAT = """name: flat
rooms:
  - name: living
    rect: {center: [0, 0], size: [5, 4]}
    openings:
      - {type: door, wall: 1}
  - name: kitchen
    polygon: [[2.5, -2], [6, -2], [6, 2], [2.5, 2]]
    openings:
      - {type: door, wall: 1, width: 0.6}
robot: {model: burger, at: [4, 0], yaw: 0}
"""


def validate(*args):
    out = CliRunner().invoke(main, ["validate", *map(str, args), "--skip-sim", "--format", "json"])
    return out.exit_code, json.loads(out.stdout)["results"]


def messages(result, check, severity=None):
    return [f for f in result["findings"] if f["check"] == check and (severity is None or f["severity"] == severity)]


def test_a_gap_is_named_by_the_specs_room_and_wall(tmp_path):
    spec = tmp_path / "flat.yaml"
    spec.write_text(FLAT)
    code, [r] = validate(spec)
    [gap] = messages(r, "enclosed", "error")
    assert code == 1
    assert "0.60 m gap at (6.00, 0.00) in room 'kitchen', wall 1 (from (6,-2) to (6,2))" in gap["message"]
    assert "Wall_" not in gap["message"]
    # the world built from it, validated with its spec beside it, speaks the same language
    assert CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path / "out")]).exit_code == 0
    (tmp_path / "out" / "flat.yaml").write_text(FLAT)
    code, [r] = validate(tmp_path / "out" / "flat.world")
    assert "in room 'kitchen', wall 1 (from (6,-2) to (6,2))" in messages(r, "enclosed", "error")[0]["message"]
    # the raw labels stay in the metrics, for programs
    assert r["metrics"]["gaps"][0]["between"][0].startswith("flat/Wall_")


def test_a_spawn_in_a_shared_wall_names_both_rooms(tmp_path):
    spec = tmp_path / "flat.yaml"
    spec.write_text(FLAT.replace("at: [4, 0]", "at: [2.5, 1.5]"))
    code, [r] = validate(spec)
    [inside] = messages(r, "enclosed", "error")
    assert code == 1 and inside["message"] == (
        "the spawn point (2.50, 1.50) is inside room 'living', wall 1 (from (2.5,-2) to (2.5,2)), shared with "
        "room 'kitchen', wall 3 (from (2.5,2) to (2.5,-2))")


def test_an_opening_of_any_width_is_located(tmp_path):
    spec = tmp_path / "hall.yaml"   # a 12 m x 10 m hall with its whole top side missing
    spec.write_text("""name: hall
segments:
  - {from: [0, 0], to: [12, 0]}
  - {from: [12, 0], to: [12, 10]}
  - {from: [0, 10], to: [0, 0]}
robot: {model: burger, at: [3, 4], yaw: 0}
""")
    code, [r] = validate(spec)
    [gap] = r["metrics"]["gaps"]
    assert code == 1 and gap["width"] == pytest.approx(11.85, abs=0.02)   # between the walls' inner faces
    assert gap["centre"][0] == pytest.approx(6.0, abs=0.05) and 9.9 < gap["centre"][1] < 10.2
    [finding] = messages(r, "enclosed", "error")
    assert "11.85 m gap at (6.00, 10.0" in finding["message"]
    assert "between segment 3 (from (0,10) to (0,0)) and segment 2 (from (12,0) to (12,10))" in finding["message"]


def test_overlapping_rooms_and_obstacles_in_walls_are_warned_about(tmp_path):
    spec = tmp_path / "flat.yaml"
    text = FLAT.replace("robot:", """  - name: closet
    rect: {center: [-2, 1.5], size: [1.5, 1.5]}
obstacles:
  - {name: table, shape: box, size: [1.2, 0.6, 0.75], at: [0, 2], yaw: 0.3}
  - {name: stool, shape: cylinder, radius: 0.2, height: 0.5, at: [1, -1]}
robot:""")
    spec.write_text(text)
    code, [r] = validate(spec)
    warnings = [f["message"] for f in messages(r, "spec", "warning")]
    assert len(warnings) == 2, warnings
    overlap, table = warnings
    assert overlap.startswith("rooms 'living' and 'closet' overlap: they share 1.56 m² of floor around (-1.8")
    assert table.startswith("obstacle 'table' stands in room 'living', wall 2 (from (2.5,2) to (-2.5,2)): ")
    assert "stool" not in " ".join(warnings)   # free-standing on the floor: nothing to say
    [where] = [f["where"] for f in messages(r, "spec") if "table" in f["message"]]
    table_line = next(i for i, line in enumerate(text.splitlines(), start=1) if "name: table" in line)
    assert where == f"{spec}:{table_line}"
    # rooms that only share a wall do not overlap
    plain = tmp_path / "plain.yaml"
    plain.write_text(FLAT)
    code, [r] = validate(plain)
    assert messages(r, "spec") == []
