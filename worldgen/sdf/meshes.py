"""Mesh files (.dae, .stl, .obj, …) loaded as plain vertex and face arrays, sized the way Gazebo sizes them.

Gazebo scales a Collada mesh by its ``<unit meter=…>`` and then by the SDF ``<scale>``; it ignores ``<up_axis>``
(the TurtleBot3 world's walls say Y_UP and stand upright). trimesh keeps the unit only as metadata, so the unit is
read here. trimesh is imported on first use: most worlds have no meshes and ``worldgen build`` must stay fast.

Text in a mesh file (an OBJ comment, a binary STL's 80-byte header, an OFF file) need not be UTF-8: trimesh then
guesses the encoding with charset-normalizer, a dependency of worldgen for that reason. A mesh that cannot be read
for any reason becomes the error string of :meth:`MeshCache.load`, which the reader turns into a warning naming
the file.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

import numpy as np

from ..core.inputs import MAX_INPUT_BYTES

MAX_MESH_TRIANGLES = 250_000   # triangles in one mesh file: validate, view and preview stay within 10 s with
#                                  the largest as a triangle soup (benchmarks/bench_limits.py)
MAX_WORLD_TRIANGLES = 500_000  # triangles of every mesh a world places, collisions and visuals, each use counted
MAX_VERTEX = 1e6   # m from a mesh's own origin, once scaled (as worldgen.sdf.shapes.MAX_SIZE for a shape)
_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([^\"']+)[\"']")


def collada_unit(path: Path) -> float:
    """The ``<unit meter=…>`` of a Collada file's asset block (1.0 when absent or unreadable)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(8192)
    except OSError:
        return 1.0
    match = _UNIT.search(head)
    try:
        unit = float(match.group(1)) if match else 1.0
    except ValueError:
        return 1.0
    return unit if unit > 0 else 1.0


_COLLADA_COUNT = re.compile(rb"<(?:triangles|polylist|polygons|trifans|tristrips)\b[^>]*?\bcount\s*=\s*[\"'](\d+)")
_PLY_FACES = re.compile(rb"element\s+face\s+(\d+)")


def triangles_in_file(path: Path) -> int:
    """How many triangles a mesh file holds, counted without parsing it (a floor: polygons count once): a
    binary STL's header, an ASCII STL's facets, an OBJ's ``f`` lines, a Collada file's primitives' counts, a
    PLY header's faces; 0 when the format says nothing this cheaply."""
    with open(path, "rb") as handle:
        data = handle.read()
    suffix = path.suffix.lower()
    if suffix == ".stl":
        if len(data) >= 84 and 84 + 50 * int.from_bytes(data[80:84], "little") == len(data):
            return int.from_bytes(data[80:84], "little")
        return data.count(b"endfacet")
    if suffix == ".obj":
        return data.count(b"\nf ") + data.count(b"\nf\t") + int(data.startswith((b"f ", b"f\t")))
    if suffix == ".dae":
        return sum(int(n) for n in _COLLADA_COUNT.findall(data))
    if suffix == ".ply":
        found = _PLY_FACES.search(data[:4096])
        return int(found.group(1)) if found else 0
    return 0


def too_many_triangles(count: int) -> str:
    return (f"holds {count:,} triangles, more than the {MAX_MESH_TRIANGLES:,} worldgen reads from one mesh (see "
            "Limits in the README)")


DECIMATE = (f"decimate it to under {MAX_MESH_TRIANGLES:,} triangles (Blender's Decimate modifier, MeshLab's quadric "
            "edge collapse): Gazebo's collisions want a few thousand")


class MeshCache:
    """Loads each (file, scale) once per read; returns read-only ``(vertices, faces)`` arrays or raises
    ``ValueError`` saying why the mesh cannot be used."""

    def __init__(self) -> None:
        self._cache: dict[tuple[str, tuple[float, float, float]], tuple[np.ndarray, np.ndarray] | str] = {}

    def load(self, path: Path, scale: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        key = (str(path), tuple(scale))
        if key not in self._cache:
            self._cache[key] = self._load(path, scale)
        found = self._cache[key]
        if isinstance(found, str):
            raise ValueError(found)
        return found

    @staticmethod
    def _load(path: Path, scale) -> tuple[np.ndarray, np.ndarray] | str:
        import trimesh  # lazy: heavy import, needed only for worlds with meshes

        try:
            info = os.stat(path)
        except OSError as err:
            return f"cannot be read ({err.strerror})"
        if not stat.S_ISREG(info.st_mode):
            return "is not a regular file (a pipe, device or socket)"
        if info.st_size > MAX_INPUT_BYTES:
            return (f"is larger than {MAX_INPUT_BYTES // 2 ** 20} MiB, the most worldgen reads (see Limits in the "
                    "README)")
        counted = triangles_in_file(path)   # before parsing: a 2 M-triangle file takes minutes to parse
        if counted > MAX_MESH_TRIANGLES:
            return too_many_triangles(counted)
        try:
            mesh = trimesh.load(str(path), force="mesh")
        except Exception as err:  # trimesh raises many types for bad files; all mean "cannot use this mesh"
            return f"cannot be loaded ({type(err).__name__}: {err})"
        if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
            return "holds no triangles"
        if len(mesh.faces) > MAX_MESH_TRIANGLES:
            return too_many_triangles(len(mesh.faces))
        unit = collada_unit(path) if path.suffix.lower() == ".dae" else 1.0
        with np.errstate(over="ignore", invalid="ignore"):
            vertices = np.asarray(mesh.vertices, dtype=float) * unit * np.asarray(scale, dtype=float)
        faces = np.asarray(mesh.faces, dtype=np.int64)
        reach = np.abs(vertices).max(initial=0.0)
        if not np.isfinite(vertices).all() or reach > MAX_VERTEX:
            return (f"has vertices {'that are not numbers' if not np.isfinite(reach) else f'{reach:.3g} m'} from its "
                    f"origin once scaled; worldgen reads meshes within {MAX_VERTEX:g} m of theirs")
        for array in (vertices, faces):
            array.setflags(write=False)  # shared by every shape that uses this file and scale
        return vertices, faces
