"""Every example spec loads, builds with `worldgen build`, previews, and the world it builds is the room it says:
the robot closed in, its rooms joined by their doors."""

from __future__ import annotations

import math
import struct

import pytest
from conftest import CliRunner

from conftest import EXAMPLES
from worldgen.cli import main
from worldgen.geometry.enclosure import enclosure
from worldgen.sdf.reader import read_world
from worldgen.spec.load import load_spec

LIDAR_HEIGHT = 0.17   # m: where a TurtleBot3's LDS-01 scans

# Every example keeps its robot in a closed region (the class's worlds must pass `worldgen validate`); doors join
# rooms. The region's area tells whether the doors open where they should: it is the rooms' floors (each polygon
# shrunk by half its wall thickness) plus each door's passage through its wall, less the free-standing walls.
EXAMPLES_WITH_AREA = ("enclosed_room", "two_rooms", "l_shaped_room", "angled_room", "line_track")
EXAMPLES_OTHER = ("room_with_window", "maze")   # obstacles in the way / a grid: see the maze test below


def _expected_area(spec) -> float:
    import shapely

    floor = sum(shapely.Polygon(r.vertices).buffer(-r.style.thickness / 2, join_style="mitre").area
                for r in spec.rooms)
    doors = sum(o.width * r.style.thickness for r in spec.rooms for o in r.openings if o.type == "door")
    partitions = sum((math.dist(s.start, s.end) + s.style.thickness) * s.style.thickness for s in spec.segments)
    return floor + doors - partitions


def test_every_example_is_listed():
    assert sorted(p.stem for p in EXAMPLES.glob("*.yaml")) == sorted(EXAMPLES_WITH_AREA + EXAMPLES_OTHER)


@pytest.mark.parametrize("name", sorted(EXAMPLES_WITH_AREA + EXAMPLES_OTHER))
def test_example_builds_previews_and_encloses_as_it_says(tmp_path, name):
    source = EXAMPLES / f"{name}.yaml"
    spec = load_spec(source)
    assert spec.name == name and spec.robot is not None
    runner = CliRunner()
    built = runner.invoke(main, ["build", str(source), "-o", str(tmp_path)])
    assert built.exit_code == 0, built.output
    world = tmp_path / f"{name}.world"
    scene = read_world(world)
    assert not [f for f in scene.findings if f.severity == "error"]

    found = enclosure(scene, spec.robot.at, LIDAR_HEIGHT)
    assert found.inside is None, f"the robot spawns inside {found.inside}"
    assert found.enclosed is True, found.gaps
    if name in EXAMPLES_WITH_AREA:
        # (the enclosure check grows every wall by 0.5 mm, which takes well under 0.2 % off the region)
        assert found.region_area == pytest.approx(_expected_area(spec), rel=0.002)

    png = tmp_path / f"{name}.png"
    shown = runner.invoke(main, ["preview", str(source), "-o", str(png)])
    assert shown.exit_code == 0, shown.output
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", data[16:24]) == (800, 800)


def test_three_line_maze_builds_and_closes(tmp_path):
    spec = tmp_path / "tiny.yaml"
    spec.write_text("name: tiny\ngrid:\n  cell: 0.5\n  rows: |\n    #####\n    #R..#\n    #####\n")
    result = CliRunner().invoke(main, ["build", str(spec), "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    scene = read_world(tmp_path / "tiny.world")
    found = enclosure(scene, (0.75, 0.75), LIDAR_HEIGHT)
    assert found.enclosed is True
    # the free cells are exactly the three in the middle row: 1.5 m × 0.5 m
    assert found.region_area == pytest.approx(1.5 * 0.5, abs=0.01)


def test_maze_free_region_is_its_free_cells(tmp_path):
    """The walls cover the '#' cells exactly: the robot's free region is the area of the cells it can reach."""
    import yaml

    source = EXAMPLES / "maze.yaml"
    grid = yaml.safe_load(source.read_text())["grid"]
    rows = grid["rows"].splitlines()
    start = next((r, c) for r, row in enumerate(rows) for c, ch in enumerate(row) if ch in "R><^v")
    seen, todo = {start}, [start]
    while todo:
        r, c = todo.pop()
        for rr, cc in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
            if (rr, cc) not in seen and 0 <= rr < len(rows) and 0 <= cc < len(rows[rr]) and rows[rr][cc] != "#":
                seen.add((rr, cc))
                todo.append((rr, cc))
    assert CliRunner().invoke(main, ["build", str(source), "-o", str(tmp_path)]).exit_code == 0
    found = enclosure(read_world(tmp_path / "maze.world"), load_spec(source).robot.at, LIDAR_HEIGHT)
    # (the enclosure check grows every wall by 0.5 mm, which takes about 0.2 % off this region)
    assert found.region_area == pytest.approx(len(seen) * grid["cell"] ** 2, rel=0.005)
