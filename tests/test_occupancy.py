"""ROS map_server maps (map.yaml + PGM/PNG) as floorplans: walls exactly where the occupied pixels are, map_server's
rules for what is occupied, errors at the map.yaml line, and the example flat in examples/map/.

The example's image is drawn here (:func:`flat_pixels`); ``python tests/test_occupancy.py`` writes it again."""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
import shapely
from conftest import CliRunner

from conftest import EXAMPLES
from worldgen.cli import main
from worldgen.geometry.enclosure import enclosure
from worldgen.core.errors import SpecError
from worldgen.sdf.reader import read_world
from worldgen.spec.load import load_spec

MAP_DIR = EXAMPLES / "map"
FREE, UNKNOWN, WALL = 254, 205, 0   # the grey levels map_saver writes
LIDAR_HEIGHT = 0.17


# ------------------------------------------------------------------------------------------------ drawing maps
def flat_pixels() -> list[list[int]]:
    """The example flat, as map_saver would save it at 0.05 m per pixel: 140 × 100 pixels, two rooms (6 m × 4 m
    between the walls' outer faces) joined by a 0.9 m door, walls two or three pixels thick with a few ragged
    pixels, a table's four legs and a cabinet in the right room, mid-grey unknown patches and light-grey free
    noise, unknown all around."""
    w, h = 140, 100
    px = [[UNKNOWN] * w for _ in range(h)]

    def fill(r0, r1, c0, c1, value):   # rows r0..r1, columns c0..c1, inclusive
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                px[r][c] = value

    fill(10, 90, 10, 129, WALL)
    fill(12, 87, 12, 127, FREE)            # bottom wall three pixels thick (rows 88–90), the others two
    fill(12, 87, 70, 71, WALL)             # the partition ...
    fill(45, 62, 70, 71, FREE)             # ... with its door, 18 pixels (0.9 m) wide
    for c in range(12, 128):               # ragged inner faces, as a scan leaves them
        if c % 9 == 4:
            px[12][c] = WALL
        if c % 13 == 6 and not 70 <= c <= 71:
            px[87][c] = WALL
    for r0, c0 in ((26, 96), (26, 111), (38, 96), (38, 111)):   # a table's legs: lone pixels
        px[r0][c0] = WALL
    fill(14, 19, 118, 127, WALL)           # a cabinet against the right wall
    fill(27, 37, 97, 110, 150)             # under the table: unknown (occupancy 0.41), not a wall
    for r in range(12, 88):                # light-grey speckle on the floor: still free (occupancy below 0.196)
        for c in range(12, 128):
            if px[r][c] == FREE and (r * 7 + c * 3) % 41 == 0:
                px[r][c] = 230
    return px


def pgm(pixels: list[list[int]], comment: str = "worldgen example: drawn by tests/test_occupancy.py") -> bytes:
    """A binary (P5) PGM, as map_saver writes it."""
    head = f"P5\n# {comment}\n{len(pixels[0])} {len(pixels)}\n255\n".encode()
    return head + bytes(v for row in pixels for v in row)


def write_map(folder, pixels, yaml_text="origin: [0.0, 0.0, 0.0]\n", name="map", resolution=0.05):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.pgm").write_bytes(pgm(pixels))
    path = folder / f"{name}.yaml"
    path.write_text(f"image: {name}.pgm\nresolution: {resolution}\n{yaml_text}")
    return path


# ------------------------------------------------------------------------------------------- reading worlds back
def footprints(scene):
    """Every box of the built world as (x0, y0, x1, y1): walls and posts are axis-aligned."""
    out = []
    for s in scene.obstacles():
        assert s.kind == "box"
        x, y, z, w = s.orientation
        yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        quarter = round(yaw / (math.pi / 2))
        assert abs(yaw - quarter * math.pi / 2) < 1e-6   # the writer rounds angles to 6 decimals
        sx, sy = (s.size[1], s.size[0]) if quarter % 2 else (s.size[0], s.size[1])
        out.append((s.position[0] - sx / 2, s.position[1] - sy / 2, s.position[0] + sx / 2, s.position[1] + sy / 2))
    return np.array(out)


