"""Validate's work is known before it is done: a spec or world past the shapes it checks in bounded time is refused
in one line naming the limit and how to get under it (in a folder: a failed row, the others still checked); what a
world checked from each of its rooms needs again — its slices, their union, the free space — is computed once;
spec_lint's pairs come from an index and say what the pairwise loop said."""

from __future__ import annotations

import gc
import json
import random

import pytest
from conftest import REPO, CliRunner

from worldgen.check import budget, spec_lint
from worldgen.cli import main
from worldgen.core.scene import Scene, Shape
from worldgen.geometry import disc_space, scene_memo, slices
from worldgen.spec.load import load_spec

README = (REPO / "README.md").read_text(encoding="utf-8")


def random_grid(path, side: int, seed: int = 1):
    rng = random.Random(seed)
    path.write_text("\n".join("".join("#" if rng.random() < 0.5 else "." for _ in range(side))
                              for _ in range(side)) + "\n")
    return path


def box(name, x, y, collisions=1):
    parts = "".join(f"<collision name='c{k}'><pose>0 {0.3 * k} 0 0 0 0</pose><geometry><box><size>0.2 0.2 1"
                    f"</size></box></geometry></collision>" for k in range(collisions))
    return (f"<model name='{name}'><static>1</static><pose>{x} {y} 0.5 0 0 0</pose><link name='l'>{parts}</link>"
            "</model>")


def world(body: str) -> str:
    return f"<sdf version='1.6'><world name='default'>{body}</world></sdf>\n"


def test_the_readme_states_the_limit():
    assert f"{budget.MAX_SHAPES:,}".replace(",", " ") in README


def test_a_spec_past_the_budget_is_refused_before_it_is_built(tmp_path, monkeypatch):
    spec = random_grid(tmp_path / "noise.txt", 60)
    shapes = budget.spec_shapes(load_spec(spec))
    monkeypatch.setattr(budget, "MAX_SHAPES", shapes - 1)
    built = []
    monkeypatch.setattr("worldgen.geometry.building.build_geometry", lambda *a, **k: built.append(a))
    done = CliRunner().invoke(main, ["validate", str(spec)])
    assert done.exit_code == 2 and built == []
    [line] = done.stderr.strip().splitlines()
    assert line.startswith(f"worldgen: error: {spec}: the spec has {shapes:,} collision shapes, more than the "
                           f"{shapes - 1:,} validate checks") and "coarser cell" in line


