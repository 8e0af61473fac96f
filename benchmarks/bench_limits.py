"""Hostile and huge inputs against worldgen's limits: each case's wall time and peak memory, against its bound.

Run: ``python benchmarks/bench_limits.py [CASE …] [--timeout S]`` (``--list`` names the cases; ``WORLDGEN_ROOT=DIR``
measures the worldgen checked out in DIR instead of this one). Every case is
generated in a temporary folder (removed afterwards), run as ``python -m worldgen …`` in a child process with a
time limit of its own, and measured there: wall time, and peak memory from ``getrusage(RUSAGE_CHILDREN)`` (the
child's maximum resident set). A refusal must take under 2 s and 300 MB; an input that is handled, 10 s and
500 MB (issue 25's bound for every command on any input under the limits; the ``bound`` column, OVER past it).
The script always finishes: a case over its time limit is killed and reported as such.
"""

from __future__ import annotations

import os
import random
import struct
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Tuple

ROOT = Path(os.environ.get("WORLDGEN_ROOT") or Path(__file__).resolve().parent.parent)   # the worldgen to measure
REFUSAL = (2.0, 300.0)   # seconds, MB


# ------------------------------------------------------------------------------------------------- worlds

def box_model(name: str, x: float, y: float, size=(0.2, 0.2, 1.0)) -> str:
    return (f"<model name='{name}'><static>1</static><pose>{x:.4f} {y:.4f} {size[2] / 2:.3f} 0 0 0</pose>"
            f"<link name='l'><collision name='c'><geometry><box><size>{size[0]} {size[1]} {size[2]}</size></box>"
            "</geometry></collision></link></model>\n")


def world(body: str) -> str:
    return f"<?xml version='1.0'?>\n<sdf version='1.6'><world name='default'>\n{body}</world></sdf>\n"


def room_walls(half: float) -> str:
    """Four walls round the origin, ``half`` m from it (so the spawn at the origin is enclosed)."""
    t, h = 0.1, 1.0
    out = ""
    for i, (x, y, sx, sy) in enumerate(((0, -half, 2 * half + t, t), (0, half, 2 * half + t, t),
                                        (-half, 0, t, 2 * half + t), (half, 0, t, 2 * half + t))):
        out += box_model(f"wall{i}", x, y, (sx, sy, h))
    return out


