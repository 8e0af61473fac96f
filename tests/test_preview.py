"""Previews: a deterministic 800 × 800 PNG that shows walls, openings, obstacles and the spawn where they are."""

from __future__ import annotations

import dataclasses
import io
import struct

import numpy as np
import pytest
from conftest import CliRunner
from matplotlib import colors
from matplotlib.image import imread

from worldgen.cli import main
from worldgen.view.preview import (DOOR_COLOUR, OBSTACLE_COLOUR, ROBOT_COLOUR, WALL_COLOUR, WINDOW_COLOUR, Picture,
                              Spawn, figure, picture, render)
from worldgen.core.scene import Scene

WORLD = """\
<?xml version="1.0"?>
<sdf version="1.6">
  <world name="probe">
    <model name="walls">
      <static>1</static>
      <pose>1 0 0 0 0 0</pose>
      <link name="Wall_3">
        <collision name="Wall_3_Collision">
          <geometry><box><size>4 0.2 1</size></box></geometry>
          <pose>0 1 0.5 0 0 0</pose>
        </collision>
      </link>
    </model>
    <model name="drum">
      <pose>1 -1 0.3 0 0 0</pose>
      <link name="link">
        <collision name="c"><geometry><cylinder><radius>0.3</radius><length>0.6</length></cylinder></geometry>
        </collision>
      </link>
    </model>
    <model name="beam">
      <static>1</static>
      <link name="link">
        <collision name="c"><pose>1 -1 1.5 0 0 0</pose><geometry><box><size>3 0.2 0.2</size></box></geometry>
        </collision>
      </link>
    </model>
  </world>
</sdf>
"""

SPEC = """\
name: probe
rooms:
  - name: a
    rect: {center: [0, 0], size: [4, 4]}
    openings:
      - {type: door, wall: 0, offset: 1.0, width: 1.0}
      - {type: window, wall: 2, offset: 1.5, width: 1.0}
obstacles:
  - {shape: box, size: [0.6, 0.6, 0.5], at: [1.0, 1.0]}
robot: {model: waffle, at: [-1, 0], yaw: 1.5708}
"""


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def _colour_at(pic: Picture, data: bytes, x: float, y: float, rays=None) -> np.ndarray:
    """The RGB of the picture at world point (x, y)."""
    image = imread(io.BytesIO(data))
    ax = figure(pic, rays).axes[0]
    ax.apply_aspect()   # the equal-aspect box is settled when drawn; settle it before reading the transform
    px, py = ax.transData.transform((x, y))
    return image[image.shape[0] - 1 - int(round(py)), int(round(px)), :3]


def _is(rgb, colour: str, tol: float = 0.06) -> bool:
    return bool(np.all(np.abs(rgb - np.array(colors.to_rgb(colour))) < tol))


def _floor(rgb) -> bool:
    """Nothing drawn there: white, or the light grey of a grid line."""
    return bool(np.all(rgb > 0.9) and np.ptp(rgb) < 0.02)


@pytest.fixture()
def world_file(tmp_path):
    path = tmp_path / "probe.world"
    path.write_text(WORLD)
    return path


def test_world_picture_draws_static_and_movable_shapes_where_they_are(world_file):
    pic = picture(world_file)
    data = render(pic)
    assert _png_size(data) == (800, 800)
    # the wall box: centre (1, 1), 4 x 0.2 m; the drum: circle r 0.3 at (1, -1); the beam is above the robot
    assert _is(_colour_at(pic, data, 1.0, 1.0), WALL_COLOUR)
    assert _is(_colour_at(pic, data, 2.8, 1.05), WALL_COLOUR)
    assert _is(_colour_at(pic, data, 1.0, -1.0), OBSTACLE_COLOUR)
    assert _is(_colour_at(pic, data, 1.2, -1.15), OBSTACLE_COLOUR)
    assert _floor(_colour_at(pic, data, 2.1, -1.1))      # under the beam: nothing at robot height
    assert _floor(_colour_at(pic, data, 1.0, 0.35))


def test_picture_is_deterministic(world_file):
    first = render(picture(world_file))
    second = render(picture(world_file))
    assert first == second
    assert b"Software" not in first and b"matplotlib" not in first.lower()


def test_spawn_is_drawn_with_its_footprint_and_heading(world_file):
    pic = picture(world_file)
    pic = Picture(pic.scene, pic.title, spawn=Spawn(-0.5, -0.5, 0.0, "burger"), walls=pic.walls)
    data = render(pic)
    # the arrow points along +x from the spawn: solid robot colour 0.15 m ahead, the pale disc 0.08 m behind
    assert _is(_colour_at(pic, data, -0.35, -0.5), ROBOT_COLOUR, tol=0.15)
    behind = _colour_at(pic, data, -0.58, -0.5)
    assert behind[0] > behind[1] + 0.1 and not _is(behind, ROBOT_COLOUR)   # tinted, not solid
    assert _floor(_colour_at(pic, data, -0.5, -0.75))               # outside the 0.105 m disc


