"""Hostile and broken inputs: how long each takes, how much memory it needs, and what the user sees.

Run: ``python benchmarks/bench_hostile.py [--timeout S] [--mem-cap GB] [--only NAME ...]``. Every case runs
``python -m worldgen ...`` in its own process (under a wrapper that reads the child's peak RSS with
``getrusage(RUSAGE_CHILDREN)``), with a per-case timeout (default 120 s: the process group is killed and the
case reported as ``timeout``) and an address-space cap (default 16 GB) so that a bomb cannot take the machine down.
Prints one row per case: exit status (or ``timeout``/``signal N``), wall time, peak memory, and the first line
of stderr (``Traceback`` flags a crash), then the goal for the case.

The cases come from issue 11. "here" cases are the ones the safe-writes / encodings work handles; the others are
the YAML bombs, big meshes, include fan-out, model counts, speckled maps and endless inputs whose limits come
later — they are measured on the current code so that the baseline is known. Kill and race behaviour is tested in
``tests/test_safe_writes.py``, not here.
"""

from __future__ import annotations

import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROOM = "name: hostile\nrooms:\n  - name: room\n    rect: {center: [0, 0], size: [5, 5]}\n"

WRAPPER = r"""
import json, os, resource, signal, subprocess, sys, time
argv, cwd, timeout, cap = json.loads(sys.argv[1])
def limit():
    os.setsid()
    if cap:
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
t0 = time.monotonic()
proc = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=limit)
try:
    _, err = proc.communicate(timeout=timeout)
    status = proc.returncode
except subprocess.TimeoutExpired:
    os.killpg(proc.pid, signal.SIGKILL)
    _, err = proc.communicate()
    status = "timeout"
seconds = time.monotonic() - t0
rss_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
lines = err.decode("utf-8", "replace").splitlines()
first = next((l for l in lines if l.startswith("Traceback")), lines[0] if lines else "")
if first.startswith("Traceback"):
    first = "Traceback … " + (lines[-1] if lines else "")
print(json.dumps({"status": status, "seconds": seconds, "rss_mb": rss_kb / 1024, "stderr": first,
                  "stderr_lines": len(lines)}))
"""


def _world(body: str) -> str:
    return f"<?xml version='1.0'?>\n<sdf version='1.6'>\n<world name='w'>\n{body}\n</world>\n</sdf>\n"


def _box_model(i: int) -> str:
    return (f"<model name='m{i}'><static>1</static><pose>{i % 300 * 0.5} {i // 300 * 0.5} 0.5 0 0 0</pose>"
            f"<link name='l'><collision name='c'><geometry><box><size>0.2 0.2 1</size></box></geometry>"
            f"</collision></link></model>")


