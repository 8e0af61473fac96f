"""Coordinates no world needs — a model posed at x = 1e308, a mesh with a vertex there, a spawn 1e300 m away — are
findings or one-line refusals, never a crash: pybullet and GEOS die with SIGSEGV on such numbers, so worldgen
skips what lies beyond 1000 km before either sees it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

WALLS = "".join(
    f"<model name='w{i}'><static>1</static><pose>{x} {y} 0.5 0 0 0</pose><link name='l'><collision name='c'>"
    f"<geometry><box><size>{sx} {sy} 1</size></box></geometry></collision></link></model>"
    for i, (x, y, sx, sy) in enumerate(((0, -1.5, 3.1, 0.1), (0, 1.5, 3.1, 0.1), (-1.5, 0, 0.1, 3.1),
                                        (1.5, 0, 0.1, 3.1))))


def world(tmp_path: Path, pose: str, vertex: str = "1 0 0") -> Path:
    (tmp_path / "tri.obj").write_text(f"v 0 0 0\nv {vertex}\nv 0 1 1\nf 1 2 3\n")
    path = tmp_path / "far.world"
    path.write_text(f"<sdf version='1.6'><world name='w'>{WALLS}<model name='far'><static>1</static>"
                    f"<pose>{pose}</pose><link name='l'><collision name='c'><geometry><mesh><uri>tri.obj</uri>"
                    "</mesh></geometry></collision><visual name='v'><geometry><mesh><uri>tri.obj</uri></mesh>"
                    "</geometry></visual></link></model></world></sdf>\n")
    return path


def worldgen(*argv, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "worldgen", *map(str, argv)], cwd=cwd, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, timeout=300)


@pytest.mark.parametrize("pose, vertex, words", [
    ("1e308 0 0 0 0 0", "1 0 0", "farther than 1000 km from the origin"),
    ("0 -1e308 0 0 0 0", "1 0 0", "farther than 1000 km from the origin"),
    ("0 0 0 0 0 0", "1e308 0 0", "has vertices 1e+308 m from its origin"),
])
@pytest.mark.parametrize("command", ["validate", "preview", "view"])
def test_a_shape_beyond_reach_is_a_finding_not_a_crash(tmp_path, pose, vertex, words, command):
    path = world(tmp_path, pose, vertex)
    out = {"validate": [], "preview": ["-o", "far.png"], "view": ["-o", "far.html"]}[command]
    done = worldgen(command, path, *out, cwd=tmp_path)
    assert done.returncode in ((0, 1) if command == "validate" else (0,)), done.stderr   # not -11 (SIGSEGV)
    said = done.stdout + done.stderr + ((tmp_path / "far.html").read_text() if command == "view" else "")
    assert words in said   # view: on the page, with the world's other findings
    assert "Traceback" not in done.stderr


def test_a_spawn_beyond_reach_is_refused_in_one_line(tmp_path):
    path = world(tmp_path, "0 0 0 0 0 0")
    done = worldgen("drive", path, "--spawn", "1e300,0", cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.splitlines() == [done.stderr.strip()] and "within 1000 km of the origin" in done.stderr
