"""Where to check a world from when nothing says where the robot spawns (a bare world, a spec without ``robot``).

The world's origin is often a wall (a grid's corner, a room drawn away from the origin), so instead every closed
room of the world is checked from its deepest free point (:func:`worldgen.geometry.placement.room_points`,
largest room first, at most :data:`MAX_ROOMS`), and the report says so. A world with no closed room at all is
checked from the free point deepest inside its walls' bounds (where the enclosed check then names the way out),
and a world where nothing stands at the robot's height from its origin; both say it plainly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Tuple

from ..core.findings import Finding
from ..geometry.placement import deepest_point, robot_radius, room_points, world_rooms

MAX_ROOMS = 8   # rooms checked at most when no spawn is given (the largest ones)


@dataclass(frozen=True)
class DefaultSpawn:
    """One place to check from: the spawn (x, y, yaw), the sentence saying why there, the room's number (1 for
    the largest; None when the world has no closed room) and findings that go with it."""

    spawn: Tuple[float, float, float]
    source: str
    room: Optional[int] = None
    findings: Tuple[Finding, ...] = ()


def _xy(x: float, y: float) -> str:
    return f"({x:.2f}, {y:.2f})"


def default_spawns(scene, robot: str) -> List[DefaultSpawn]:
    """The places to check ``scene`` from for ``robot`` when no spawn is given (see the module docstring)."""
    rooms = world_rooms(scene, robot_radius(robot))
    regions = rooms.rooms()
    shown = room_points(rooms, MAX_ROOMS, regions)   # only the rooms checked are measured
    count = len(regions)
    if shown:
        spawns = []
        for i, (x, y) in enumerate(shown, start=1):
            which = f"room {i}" if count > 1 else "the world's only closed room"
            note = (f"no spawn given: checked from the deepest free point of {which} at {_xy(x, y)}"
                    + (f" (rooms numbered largest first, {count} in all)" if count > 1 and i == 1 else ""))
            spawns.append(DefaultSpawn((x, y, 0.0), note, i if count > 1 else None))
        if count > MAX_ROOMS:
            first = spawns[0]
            spawns[0] = DefaultSpawn(first.spawn, first.source, first.room, (Finding(
                "enclosed", "info", f"the world has {count} closed rooms: only the {MAX_ROOMS} largest "
                "were checked", fix="give the spawn (--spawn, a launch file or the spec's robot) to check "
                                    "from a given room"),))
        return spawns
    point = deepest_point(rooms)
    if point is None:
        if rooms.centre is None:
            return [DefaultSpawn((0.0, 0.0, 0.0), "no spawn given and nothing in this world stands at the robot's "
                                                  "height: checked from the world's origin")]
        return [DefaultSpawn((0.0, 0.0, 0.0), "no spawn given and the robot fits nowhere in this world: checked "
                                              "from the world's origin")]
    x, y = point
    return [DefaultSpawn((x, y, 0.0), f"no spawn given and this world has no closed room: checked from "
                                      f"{_xy(x, y)}, the free point deepest inside its walls' bounds")]