def pixel_centres(width, height, resolution, origin):
    """(x, y) of every pixel's centre, row by row from the image's top."""
    rows, cols = np.mgrid[0:height, 0:width]
    return np.stack([origin[0] + (cols + 0.5) * resolution, origin[1] + (height - rows - 0.5) * resolution], -1)


def covered(points, boxes):
    """Which points (…, 2) lie inside some box."""
    flat = points.reshape(-1, 2)
    inside = np.zeros(len(flat), bool)
    for x0, y0, x1, y1 in boxes:
        inside |= (flat[:, 0] > x0) & (flat[:, 0] < x1) & (flat[:, 1] > y0) & (flat[:, 1] < y1)
    return inside.reshape(points.shape[:-1])


def spill(boxes, occupied, resolution, origin):
    """The area (m²) by which the boxes' union and the occupied pixels' squares differ."""
    height = occupied.shape[0]
    squares = shapely.union_all([shapely.box(origin[0] + c * resolution, origin[1] + (height - 1 - r) * resolution,
                                             origin[0] + (c + 1) * resolution, origin[1] + (height - r) * resolution)
                                 for r, c in zip(*np.nonzero(occupied))])
    return shapely.union_all([shapely.box(*b) for b in boxes]).symmetric_difference(squares).area


def build(tmp_path, source):
    result = CliRunner().invoke(main, ["build", str(source), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    (world,) = (tmp_path / "out").glob("*.world")
    return world


# ------------------------------------------------------------------------------------------------------- tests
def test_walls_are_where_the_occupied_pixels_are(tmp_path):
    pixels = flat_pixels()
    source = write_map(tmp_path, pixels, "origin: [-3.25, 7.5, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
                                         "free_thresh: 0.196\n", name="scan")
    scene = read_world(build(tmp_path, source))
    assert scene.world_name == "default" and "scan" in scene.models
    boxes = footprints(scene)
    inside = covered(pixel_centres(140, 100, 0.05, (-3.25, 7.5)), boxes)
    occupied = np.array(pixels) == WALL
    assert (inside == occupied).all()   # every wall pixel's centre is in a box; no free or unknown one is
    # and not just the centres: the boxes' union is the occupied pixels' squares, to a square millimetre
    assert spill(boxes, occupied, 0.05, (-3.25, 7.5)) < 1e-6
    # merged: a few dozen boxes for the ~1,200 occupied pixels
    assert occupied.sum() > 1100 and len(boxes) < 60


def test_noise_maps_are_covered_exactly(tmp_path):
    """Random speckle (lone pixels, diagonal touches, thick blobs) still builds, with walls on exactly its pixels."""
    rnd = random.Random(7)
    for trial in range(3):
        pixels = [[WALL if rnd.random() < 0.35 else FREE for _ in range(30)] for _ in range(24)]
        source = write_map(tmp_path / str(trial), pixels)
        boxes = footprints(read_world(build(tmp_path / str(trial), source)))
        occupied = np.array(pixels) == WALL
        assert (covered(pixel_centres(30, 24, 0.05, (0.0, 0.0)), boxes) == occupied).all()
        assert spill(boxes, occupied, 0.05, (0.0, 0.0)) < 1e-6
        assert len(boxes) < occupied.sum() * 0.7


def wall_columns(spec):
    """The pixel columns (from 0) that the walls and posts of a one-row map at 1 m per pixel cover."""
    columns = set()
    for seg in spec.segments:
        a, b = sorted((seg.start[0], seg.end[0]))
        columns.update(range(round(a - 0.5), round(b - 0.5) + 1))
    columns.update(round(o.at[0] - 0.5) for o in spec.obstacles)
    return sorted(columns)


def test_map_server_rules_for_what_is_a_wall(tmp_path):
    from PIL import Image

    # occupancy (255 - mean) / 255 > occupied_thresh; the mean is over colour channels, alpha left out
    colours = [
        (0, 0, 0, 0),           # 0: black, even fully transparent: a wall
        (0, 255, 0, 255),       # 1: mean 85, occupancy 0.667: a wall (its luma, 150, would say 0.41)
        (89, 89, 89, 255),      # 2: occupancy 0.651 > 0.65: a wall
        (90, 90, 90, 255),      # 3: 0.647: unknown, not a wall
        (205, 205, 205, 255),   # 4: unknown
        (255, 255, 255, 255),   # 5: free
        (255, 0, 0, 128),       # 6: mean 85 again, half transparent: a wall
    ]
    img = Image.new("RGBA", (len(colours), 1))
    for i, colour in enumerate(colours):
        img.putpixel((i, 0), colour)
    img.save(tmp_path / "rgba.png")
    (tmp_path / "rgba.yaml").write_text("image: rgba.png\nresolution: 1\norigin: [0, 0, 0]\n")
    assert wall_columns(load_spec(tmp_path / "rgba.yaml")) == [0, 1, 2, 6]

    # negate: light pixels are walls; the thresholds move the line (occupancies 1, 0.529, 0.498, 0)
    (tmp_path / "g.pgm").write_bytes(pgm([[0, 120, 128, 255]]))
    for extra, walls in (("", [0]), ("mode: scale\n", [0]), ("occupied_thresh: 0.5\n", [0, 1]),
                         ("negate: 1\n", [3]), ("negate: 1\noccupied_thresh: 0.5\nfree_thresh: 0.1\n", [2, 3]),
                         ("negate: true\noccupied_thresh: 0.45\n", [1, 2, 3])):
        (tmp_path / "g.yaml").write_text("image: g.pgm\nresolution: 1\norigin: [0, 0, 0]\n" + extra)
        assert wall_columns(load_spec(tmp_path / "g.yaml")) == walls, extra

    spec = load_spec(tmp_path / "g.yaml")
    assert {s.style.thickness for s in spec.segments} == {1.0}


def test_crop_origin_and_post_names(tmp_path):
    """A big, mostly unknown map (as gmapping saves it) is cropped to its occupied pixels; coordinates stay those
    of the map frame, and a lone pixel's post is named after its pixel."""
    size = 2000
    pixels = [[UNKNOWN] * size for _ in range(size)]
    for c in range(1000, 1010):
        pixels[1500][c] = WALL      # a wall 10 pixels long, 500 pixels above the bottom row
    pixels[1200][1300] = WALL       # a lone pixel
    source = write_map(tmp_path, pixels, "origin: [-50.0, -50.0, 0.0]\n")
    spec = load_spec(source)
    assert spec.name == "map" and spec.robot is None
    (seg,) = spec.segments
    y = -50 + (size - 1500 - 0.5) * 0.05
    assert seg.start == pytest.approx((-50 + 1000.5 * 0.05, y)) and seg.end == pytest.approx((-50 + 1009.5 * 0.05, y))
    (post,) = spec.obstacles
    assert post.name == "map_post_1200_1300" and post.size == (0.05, 0.05, 2.5)
    assert post.at == pytest.approx((-50 + 1300.5 * 0.05, -50 + (size - 1200 - 0.5) * 0.05))


def test_example_map_yaml_as_read():
    from worldgen.spec.maps import MapFile, load_map_yaml

    assert load_map_yaml(MAP_DIR / "map.yaml") == MapFile(
        path=MAP_DIR / "map.yaml", image=MAP_DIR / "map.pgm", resolution=0.05, origin=(-1.5, -2.5), negate=False,
        occupied_thresh=0.65, free_thresh=0.196, mode="trinary", line=1)


def test_walls_farther_than_1000_m_are_refused(tmp_path):
    source = write_map(tmp_path, [[WALL, WALL]], "origin: [999.5, 0, 0]\n", resolution=0.5)
    with pytest.raises(SpecError) as err:
        load_spec(source)
    assert str(err.value).startswith(f"{source}:1: the map's walls reach farther than 1000 m")


def test_spec_wrapping_a_map(tmp_path):
    write_map(tmp_path / "maps", [[WALL] * 4, [FREE] * 4, [WALL, FREE, FREE, WALL]], "origin: [1, 2, 0]\n",
              name="lab", resolution=0.5)
    spec_path = tmp_path / "world.yaml"
    spec_path.write_text("name: lab_world\nmap: maps/lab.yaml\nwalls: {height: 0.8, material: Gazebo/Wood}\n"
                         "robot: {model: waffle, at: [2, 2.75], yaw: 1.5}\n"
                         "obstacles: [{shape: cylinder, radius: 0.1, height: 0.3, at: [1.5, 2.5]}]\n")
    spec = load_spec(spec_path)
    assert spec.name == "lab_world" and (spec.robot.model, spec.robot.at) == ("waffle", (2.0, 2.75))
    assert [(s.start, s.end, s.style.thickness, s.style.height, s.style.material.script, s.line)
            for s in spec.segments] == [((1.25, 3.25), (2.75, 3.25), 0.5, 0.8, "Gazebo/Wood", 2)]
    assert sorted(o.name or o.shape for o in spec.obstacles) == ["cylinder", "map_post_2_0", "map_post_2_3"]
    assert {o.size for o in spec.obstacles if o.name} == {(0.5, 0.5, 0.8)}


YAML = "image: map.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n" \
       "free_thresh: 0.196\n"


@pytest.mark.parametrize("change, line, words", [
    (("image: map.pgm", "image: gone.pgm"), 1, ["gone.pgm does not exist", "relative to the YAML's folder"]),
    (("image: map.pgm", "image: /home/someone/maps/map.pgm"), 1, ["does not exist", "map.pgm lies beside this file"]),
    (("image: map.pgm", "image: ."), 1, ["is a folder, not an image"]),
    (("image: map.pgm", "image: notes.txt"), 1, ["cannot be read as an image"]),
    (("resolution: 0.05", "resolution: 0"), 2, ["resolution must be more than 0"]),
    (("resolution: 0.05", "resolution: -0.05"), 2, ["resolution must be more than 0"]),
    (("0.0]", "0.3]"), 3, ["yaw of 0.3 rad", "write 0 for the yaw"]),
    (("[-1.0, -2.0, 0.0]", "[-1.0]"), 3, ["origin must be [x, y, yaw]"]),
    (("occupied_thresh: 0.65", "occupied_thresh: 1.5"), 5, ["occupied_thresh is 1.5, outside 0–1"]),
    (("free_thresh: 0.196", "free_thresh: 0.7"), 6, ["free_thresh 0.7 is above occupied_thresh 0.65"]),
    (("negate: 0", "negate: 2"), 4, ["negate must be 0 or 1"]),
    (("negate: 0", "ocupied_thresh: 0.6"), 4, ["unknown key 'ocupied_thresh'", "did you mean 'occupied_thresh'"]),
    (("negate: 0", "robot: {at: [0, 0]}"), 4, ["'robot' belongs in a spec", "map: map.yaml"]),
    (("negate: 0", "mode: raw"), 4, ["mode raw has no thresholds"]),
    (("resolution: 0.05\n", ""), 1, ["has no 'resolution'"]),
    (("occupied_thresh: 0.65", "occupied_thresh: 1"), 1, ["has no occupied pixel", "the highest is 1.000"]),
])
def test_map_errors_name_the_map_yaml_line(tmp_path, change, line, words):
    (tmp_path / "map.pgm").write_bytes(pgm([[WALL, WALL, FREE]]))
    (tmp_path / "notes.txt").write_text("not an image\n")
    source = tmp_path / "map.yaml"
    source.write_text(YAML.replace(*change))
    with pytest.raises(SpecError) as err:
        load_spec(source)
    text = str(err.value)
    assert text.startswith(f"{source}:{line}: "), text
    for word in words:
        assert word in text


@pytest.mark.parametrize("value, words", [
    ("maps/none.yaml", ["none.yaml does not exist"]),
    ("map.pgm", ["map names an image", "write map: map.yaml"]),
    ("[1, 2]", ["map must name a map_server YAML file"]),
])
def test_spec_map_errors_name_the_spec_line(tmp_path, value, words):
    write_map(tmp_path, [[WALL, WALL]])
    spec = tmp_path / "s.yaml"
    spec.write_text(f"name: s\nmap: {value}\n")
    with pytest.raises(SpecError) as err:
        load_spec(spec)
    assert str(err.value).startswith(f"{spec}:2: ")
    for word in words:
        assert word in str(err.value)


def test_an_image_given_as_the_spec_points_to_its_yaml(tmp_path):
    write_map(tmp_path, [[WALL, WALL]])
    result = CliRunner().invoke(main, ["build", str(tmp_path / "map.pgm"), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and "map.pgm: is an image, not a spec" in result.output
    assert "give the map's YAML" in result.output


def test_error_inside_the_wrapped_map_names_the_map_yaml(tmp_path):
    source = write_map(tmp_path, [[WALL, WALL]], "origin: [0, 0, 0]\noccupied_thresh: high\n")
    (tmp_path / "s.yaml").write_text("name: s\nmap: map.yaml\n")
    with pytest.raises(SpecError) as err:
        load_spec(tmp_path / "s.yaml")
    assert str(err.value).startswith(f"{source}:4: occupied_thresh must be a number")


def test_build_refuses_a_broken_map_with_one_line(tmp_path):
    (tmp_path / "map.yaml").write_text("image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n")
    result = CliRunner().invoke(main, ["build", str(tmp_path / "map.yaml"), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and "map.yaml:1: the map's image" in result.output
    assert not (tmp_path / "out").exists()


# ------------------------------------------------------------------------------------------------- the example
def test_example_image_is_the_drawn_flat():
    assert (MAP_DIR / "map.pgm").read_bytes() == pgm(flat_pixels())


@pytest.mark.parametrize("name", ["map", "flat"])
def test_example_builds_closed_around_the_robot(tmp_path, name):
    spec = load_spec(MAP_DIR / f"{name}.yaml")
    spawn = spec.robot.at if spec.robot else (0.0, 0.0)   # validate's spawn without a robot: the origin
    scene = read_world(build(tmp_path, MAP_DIR / f"{name}.yaml"))
    assert not [f for f in scene.findings if f.severity == "error"]
    found = enclosure(scene, spawn, LIDAR_HEIGHT)
    assert found.inside is None and found.enclosed is True, found.gaps
    # the region is the pixels the robot can reach from its spawn (both rooms, through the door), to within the
    # 0.5 mm the enclosure check grows every wall by
    pixels = flat_pixels()
    start = (round(100 - (spawn[1] + 2.5) / 0.05 - 0.5), round((spawn[0] + 1.5) / 0.05 - 0.5))
    seen, todo = {start}, [start]
    while todo:
        r, c = todo.pop()
        for cell in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
            if cell not in seen and pixels[cell[0]][cell[1]] != WALL:
                seen.add(cell)
                todo.append(cell)
    assert 8000 < len(seen) < 9000
    assert found.region_area == pytest.approx(len(seen) * 0.05 ** 2, rel=0.003)


def test_example_validates(tmp_path):
    import json

    from worldgen.check.sdformat import sdformat_check

    result = CliRunner().invoke(main, ["validate", str(MAP_DIR / "flat.yaml"), "--format", "json"])
    assert result.exit_code == 0, result.output
    (report,) = json.loads(result.stdout)["results"]
    assert report["ok"] and report["metrics"]["enclosed"] is True
    checked = sdformat_check(build(tmp_path, MAP_DIR / "flat.yaml"))
    assert checked is None or checked[0], checked   # None: no libsdformat on this machine


if __name__ == "__main__":
    (MAP_DIR / "map.pgm").write_bytes(pgm(flat_pixels()))
