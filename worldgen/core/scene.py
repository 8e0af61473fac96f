"""The scene: what a world file holds once read, as collision shapes in the world frame (what the robot bumps
into and the LiDAR sees) and visual shapes with their colours (what a camera sees, floor markings included).

Data flows file → :mod:`worldgen.sdf.reader` → :class:`Scene` → checks / pybullet / preview. A scene holds no
pybullet or trimesh objects, only numbers, so it can be tested and drawn without a simulator.
"""

from __future__ import annotations

import pickle
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal, Tuple

from .findings import Finding

ShapeKind = Literal["box", "cylinder", "sphere", "mesh", "plane"]
Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # x, y, z, w (pybullet's order)


@dataclass
class Shape:
    """One collision shape, placed in the world frame.

    ``position``/``orientation`` are the world pose of the shape's own frame (its centre for box, cylinder and
    sphere, as in SDF). ``size`` is the box's full x, y, z; a cylinder has ``radius`` and ``length`` along its
    local z; a sphere has ``radius``; a mesh has ``vertices`` (N × 3, already scaled, in the shape's frame) and
    ``faces`` (M × 3 indices); a plane has ``normal`` (local). ``model``/``link``/``name`` say where it came from.
    ``color`` is a visual's material colour, RGBA from 0 to 1 (None for a collision, or a visual whose material
    is not known: drawn grey).
    """

    kind: ShapeKind
    position: Vec3
    orientation: Quat = (0.0, 0.0, 0.0, 1.0)
    size: Vec3 | None = None
    radius: float | None = None
    length: float | None = None
    normal: Vec3 | None = None
    vertices: object | None = None  # numpy array (N, 3) for meshes
    faces: object | None = None     # numpy array (M, 3) for meshes
    model: str = ""
    link: str = ""
    name: str = ""
    static: bool = True
    color: Tuple[float, float, float, float] | None = None
    closed: bool | None = field(default=None, compare=False)   # a mesh's surface is closed: None until a slice
    # needs to know (worldgen.geometry.mesh_section.closed_surface finds it once and keeps it here)

    @property
    def label(self) -> str:
        return "/".join(p for p in (self.model, self.link, self.name) if p)

    def reach(self) -> float:
        """How far from its own frame's origin the shape reaches (the radius of a sphere round it; infinite for
        a plane)."""
        if self.kind == "box":
            return 0.5 * sum(v * v for v in self.size) ** 0.5
        if self.kind == "cylinder":
            return (self.radius ** 2 + (0.5 * self.length) ** 2) ** 0.5
        if self.kind == "sphere":
            return self.radius
        if self.kind == "mesh" and self.vertices is not None and len(self.vertices):
            return float((self.vertices ** 2).sum(axis=1).max()) ** 0.5
        return float("inf") if self.kind == "plane" else 0.0


@dataclass
class Scene:
    """A world read from a file: its collision shapes, its visual shapes (``visuals``, each with its colour, in
    the world frame: walls, obstacles and floor markings as a camera sees them), and what the reader had to say
    about it."""

    source: Path | None
    sdf_version: str | None = None
    world_name: str | None = None
    shapes: list[Shape] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)
    models: list[str] = field(default_factory=list)
    model_poses: dict[str, tuple[float, ...]] = field(default_factory=dict)   # name → (x, y, z, qx, qy, qz, qw)
    visuals: list[Shape] = field(default_factory=list)

    def save(self, path: str | Path) -> None:
        """Pickle the scene to ``path``: how a parent hands it to a simulator child (see :meth:`load`)."""
        Path(path).write_bytes(pickle.dumps(self, protocol=pickle.HIGHEST_PROTOCOL))

    @staticmethod
    def load(path: str | Path) -> "Scene":
        """The scene :meth:`save` wrote (a file the parent wrote into its own private folder)."""
        with open(path, "rb") as handle:
            return pickle.load(handle)

    def obstacles(self) -> list[Shape]:
        """Every shape but ground planes."""
        return [s for s in self.shapes if s.kind != "plane"]

    def around(self, x: float, y: float, radius: float) -> "Scene":
        """This scene with only the shapes that come within ``radius`` (horizontally) of (``x``, ``y``), for a
        simulation that can neither go nor see farther; planes and shapes that move are always kept. The shapes
        themselves are shared, not copied."""
        def near(shape: Shape) -> bool:
            if not shape.static or shape.kind == "plane":
                return True
            gap = ((shape.position[0] - x) ** 2 + (shape.position[1] - y) ** 2) ** 0.5
            return gap <= radius + shape.reach()

        return replace(self, shapes=[s for s in self.shapes if near(s)],
                       visuals=[s for s in self.visuals if near(s)])