def grid_body(count: int, pitch: float = 0.5, size: float = 0.2, corner: float = 1.0) -> str:
    """``count`` static 0.2 m boxes, one model each, on a square grid of ``pitch`` from (corner, corner)."""
    side = int(count ** 0.5 + 0.999)
    return "".join(box_model(f"b{i}", corner + (i % side) * pitch, corner + (i // side) * pitch, (size, size, 1.0))
                   for i in range(count))


def grid_of_boxes(count: int) -> str:
    """A world of ``count`` boxes from (1, 1): the spawn at (-1, -1) is outside them all, so the enclosure search
    runs to its end (no wall surrounds it)."""
    return world(grid_body(count))


def boxes_beside_room(count: int) -> str:
    """A closed room round the origin and ``count`` boxes beside it (from (3, 3)): the spawn is enclosed."""
    return world(room_walls(1.5) + grid_body(count, corner=3.0))


def room_with_door_and_clutter(count: int) -> str:
    """A 20 × 20 m room with a 1 m door and a partition, ``count`` 5 cm posts on a grid inside: the gap search
    runs among thousands of obstacles."""
    t, half, door = 0.1, 10.0, 1.0
    seg = (2 * half - door) / 2
    walls = (box_model("s", 0, -half, (2 * half + t, t, 1)) + box_model("n", 0, half, (2 * half + t, t, 1))
             + box_model("w", -half, 0, (t, 2 * half + t, 1)) + box_model("e1", half, -half + seg / 2, (t, seg, 1))
             + box_model("e2", half, half - seg / 2, (t, seg, 1)) + box_model("p", half - 3, -2, (0.1, 4, 1)))
    side = int(count ** 0.5 + 0.999)
    pitch = 18 / side
    return world(walls + "".join(box_model(f"b{i}", -9 + (i % side) * pitch, -9 + (i // side) * pitch,
                                           (0.05, 0.05, 1)) for i in range(count)))


def include_fanout(tmp: Path, fan: int, depth: int) -> Path:
    """Models m0 … m<depth>: each includes ``fan`` copies of the next; the world includes ``fan`` of m0."""
    models = tmp / "models"
    for level in range(depth + 1):
        folder = models / f"m{level}"
        folder.mkdir(parents=True)
        (folder / "model.config").write_text(f"<model><name>m{level}</name><sdf version='1.6'>model.sdf</sdf>"
                                             "</model>\n")
        inner = "".join(f"<include><uri>model://m{level + 1}</uri><name>i{k}</name>"
                        f"<pose>{k} 0 0 0 0 0</pose></include>" for k in range(fan)) if level < depth else ""
        link = ("<link name='l'><collision name='c'><geometry><box><size>0.1 0.1 0.1</size></box></geometry>"
                "</collision></link>")
        (folder / "model.sdf").write_text(f"<sdf version='1.6'><model name='m{level}'><static>1</static>{link}"
                                          f"{inner}</model></sdf>\n")
    path = tmp / "fanout.world"
    path.write_text(world("".join(f"<include><uri>model://m0</uri><name>top{k}</name></include>"
                                  for k in range(fan))))
    return path


def binary_stl(path: Path, triangles) -> None:
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(triangles)))
        for tri in triangles:
            out.write(struct.pack("<12fH", 0, 0, 0, *[c for v in tri for c in v], 0))


def mesh_soup(tmp: Path, count: int) -> Path:
    """A mesh of ``count`` random triangles in a 4 × 4 × 1 m box beside the room (seeded: the same every run)."""
    rng = random.Random(count)
    tris = [[(rng.uniform(2, 6), rng.uniform(-2, 2), rng.uniform(0, 1)) for _ in range(3)] for _ in range(count)]
    binary_stl(tmp / "soup.stl", tris)
    mesh = ("<model name='soup'><static>1</static><link name='l'><collision name='c'><geometry><mesh>"
            "<uri>soup.stl</uri></mesh></geometry></collision></link></model>\n")
    path = tmp / "soup.world"
    path.write_text(world(room_walls(1.5) + mesh))
    return path


# -------------------------------------------------------------------------------------------------- specs

MERGE_BOMB = """a: &a {x: 1, y: 2}
b: &b {<<: [*a, *a, *a, *a, *a, *a, *a, *a, *a]}
c: &c {<<: [*b, *b, *b, *b, *b, *b, *b, *b, *b]}
d: &d {<<: [*c, *c, *c, *c, *c, *c, *c, *c, *c]}
e: &e {<<: [*d, *d, *d, *d, *d, *d, *d, *d, *d]}
f: &f {<<: [*e, *e, *e, *e, *e, *e, *e, *e, *e]}
g: &g {<<: [*f, *f, *f, *f, *f, *f, *f, *f, *f]}
h: &h {<<: [*g, *g, *g, *g, *g, *g, *g, *g, *g]}
name: bomb
"""

ALIAS_BOMB = """a: &a [x, x, x, x, x, x, x, x, x, x]
b: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]
c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]
d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]
e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]
f: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]
g: &g [*f, *f, *f, *f, *f, *f, *f, *f, *f, *f]
name: bomb
"""


def speckled_map(tmp: Path, side: int, density: float = 0.3) -> Path:
    """A ``side`` × ``side`` map_server map: rooms 100 pixels wide (walls 2 pixels thick) under a salt of wall
    pixels at random (``density`` of all pixels, seeded), a noisy SLAM map's specks."""
    import numpy as np
    from PIL import Image

    rng = np.random.default_rng(side)
    walls = np.zeros((side, side), dtype=bool)
    for k in range(0, side, 100):
        walls[k:k + 2, :] = walls[:, k:k + 2] = True
    walls |= rng.random((side, side)) < density
    Image.fromarray(np.where(walls, 0, 254).astype(np.uint8), mode="L").save(tmp / "speckle.pgm")
    path = tmp / "speckle.yaml"
    path.write_text("image: speckle.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                    "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return path


# -------------------------------------------------------------------------------------------------- cases

@dataclass
class Case:
    name: str
    make: Callable[[Path], List[str]]       # folder -> worldgen arguments
    bound: Tuple[float, float]              # seconds, MB
    expect: Tuple[int, ...] = (0, 1, 2)     # acceptable exit codes


def _validate(path, *extra) -> List[str]:
    return ["validate", "--skip-sim", *extra, str(path)]


def _write(tmp: Path, name: str, text: str) -> Path:
    path = tmp / name
    path.write_text(text)
    return path


def _big_world(tmp: Path) -> List[str]:
    path = tmp / "big.world"
    with open(path, "wb") as out:
        out.write(b"<sdf version='1.6'><world name='default'>")
        out.truncate(200 * 2 ** 20)   # sparse: 200 MB of NUL after the opening tags
    return _validate(path)


def _fifo(tmp: Path) -> List[str]:
    path = tmp / "pipe.world"
    os.mkfifo(path)
    return _validate(path)


def _spec_dev_zero(tmp: Path) -> List[str]:
    link = tmp / "zero.yaml"
    link.symlink_to("/dev/zero")
    return ["build", str(link), "-o", str(tmp / "out")]


def _deep(tmp: Path) -> List[str]:
    return ["build", str(_write(tmp, "deep.yaml", "name: deep\nwalls: " + "[" * 40000 + "\n")),
            "-o", str(tmp / "out")]


# Inputs that once were silently wrong or crashed (issue: hostile input): each must now get a verdict or one line.
SMALL_ROOM = "name: hostile\nrooms:\n  - name: room\n    rect: {center: [0, 0], size: [5, 5]}\n"


def _mesh_wall_world(tmp: Path, mesh: Path) -> Path:
    return _write(tmp, "mesh.world", "<?xml version='1.0'?>\n<sdf version='1.6'><world name='w'><model name='m'>"
                  "<static>1</static><link name='l'><collision name='c'><geometry><mesh><uri>"
                  f"{mesh}</uri></mesh></geometry></collision></link></model></world></sdf>\n")


def _latin1_obj(tmp: Path) -> List[str]:
    corners = [(x, y, z) for x in (-2, 2) for y in (-0.1, 0.1) for z in (0, 2)]
    faces = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2), (3, 4, 8), (3, 8, 7), (1, 3, 7),
             (1, 7, 5), (2, 6, 8), (2, 8, 4)]
    obj = tmp / "wall.obj"
    obj.write_bytes("# Mauer für Raum 3, 20 °C\n".encode("latin-1") + b"".join(b"v %g %g %g\n" % c for c in corners)
                    + b"".join(b"f %d %d %d\n" % f for f in faces))
    return _validate(_mesh_wall_world(tmp, obj))


