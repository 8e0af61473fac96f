"""A mesh's section at one height, worldgen's against trimesh's, on about a million triangles:

- the section's segments: ``mesh_section.mesh_section_segments`` and ``trimesh.intersections.mesh_plane`` (time,
  and whether the segments' ends meet so that the section of a closed surface fills: its area after polygonize);
- the closed-surface test worldgen uses (trimesh's ``merge_vertices`` and ``is_watertight``), once per shape.

Meshes: an icosphere of 1.3 M triangles with shared vertices (as trimesh loads a file), the same with each
triangle's vertices repeated (a raw STL), and a seeded soup of 1 M random triangles.

    .venv/bin/python benchmarks/bench_mesh_section.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import shapely
import trimesh

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from worldgen.geometry.mesh_section import mesh_section_segments, watertight  # noqa: E402


def best(fn, repeat: int = 3):
    """The fastest of ``repeat`` runs (seconds) and the result."""
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def filled_area(segments) -> float:
    """The area the segments enclose once noded and polygonized (0 when no ring closes)."""
    if len(segments) == 0 or len(segments) > 50_000:
        return float("nan")
    lines = shapely.get_parts(shapely.union_all(shapely.multilinestrings(segments)))
    return sum(p.area for p in shapely.get_parts(shapely.polygonize(lines)))


def meshes():
    sphere = trimesh.creation.icosphere(subdivisions=8, radius=2.0)
    v, f = np.asarray(sphere.vertices), np.asarray(sphere.faces, dtype=np.int64)
    yield "icosphere, shared vertices", v, f
    yield "icosphere, vertices per triangle", v[f].reshape(-1, 3), np.arange(3 * len(f)).reshape(-1, 3)
    n = 1_000_000
    yield "random soup", np.random.default_rng(1).uniform(0, 1, (3 * n, 3)), np.arange(3 * n).reshape(-1, 3)


def main() -> None:
    for name, v, f in meshes():
        z = v[:, 2].min() + 0.3 * np.ptp(v[:, 2])
        print(f"{name}: {len(f)} triangles, cut at z = {z:.3f}")
        ours_t, ours = best(lambda: mesh_section_segments(v, f, z))
        mesh = trimesh.Trimesh(v, f, process=False)
        theirs_t, theirs = best(lambda: trimesh.intersections.mesh_plane(mesh, [0, 0, 1], [0, 0, z])[:, :, :2])
        print(f"  segments   worldgen {ours_t * 1000:8.1f} ms  ({len(ours)}, filled area {filled_area(ours):.3f})")
        print(f"             trimesh  {theirs_t * 1000:8.1f} ms  ({len(theirs)}, filled area "
              f"{filled_area(theirs):.3f})")
        closed_t, closed = best(lambda: watertight(v, f), repeat=1)
        print(f"  closed     trimesh  {closed_t * 1000:8.1f} ms  ({closed})")


if __name__ == "__main__":
    main()
