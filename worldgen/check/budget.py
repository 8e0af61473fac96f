"""How much work a world asks of ``worldgen validate``, known before the work: its collision shapes.

Every geometric check slices, unites and searches the world's shapes, and a world of many shapes that touch (a
noisy grid or map: thousands of boxes in one block) costs time in proportion to them and more: a random 200 × 200
grid (9 000 shapes) takes about 5 s, 280 × 280 (17 800) 11 s, 400 × 400 (36 000) 25 s and 490 MB (2 cores,
loaded). Past :data:`MAX_SHAPES` the world is refused in one line before anything is built, read or simulated:
a spec by the walls and obstacles it draws (:func:`spec_shapes`), a world file by the ``<collision>`` elements it
holds itself (:func:`file_shapes`: its includes come on top, so a world whose includes take it past the limit is
refused once read, :func:`too_many`).
"""

from __future__ import annotations

from pathlib import Path

from ..core.errors import InputError
from ..core.findings import Finding

MAX_SHAPES = 15_000   # collision shapes validate checks in one world (about 10 s of geometric checks)
WORLD_HINT = "validate a part of it: split its models into smaller worlds (see Limits in the README)"
SPEC_HINT = ("draw it with fewer pieces: a grid with a coarser cell or fewer lone # cells, a map with its specks "
             "cleaned; or split it into smaller specs (see Limits in the README)")


def spec_shapes(spec) -> int:
    """The collision shapes a spec builds, about: a wall per room side and per drawn or grid wall, each obstacle
    (the floor markings are drawn, not collided with)."""
    return len(spec.segments) + len(spec.obstacles) + sum(len(room.vertices) for room in spec.rooms)


def file_shapes(path: Path, cap: int = 256 * 2 ** 20) -> int:
    """The ``<collision>`` elements written in a world file itself (0 when it cannot be read: the reader says
    why); its first ``cap`` bytes."""
    try:
        with open(path, "rb") as handle:
            return handle.read(cap).count(b"<collision")
    except OSError:
        return 0


def refuse(count: int, what: str, path, hint: str) -> None:
    """InputError when ``count`` shapes are past :data:`MAX_SHAPES`."""
    if count > MAX_SHAPES:
        raise InputError(_message(count, what), path=path, hint=hint)


def too_many(scene, where: str) -> Finding | None:
    """The error finding of a world read whose shapes are past :data:`MAX_SHAPES` (its includes took it there),
    else None."""
    count = len(scene.obstacles())
    if count <= MAX_SHAPES:
        return None
    return Finding("parse", "error", _message(count, "the world"), where=where, fix=WORLD_HINT)


def _message(count: int, what: str) -> str:
    return (f"{what} has {count:,} collision shapes, more than the {MAX_SHAPES:,} validate checks in bounded time "
            "(not checked)")