def _unreadable_mesh(tmp: Path) -> List[str]:
    bad = tmp / "broken.stl"
    bad.write_bytes(b"\x00garbage" * 50)
    return _validate(_mesh_wall_world(tmp, bad))


def _non_utf8_preview(tmp: Path) -> List[str]:
    spec = tmp / os.fsdecode(b"r\xe9sum\xe9.yaml")
    spec.write_text(SMALL_ROOM)
    return ["preview", str(spec), "-o", str(tmp / "out.png")]


def _dangling_output(tmp: Path) -> List[str]:
    (tmp / "hostile.world").symlink_to(tmp / "nowhere")
    return ["build", str(_write(tmp, "spec.yaml", SMALL_ROOM)), "-o", str(tmp)]


# Issue 25's campaign: every command answers within 10 s and 500 MB, or refuses in one line.
BOUNDED = (10.0, 500.0)


def _soup_obj(tmp: Path, count: int) -> Path:
    """An OBJ triangle soup of ``count`` triangles over 3·count/8 shared vertices (short lines, as the campaign's
    4 MB file), beside a closed room."""
    rng = random.Random(count)
    vertices = max(3, 3 * count // 8)
    with open(tmp / "soup.obj", "w") as out:
        out.writelines(f"v {rng.uniform(2, 6):.3f} {rng.uniform(-2, 2):.3f} {rng.uniform(0, 1):.3f}\n"
                       for _ in range(vertices))
        out.writelines(f"f {rng.randrange(vertices) + 1} {rng.randrange(vertices) + 1} {rng.randrange(vertices) + 1}\n"
                       for _ in range(count))
    path = tmp / "soup_obj.world"
    path.write_text(world(room_walls(1.5) + "<model name='soup'><static>1</static><link name='l'><collision "
                          "name='c'><geometry><mesh><uri>soup.obj</uri></mesh></geometry></collision><visual "
                          "name='v'><geometry><mesh><uri>soup.obj</uri></mesh></geometry></visual></link></model>\n"))
    return path


def _far_pose(tmp: Path) -> Path:
    (tmp / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n")
    return _write(tmp, "far.world", world(room_walls(1.5) + "<model name='far'><static>1</static><pose>1e308 0 0 0 0 "
                                          "0</pose><link name='l'><collision name='c'><geometry><mesh><uri>tri.obj"
                                          "</uri></mesh></geometry></collision></link></model>\n"))


def _fine_grid(tmp: Path) -> Path:
    """A 17.5 KB spec: a 140 × 120 grid of 1 cm cells, a tenth of them walls (seeded), the robot in the middle."""
    rng = random.Random(1)
    rows = ["".join("#" if r in (0, 119) or c in (0, 139) or rng.random() < 0.1 else "." for c in range(140))
            for r in range(120)]
    rows[60] = rows[60][:70] + "R" + rows[60][71:]
    return _write(tmp, "fine.yaml", "name: fine\ngrid:\n  cell: 0.01\n  rows: |\n"
                  + "".join(f"    {r}\n" for r in rows))


def _random_grid(tmp: Path, side: int) -> Path:
    rng = random.Random(side)
    return _write(tmp, "random.txt", "\n".join("".join("#" if rng.random() < 0.5 else "." for _ in range(side))
                                                for _ in range(side)) + "\n")


def _plain_big_yaml(tmp: Path) -> Path:
    """1.1 MB of plain YAML (no alias): a line of 140 000 points."""
    points = ", ".join(f"[{i % 9}, {i % 7}]" for i in range(140_000))
    return _write(tmp, "big.yaml", "name: big\nrooms:\n  - name: room\n    rect: {center: [0, 0], size: [5, 5]}\n"
                  f"lines:\n  - name: t\n    points: [{points}]\n")


def _manifest(folder: Path) -> None:
    """The least package.xml for a package named after ``folder``."""
    (folder / "package.xml").write_text(
        f"<package format='2'><name>{folder.name}</name><version>0.0.1</version><description>d</description>"
        "<maintainer email='a@b.c'>a</maintainer><license>BSD</license></package>\n")


def _link_to_root(tmp: Path) -> List[str]:
    """A class folder where one submission holds a link to / (the walk once took 46 s over 1 873 files)."""
    sub = tmp / "submissions" / "ana" / "lab"
    sub.mkdir(parents=True)
    _manifest(sub)
    os.symlink("/", tmp / "submissions" / "ana" / "root")
    return _validate(tmp / "submissions")


def _hostile_launch_py(tmp: Path) -> List[str]:
    """A launch.py whose values would grow to gigabytes and whose lists hold themselves: read, never run."""
    path = tmp / "hostile.launch.py"
    path.write_text("from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n"
                    "def generate_launch_description():\n"
                    "    s = 'a' * 1000000\n    t = s.replace('a', s)\n    u = ''.join([s] * 1000000)\n"
                    "    w = '{0:{1}}'.format('x', 999999999)\n    l = ['a']\n    l.append(l)\n    l.append(l)\n"
                    "    return LaunchDescription([Node(package='p', executable='x', arguments=[l, t, u, w])])\n")
    return _validate(path)


def _launch_include_fanout(tmp: Path) -> List[str]:
    """roslaunch XML including 5 files at each of 5 levels (3 905 includes): refused past 1 000 launch files."""
    for level in range(6):
        inner = "".join(f"<include file='{tmp}/l{level + 1}.launch'/>" for _ in range(5)) if level < 5 else ""
        (tmp / f"l{level}.launch").write_text(f"<launch>{inner}</launch>")
    return _validate(tmp / "l0.launch")


def _symlink_loops(tmp: Path) -> List[str]:
    """A class folder whose submissions link back up the tree (catkin_pkg's walk never ends on it)."""
    root = tmp / "class"
    for student in ("ana/src/a", "ben/catkin_ws/src/b"):
        (root / student).mkdir(parents=True)
        _manifest(root / student)
    (root / "ana" / "src" / "up").symlink_to(root)
    (root / "ben" / "catkin_ws" / "src" / "b" / "back").symlink_to(root / "ben")
    return _validate(root)


def _many_markings(tmp: Path) -> List[str]:
    """A spec with more floor lines than worldgen builds: refused before any is read further."""
    lines = "".join(f"  - {{points: [[0, {i}], [1, {i}]], color: Gazebo/Red}}\n" for i in range(2001))
    return ["build", str(_write(tmp, "marks.yaml", f"name: marks\nlines:\n{lines}")), "-o", str(tmp / "o")]


CAMPAIGN = [
    Case("mesh-soup-obj-250k", lambda t: ["validate", str(_soup_obj(t, 250_000))], BOUNDED, (0, 1)),
    Case("mesh-soup-obj-250k-view", lambda t: ["view", str(_soup_obj(t, 250_000)), "-o", str(t / "s.html")],
         BOUNDED, (0,)),
    Case("mesh-soup-obj-250k-preview", lambda t: ["preview", str(_soup_obj(t, 250_000)), "-o", str(t / "s.png")],
         BOUNDED, (0,)),
    Case("mesh-soup-obj-2M", lambda t: ["validate", str(_soup_obj(t, 2_000_000))], BOUNDED, (0, 1)),
    Case("far-pose-1e308", lambda t: ["validate", str(_far_pose(t))], BOUNDED, (0, 1)),
    Case("far-pose-1e308-preview", lambda t: ["preview", str(_far_pose(t)), "-o", str(t / "f.png")], BOUNDED, (0,)),
    Case("grid-cell-1cm", lambda t: ["validate", str(_fine_grid(t))], BOUNDED, (0, 1)),
    Case("grid-random-200", lambda t: _validate(_random_grid(t, 200)), BOUNDED, (0, 1)),
    Case("grid-random-200-sim", lambda t: ["validate", str(_random_grid(t, 200))], BOUNDED, (0, 1)),
    Case("grid-random-400", lambda t: ["validate", str(_random_grid(t, 400))], REFUSAL, (2,)),
    Case("yaml-plain-1.1MB", lambda t: ["build", str(_plain_big_yaml(t)), "-o", str(t / "o")], BOUNDED, (2,)),
    Case("folder-link-to-root", _link_to_root, BOUNDED, (0, 1)),
    Case("folder-symlink-loops", _symlink_loops, REFUSAL, (0, 1)),
    Case("launch-py-hostile", _hostile_launch_py, REFUSAL, (0, 1)),
    Case("launch-include-fanout", _launch_include_fanout, REFUSAL, (1,)),
    Case("spec-many-markings", _many_markings, REFUSAL, (2,)),
] + [   # each generator at the largest footprint and its finest grain (the arena's carving once took minutes)
    Case(f"generate-{kind}-200m", lambda t, kind=kind, flags=flags: [
        "generate", kind, "--seed", "3", "--size", "200x200", *flags, "-o", str(t / "g")], BOUNDED, (0,))
    for kind, flags in (("arena", ("--robot", "burger", "--min-width", "0.85")),
                        ("clutter", ("--robot", "burger", "--density", "0.3")),
                        ("maze", ("--robot", "burger")), ("rooms", ("--robot", "burger")), ("track", ()))
]


CASES = [
    Case("mesh-obj-latin1", _latin1_obj, REFUSAL, (0, 1)),
    Case("mesh-unreadable", _unreadable_mesh, REFUSAL, (0, 1)),
    Case("preview-non-utf8-name", _non_utf8_preview, REFUSAL, (0,)),
    Case("output-dangling-symlink", _dangling_output, REFUSAL, (2,)),
    Case("include-fanout-10x5", lambda t: _validate(include_fanout(t, 10, 5), "--model-path", str(t / "models")),
         REFUSAL),
    Case("include-depth-40", lambda t: _validate(include_fanout(t, 1, 40), "--model-path", str(t / "models")),
         REFUSAL),
    Case("world-200MB", _big_world, REFUSAL, (1, 2)),
    Case("world-fifo", _fifo, REFUSAL, (1, 2)),
    Case("world-dev-zero", lambda t: _validate("/dev/zero"), REFUSAL, (1, 2)),
    Case("boxes-2000-grid", lambda t: _validate(_write(t, "g.world", grid_of_boxes(2000)), "--spawn", "-1,-1"),
         BOUNDED),
    Case("boxes-10000-grid", lambda t: _validate(_write(t, "g.world", grid_of_boxes(10000)), "--spawn", "-1,-1"),
         BOUNDED),
    Case("door-clutter-10000", lambda t: _validate(_write(t, "d.world", room_with_door_and_clutter(10000)),
                                                   "--spawn", "0.1,0.1"), BOUNDED),
    Case("models-10000", lambda t: _validate(_write(t, "m.world", boxes_beside_room(10000))),
         BOUNDED),
    Case("models-100000", lambda t: _validate(_write(t, "m.world", boxes_beside_room(100000))),
         REFUSAL, (2,)),
    Case("mesh-soup-10000", lambda t: _validate(mesh_soup(t, 10000)), BOUNDED),
    Case("mesh-soup-100000", lambda t: _validate(mesh_soup(t, 100000)), BOUNDED),
    Case("map-speckle-1500-30%", lambda t: ["build", str(speckled_map(t, 1500)), "-o", str(t / "out")],
         BOUNDED),
    Case("map-speckle-1500-2%", lambda t: ["build", str(speckled_map(t, 1500, 0.02)), "-o", str(t / "o")],
         BOUNDED),
    Case("map-9000-square", lambda t: ["build", str(speckled_map(t, 9000, 0.0)), "-o", str(t / "o")],
         REFUSAL, (2,)),
    Case("grid-checker-1400", lambda t: ["build", str(_write(t, "c.txt", "\n".join(
        ("#." if r % 2 == 0 else ".#") * 700 for r in range(1400)) + "\n")), "-o", str(t / "o")], REFUSAL, (2,)),
    Case("yaml-merge-bomb", lambda t: ["build", str(_write(t, "m.yaml", MERGE_BOMB)), "-o", str(t / "o")],
         REFUSAL, (2,)),
    Case("yaml-alias-bomb", lambda t: ["build", str(_write(t, "a.yaml", ALIAS_BOMB)), "-o", str(t / "o")],
         REFUSAL, (2,)),
    Case("yaml-deep-40000", _deep, REFUSAL, (2,)),
    Case("yaml-dev-zero", _spec_dev_zero, REFUSAL, (2,)),
] + CAMPAIGN


RUNNER = """
import json, os, resource, signal, subprocess, sys, time
args, timeout = json.loads(sys.argv[1]), float(sys.argv[2])
start = time.perf_counter()
proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
try:
    out, err = proc.communicate(timeout=timeout)
    rc = proc.returncode
except subprocess.TimeoutExpired:
    os.killpg(proc.pid, signal.SIGKILL)
    out, err = proc.communicate()
    rc = None
seconds = time.perf_counter() - start
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024   # KiB on Linux; this runner's one child
print(json.dumps({"rc": rc, "s": seconds, "mb": peak, "out": out.decode("utf-8", "replace")[-2000:],
                  "err": err.decode("utf-8", "replace")[-4000:]}))
"""


def run_case(case: Case, timeout: float) -> str:
    """One case in a runner process of its own, so that its peak memory is the worldgen child's alone."""
    import json

    with tempfile.TemporaryDirectory(prefix="worldgen_bench_limits_") as tmp:
        args = [sys.executable, "-m", "worldgen", *case.make(Path(tmp))]
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        done = subprocess.run([sys.executable, "-c", RUNNER, json.dumps(args), str(timeout)], cwd=tmp, env=env,
                              stdout=subprocess.PIPE, check=True)
        got = json.loads(done.stdout)
        rc, seconds, mb = got["rc"], got["s"], got["mb"]
        lines = got["err"].strip().splitlines()
        verdict = (got["out"].strip().splitlines() or [""])[-1]
        said = lines[-1] if rc == 2 and lines else verdict
        ok = rc is not None and rc in case.expect and seconds < case.bound[0] and mb < case.bound[1] and \
            not any("Traceback" in line for line in lines) and (rc != 2 or len(lines) == 1)
        status = "ok" if ok else ("TIMEOUT" if rc is None else "OVER")
        return (f"{case.name:24} {status:7} exit {rc!s:4} {seconds:7.2f} s {mb:8.0f} MB   bound "
                f"{case.bound[0]:g} s {case.bound[1]:g} MB   {said[:110]}")


def main(argv: List[str]) -> int:
    timeout = 120.0
    if "--timeout" in argv:
        i = argv.index("--timeout")
        timeout = float(argv[i + 1])
        del argv[i:i + 2]
    if "--list" in argv:
        print("\n".join(c.name for c in CASES))
        return 0
    chosen = [c for c in CASES if not argv or c.name in argv]
    print(f"{'case':24} {'status':7} {'exit':9} {'time':>9} {'peak':>11}")
    failed = 0
    for case in chosen:
        line = run_case(case, timeout)
        failed += " ok " not in line
        print(line, flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