def test_a_world_file_past_the_budget_is_refused_in_one_line(tmp_path, monkeypatch):
    path = tmp_path / "many.world"
    path.write_text(world("".join(box(f"b{i}", i % 10, i // 10) for i in range(30))))
    monkeypatch.setattr(budget, "MAX_SHAPES", 20)
    done = CliRunner().invoke(main, ["validate", str(path)])
    assert done.exit_code == 2
    [line] = done.stderr.strip().splitlines()
    assert "the world has 30 collision shapes, more than the 20" in line and "split its models" in line


def test_in_a_folder_the_refused_file_is_one_failed_row(tmp_path, monkeypatch):
    (tmp_path / "class").mkdir()
    (tmp_path / "class" / "big.world").write_text(world("".join(box(f"b{i}", i, 0) for i in range(30))))
    (tmp_path / "class" / "small.world").write_text(world(box("w", 0, 2)))
    monkeypatch.setattr(budget, "MAX_SHAPES", 20)
    done = CliRunner().invoke(main, ["validate", "--skip-sim", "--format", "json", str(tmp_path / "class")])
    rows = {r["path"].rsplit("/", 1)[-1]: r for r in json.loads(done.stdout)["results"]}
    assert done.exit_code == 1 and sorted(rows) == ["big.world", "small.world"]
    [finding] = rows["big.world"]["findings"]
    assert finding["check"] == "input" and "30 collision shapes" in finding["message"]
    assert "parse" in rows["small.world"]["checks"]


def test_a_world_whose_includes_take_it_past_the_budget_is_not_checked(tmp_path, monkeypatch):
    model = tmp_path / "models" / "shelf"
    model.mkdir(parents=True)
    (model / "model.config").write_text("<model><name>shelf</name><sdf version='1.6'>model.sdf</sdf></model>\n")
    (model / "model.sdf").write_text(f"<sdf version='1.6'>{box('shelf', 0, 0, collisions=5)}</sdf>\n")
    path = tmp_path / "shop.world"
    path.write_text(world("".join(f"<include><uri>model://shelf</uri><name>s{i}</name><pose>{2 * i} 0 0 0 0 0</pose>"
                                  "</include>" for i in range(5))))
    monkeypatch.setattr(budget, "MAX_SHAPES", 20)   # the file holds none itself; read, it holds 25
    done = CliRunner().invoke(main, ["validate", "--format", "json", "--model-path", str(tmp_path / "models"),
                                     str(path)])
    [row] = json.loads(done.stdout)["results"]
    assert done.exit_code == 1
    [finding] = [f for f in row["findings"] if f["severity"] == "error"]
    assert finding["check"] == "parse" and "25 collision shapes, more than the 20" in finding["message"]
    assert row["skipped"]["enclosed"] == "too many shapes to check" and "settle" in row["skipped"]


# -------------------------------------------------------------------------------------------------- memos

def wall(name, x0, y0, x1, y1):
    return Shape("box", ((x0 + x1) / 2, (y0 + y1) / 2, 0.5), size=(abs(x1 - x0) + 0.1, abs(y1 - y0) + 0.1, 1.0),
                 model=name)


def test_a_scenes_slices_are_cut_once_and_afresh_when_its_shapes_change():
    scene = Scene(None, shapes=[wall("a", -1, -1, 1, -1), wall("b", -1, 1, 1, 1)])
    first = slices.footprints(scene, 0.2)
    assert [p.geometry for p in slices.footprints(scene, 0.2)] == [p.geometry for p in first]
    assert slices.footprints(scene, 0.2)[0].geometry is first[0].geometry   # kept, not cut again
    scene.shapes.append(wall("c", -1, -1, -1, 1))
    assert [p.label for p in slices.footprints(scene, 0.2)] == ["a", "b", "c"]
    scene.shapes[0] = wall("d", -1, -1, 1, -1)
    assert [p.label for p in slices.footprints(scene, 0.2)][0] == "d"


def test_a_scene_that_is_gone_leaves_nothing_kept():
    """Asked by its own key (other scenes, of other tests' threads, may come and go meanwhile)."""
    scene = Scene(None, shapes=[wall("a", -1, -1, 1, -1)])
    key = id(scene)
    slices.footprints(scene, 0.2)
    ref, memo = scene_memo._MEMOS[key]
    assert ref() is scene and memo
    del scene
    gc.collect()
    assert ref() is None and scene_memo._MEMOS.get(key, (None,))[0] is not ref


def test_the_union_of_many_footprints_is_made_once_for_the_same_ones():
    scene = Scene(None, shapes=[wall(f"w{i}", i * 0.3, 0, i * 0.3, 1) for i in range(disc_space.SMALL + 50)])
    again = Scene(None, shapes=list(scene.shapes))   # another scene, the same shapes: the same union
    union = disc_space.obstacle_union(slices.footprints(scene, 0.2))
    assert disc_space.obstacle_union(slices.footprints(again, 0.2)) is union
    other = Scene(None, shapes=scene.shapes[:-1])
    assert disc_space.obstacle_union(slices.footprints(other, 0.2)) is not union


def test_each_room_of_a_grid_gets_the_verdict_it_got_alone(tmp_path):
    """The rooms of a noisy grid, checked one after another, as each is checked in a fresh process."""
    from worldgen.check.checks import check_enclosed, robot_body
    from worldgen.check.nospawn import default_spawns
    from worldgen.check.sources import WorldSource
    from worldgen.sdf.writer import spec_world_sdf

    spec = random_grid(tmp_path / "noise.txt", 40, seed=3)
    text = spec_world_sdf(load_spec(spec))
    scene = WorldSource(spec.with_suffix(".world"), text).read(())
    spawns = [s.spawn for s in default_spawns(scene, "burger")]
    assert len(spawns) > 1
    together = [check_enclosed(scene, s, robot_body("burger")).metrics for s in spawns]
    alone = [check_enclosed(WorldSource(spec.with_suffix(".world"), text).read(()), s, robot_body("burger")).metrics
             for s in spawns]
    assert together == alone


# ------------------------------------------------------------------------------------------------ spec lint

@pytest.mark.parametrize("seed", range(6))
def test_spec_lint_finds_what_comparing_every_pair_finds(seed):
    """Random rooms and obstacles, some overlapping, some in walls: the indexed lint says what a loop over every
    pair says, in the same order."""
    import shapely

    from worldgen.geometry.building import build_geometry, obstacle_names
    from worldgen.spec.load import parse_spec

    rng = random.Random(seed)
    rooms = "".join(f"  - name: r{i}\n    rect: {{center: [{rng.uniform(-6, 6):.2f}, {rng.uniform(-6, 6):.2f}], "
                    f"size: [{rng.uniform(1, 4):.2f}, {rng.uniform(1, 4):.2f}]}}\n" for i in range(8))
    obstacles = "".join(f"  - {{shape: box, at: [{rng.uniform(-7, 7):.2f}, {rng.uniform(-7, 7):.2f}], size: [0.4, 0.4, "
                        f"0.5], yaw: {rng.uniform(0, 3):.2f}}}\n" for _ in range(12))
    spec = parse_spec(f"name: lint\nrooms:\n{rooms}obstacles:\n{obstacles}")
    found = spec_lint.lint_spec(spec)
    building = build_geometry(spec)
    polygons = [(r.name, shapely.Polygon(r.vertices)) for r in spec.rooms]
    pairs = [f"rooms '{a}' and '{b}' overlap" for i, (a, pa) in enumerate(polygons) for b, pb in polygons[i + 1:]
             if pa.intersection(pb).area > spec_lint.MIN_OVERLAP]
    walls = [shapely.Polygon(w.footprint()) for w in building.walls]
    stands = [f"obstacle '{name}' stands in" for o, name in zip(spec.obstacles, obstacle_names(spec.obstacles, spec.name))
              for _ in [c for c in (spec_lint._obstacle_shape(o).intersection(w) for w in walls) if c.area > 1e-4][:3]]
    assert [f.message.split(":")[0] for f in found if "overlap" in f.message] == pairs
    assert [f.message.split(" stands in")[0] + " stands in" for f in found if "stands in" in f.message] == stands


# --------------------------------------------------------------------------------- the simulation's reach

def test_the_simulation_gives_the_same_numbers_without_what_the_robot_cannot_reach_or_see():
    """A room and, beyond the job's reach, more boxes than a world is simulated whole with: the simulated job
    measures exactly what it measures in the room alone, and loads only the room."""
    from worldgen.check.sim_job import WHOLE_UP_TO, in_reach, reach, sim_numbers
    from worldgen.robots import robot_urdf
    urdf = robot_urdf("burger")
    walls = [Shape("box", (x, y, 0.5), size=(sx, sy, 1.0), model=f"wall{i}")
             for i, (x, y, sx, sy) in enumerate(((0, -2, 4.1, 0.1), (0, 2, 4.1, 0.1), (-2, 0, 0.1, 4.1),
                                                 (2, 0, 0.1, 4.1)))]
    far = reach(urdf) + 2.0   # past the reach from the spawn by more than a box's own
    boxes = [Shape("box", (far + 0.5 * (i % 40), 0.5 * (i // 40) - 6, 0.5), size=(0.2, 0.2, 1.0), model=f"b{i}")
             for i in range(WHOLE_UP_TO + 500)]
    room = Scene(source=None, shapes=walls, models=[s.model for s in walls])
    crowded = Scene(source=None, shapes=walls + boxes, models=[s.model for s in walls + boxes])
    assert in_reach(crowded, (0.5, 0.3, 0.2), urdf).shapes == walls
    assert in_reach(room, (0.5, 0.3, 0.2), urdf) is room   # a world of a usual size: simulated whole

    alone = sim_numbers(room, "burger", (0.5, 0.3, 0.2), urdf=urdf).to_dict()
    among = sim_numbers(crowded, "burger", (0.5, 0.3, 0.2), urdf=urdf).to_dict()
    alone.pop("wall_seconds"), among.pop("wall_seconds")
    assert among == alone
    assert alone["stop"]["distance"] == pytest.approx(0.5, abs=0.05)   # it did drive to a wall


def test_a_shapes_reach_is_its_farthest_point():
    assert Shape("box", (0, 0, 0), size=(2.0, 2.0, 1.0)).reach() == pytest.approx(1.5)
    assert Shape("cylinder", (0, 0, 0), radius=0.3, length=0.8).reach() == pytest.approx(0.5)
    assert Shape("sphere", (0, 0, 0), radius=0.7).reach() == 0.7
    import numpy as np

    mesh = Shape("mesh", (0, 0, 0), vertices=np.array([[0, 0, 0], [3.0, 4.0, 0], [1, 1, 1]]), faces=np.array([[0, 1, 2]]))
    assert mesh.reach() == pytest.approx(5.0)
    assert Shape("plane", (0, 0, 0), normal=(0, 0, 1)).reach() == float("inf")