def _stl(path: Path, triangles: int, seed: int = 1) -> None:
    """A binary STL of ``triangles`` random triangles in a 5 m cube (a 'soup')."""
    import numpy as np

    rng = np.random.default_rng(seed)
    tris = rng.uniform(-2.5, 2.5, size=(triangles, 3, 3)).astype("<f4")
    rec = np.zeros(triangles, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = tris
    path.write_bytes(b"soup".ljust(80, b" ") + struct.pack("<I", triangles) + rec.tobytes())


def _mesh_world(folder: Path, mesh: Path) -> Path:
    world = folder / "mesh.world"
    world.write_text(_world(f"<model name='soup'><static>1</static><pose>0 0 1.5 0 0 0</pose><link name='l'>"
                            f"<collision name='c'><geometry><mesh><uri>{mesh}</uri></mesh></geometry></collision>"
                            f"</link></model>"))
    return world


# ---------------------------------------------------------------------------------------------- the cases
def latin1_obj(d: Path):
    obj = d / "wall.obj"
    corners = [(x, y, z) for x in (-2, 2) for y in (-0.1, 0.1) for z in (0, 2)]
    faces = [(1, 2, 4), (1, 4, 3), (5, 7, 8), (5, 8, 6), (1, 5, 6), (1, 6, 2), (3, 4, 8), (3, 8, 7), (1, 3, 7),
             (1, 7, 5), (2, 6, 8), (2, 8, 4)]
    obj.write_bytes("# Mauer für Raum 3, 20 °C\n".encode("latin-1")
                    + b"".join(b"v %g %g %g\n" % c for c in corners) + b"".join(b"f %d %d %d\n" % f for f in faces))
    return ["validate", "--skip-sim", _mesh_world(d, obj)]


def unreadable_mesh(d: Path):
    bad = d / "broken.stl"
    bad.write_bytes(b"\x00garbage" * 50)
    return ["validate", "--skip-sim", _mesh_world(d, bad)]


def non_utf8_preview(d: Path):
    name = os.fsdecode(b"r\xe9sum\xe9.yaml")
    (d / name).write_text(ROOM)
    return ["preview", d / name, "-o", d / "out.png"]


def dangling_output(d: Path):
    (d / "spec.yaml").write_text(ROOM)
    (d / "hostile.world").symlink_to(d / "nowhere")
    return ["build", d / "spec.yaml", "-o", d]


def course_replace(d: Path):
    subprocess.run([sys.executable, "-m", "worldgen", "course", "-w", str(d)], check=True, capture_output=True)
    return ["course", "-w", d, "--force"]


def yaml_text(text: str):
    def make(d: Path):
        (d / "spec.yaml").write_text(text)
        return ["build", d / "spec.yaml", "-o", d / "out"]
    return make


def merge_bomb(d: Path):
    lines = ["a0: &a0 {k: 1}"]
    for i in range(1, 9):
        prev = f"*a{i - 1}"
        lines.append(f"a{i}: &a{i} {{<<: [{', '.join([prev] * 10)}]}}")
    text = "name: bomb\n" + "\n".join(lines) + "\n"
    (d / "spec.yaml").write_text(text)
    return ["build", d / "spec.yaml", "-o", d / "out"]


def dev_zero(d: Path):
    return ["build", "/dev/zero", "-o", d / "out"]


def mesh_soup(triangles: int):
    def make(d: Path):
        _stl(d / "soup.stl", triangles)
        return ["validate", "--skip-sim", _mesh_world(d, d / "soup.stl")]
    return make


def include_fanout(d: Path, depth: int = 5, fan: int = 10):
    for level in range(depth + 1):
        folder = d / "models" / f"lvl{level}"
        folder.mkdir(parents=True)
        (folder / "model.config").write_text(f"<model><name>lvl{level}</name><sdf version='1.6'>model.sdf</sdf>"
                                             "</model>")
        if level == depth:
            body = ("<static>1</static><link name='l'><collision name='c'><geometry><box><size>0.1 0.1 0.1</size>"
                    "</box></geometry></collision></link>")
        else:
            body = "".join(f"<include><uri>model://lvl{level + 1}</uri><name>c{k}</name>"
                           f"<pose>{k * 0.2} 0 0 0 0 0</pose></include>" for k in range(fan))
        (folder / "model.sdf").write_text(f"<sdf version='1.6'><model name='lvl{level}'>{body}</model></sdf>")
    (d / "fan.world").write_text(_world("<include><uri>model://lvl0</uri></include>"))
    return ["validate", "--skip-sim", "--model-path", d / "models", d / "fan.world"]


def many_models(count: int):
    def make(d: Path):
        (d / "many.world").write_text(_world("\n".join(_box_model(i) for i in range(count))))
        return ["validate", "--skip-sim", d / "many.world"]
    return make


def speckled_map(d: Path, size: int = 1500):
    import numpy as np
    from PIL import Image

    rng = np.random.default_rng(7)
    pixels = np.where(rng.random((size, size)) < 0.3, 0, 254).astype("uint8")   # 30 % occupied speckle
    Image.fromarray(pixels, "L").save(d / "map.pgm")
    (d / "map.yaml").write_text("image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                                "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return ["build", d / "map.yaml", "-o", d / "out"]


CASES = [   # name, part ("here" = handled by the safe-writes/encodings work, "later" = limits to come), make, goal
    ("latin1-obj-mesh", "here", latin1_obj, "verdict, the mesh wall in the scene"),
    ("unreadable-mesh", "here", unreadable_mesh, "verdict with a warning naming the file"),
    ("preview-non-utf8-name", "here", non_utf8_preview, "exit 0"),
    ("dangling-symlink-output", "here", dangling_output, "exit 2, one line"),
    ("course-force-replace", "here", course_replace, "exit 0, swapped in one rename"),
    ("yaml-invalid-date", "later", yaml_text("name: t\nwhen: 2001-13-45\n"), "exit 2, < 2 s, < 300 MB"),
    ("yaml-int-tag", "later", yaml_text("name: !!int abc\n"), "exit 2, < 2 s, < 300 MB"),
    ("yaml-float-tag", "later", yaml_text("name: !!float .\n"), "exit 2, < 2 s, < 300 MB"),
    ("yaml-binary-tag", "later", yaml_text("name: !!binary 'a'\n"), "exit 2, < 2 s, < 300 MB"),
    ("yaml-40000-nested", "later", yaml_text("name: t\nx: " + "[" * 40000 + "\n"), "exit 2, < 2 s, < 300 MB"),
    ("yaml-merge-bomb", "later", merge_bomb, "exit 2, < 2 s, < 300 MB"),
    ("spec-dev-zero", "later", dev_zero, "exit 2, < 2 s, < 300 MB"),
    ("mesh-soup-10k", "later", mesh_soup(10_000), "verdict, < 10 s, < 1 GB"),
    ("mesh-soup-100k", "later", mesh_soup(100_000), "verdict or exit 2, bounded"),
    ("include-fanout-10^5", "later", include_fanout, "exit 2 past the include limit, < 2 s"),
    ("models-10k", "later", many_models(10_000), "verdict"),
    ("models-100k", "later", many_models(100_000), "verdict, < 60 s (about 10 x models-10k)"),
    ("speckled-map-1500", "later", speckled_map, "a bounded number of walls"),
]


def measure(argv, cwd: Path, timeout: float, cap_bytes: int) -> dict:
    cmd = [sys.executable, "-m", "worldgen", *map(str, argv)]
    out = subprocess.run([sys.executable, "-c", WRAPPER, json.dumps([cmd, str(cwd), timeout, cap_bytes])],
                         capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    return json.loads(out.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--timeout", type=float, default=120.0, help="seconds per case (default 120)")
    parser.add_argument("--mem-cap", type=float, default=16.0, help="address-space cap per case, GB (default 16)")
    parser.add_argument("--only", nargs="*", default=None, help="run only these cases")
    args = parser.parse_args()
    print(f"{'case':26} {'part':5} {'status':>8} {'time':>9} {'peak':>9}  stderr (first line)  |  goal")
    for name, part, make, goal in CASES:
        if args.only and name not in args.only:
            continue
        with tempfile.TemporaryDirectory(prefix="bench_hostile_") as tmp:
            argv = make(Path(tmp))
            r = measure(argv, Path(tmp), args.timeout, int(args.mem_cap * 2**30))
        status = r["status"] if isinstance(r["status"], str) else (
            f"exit {r['status']}" if r["status"] >= 0 else f"signal {-r['status']}")
        line = r["stderr"][:90] + ("" if r["stderr_lines"] <= 1 else f" (+{r['stderr_lines'] - 1} lines)")
        print(f"{name:26} {part:5} {status:>8} {r['seconds']:8.2f}s {r['rss_mb']:7.0f}MB  {line}  |  {goal}",
              flush=True)


if __name__ == "__main__":
    main()