def test_rays_hook_draws_lines():
    empty = Picture(Scene(source=None), "rays")
    rays = [(0.1, 0.1, 2.1, 0.4, True), (0.1, 0.1, 0.3, -1.9, False)]
    with_rays = render(empty, rays)
    assert with_rays != render(empty)
    hit = _colour_at(empty, with_rays, 2.1, 0.4, rays)        # a hit ends in a dot
    assert hit[1] > hit[0] + 0.3 and hit[1] > hit[2] + 0.3   # green
    assert _floor(_colour_at(empty, with_rays, 0.3, -1.9, rays))   # a miss does not


def test_spec_picture_marks_doors_windows_obstacles_and_spawn(tmp_path):
    spec = tmp_path / "probe.yaml"
    spec.write_text(SPEC)
    pic = picture(spec)
    data = render(pic)
    assert _png_size(data) == (800, 800)
    # the door: wall 0 (y = -2) from x = -1 to 0; the window: wall 2 (y = 2) runs from x = 2 to -2, offset 1.5
    assert _is(_colour_at(pic, data, -0.5, -2.0), DOOR_COLOUR, tol=0.1)
    assert _is(_colour_at(pic, data, 0.0, 2.0), WINDOW_COLOUR, tol=0.1)
    assert _is(_colour_at(pic, data, 1.5, -2.0), WALL_COLOUR)
    assert _is(_colour_at(pic, data, -2.0, 0.5), WALL_COLOUR)
    assert _is(_colour_at(pic, data, 1.0, 1.0), OBSTACLE_COLOUR)
    assert _floor(_colour_at(pic, data, 0.0, -1.0))
    assert pic.spawn == Spawn(-1.0, 0.0, 1.5708, "waffle")
    assert render(picture(spec)) == data


def test_preview_command_writes_the_png(tmp_path, world_file):
    spec = tmp_path / "probe.yaml"
    spec.write_text(SPEC)
    out = tmp_path / "pics" / "probe.png"
    result = CliRunner().invoke(main, ["preview", str(spec), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert _png_size(out.read_bytes()) == (800, 800)
    assert out.read_bytes() == render(picture(spec))
    result = CliRunner().invoke(main, ["preview", str(world_file), "-o", str(out), "--spawn", "0,0,1", "--force"])
    assert result.exit_code == 0, result.output
    assert out.read_bytes() == render(dataclasses.replace(picture(world_file), spawn=Spawn(0.0, 0.0, 1.0, "burger")))


def test_preview_spawn_and_robot_options(tmp_path):
    """--spawn moves the spec's robot and keeps its model; --robot changes the model and keeps the pose."""
    spec = tmp_path / "probe.yaml"
    spec.write_text(SPEC)
    out = tmp_path / "probe.png"
    pic = picture(spec)
    for options, spawn in ((["--spawn", "0.5,-0.5"], Spawn(0.5, -0.5, 0.0, "waffle")),
                           (["--robot", "burger"], Spawn(-1.0, 0.0, 1.5708, "burger")),
                           (["--spawn", "0,0,3", "--robot", "burger"], Spawn(0.0, 0.0, 3.0, "burger"))):
        result = CliRunner().invoke(main, ["preview", str(spec), "-o", str(out), "--force", *options])
        assert result.exit_code == 0, result.output
        assert out.read_bytes() == render(dataclasses.replace(pic, spawn=spawn)), options


def test_lidar_rays_end_on_the_walls(tmp_path):
    """One simulated scan in the 5 m room: every beam hits, on the walls' inner faces (2.425 m from the centre)."""
    from conftest import EXAMPLES
    from worldgen.view.preview import lidar_rays

    pic = picture(EXAMPLES / "enclosed_room.yaml")
    rays = lidar_rays(pic, pic.spawn)
    assert len(rays) == 360 and all(hit for *_, hit in rays)
    assert all(abs(max(abs(x1), abs(y1)) - 2.425) < 0.01 for _, _, x1, y1, _ in rays)
    data = render(pic, rays)
    assert data != render(pic)


def test_grid_posts_are_drawn_as_walls(tmp_path):
    spec = tmp_path / "posts.yaml"
    spec.write_text('name: posts\ngrid: {cell: 1, rows: ["#######", "#R....#", "#..#..#", "#.....#", "#######"]}\n')
    pic = picture(spec)
    data = render(pic)
    assert _is(_colour_at(pic, data, 3.5, 2.5), WALL_COLOUR)     # the lone '#' in row 3, column 4
    assert _is(_colour_at(pic, data, 0.5, 2.5), WALL_COLOUR)     # the left wall
    assert _floor(_colour_at(pic, data, 2.4, 2.4))
