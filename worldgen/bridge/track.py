"""What a line-follow run is judged against: the tape on the floor as a centre-line, and the point on the floor
the robot's camera looks at.

The tape is the world's floor marking (:func:`worldgen.geometry.markings.floor_markings`) with the longest
centre-line: each of its boxes is a piece of tape along its x axis, as the writer lays a strip along its segment
(discs only round the joints). A loop is a line whose two ends meet. The camera's floor point is where the middle of the bottom image row
meets the floor, straight ahead of the robot: the nearest floor a camera-steered robot can see, and so what a line
follower keeps on the line (the robot's own centre cuts the corners of a bend).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.errors import InputError
from ..geometry.markings import floor_markings

CLOSE = 0.02   # m: the two ends of a line this close make a loop
SNAP = 1e-4    # m: the grid the tape pieces' ends are put on before they are joined


@dataclass
class Track:
    """The tape's centre-line (a shapely LineString), its width, colour and name, and whether it is a loop."""

    line: object
    width: float
    color: tuple
    name: str
    loop: bool

    @property
    def length(self) -> float:
        return float(self.line.length)


def tape_track(scene, where: str = "") -> Track:
    """The world's tape (see the module docstring); InputError when it has no floor marking longer than wide."""
    import numpy as np
    import shapely
    from shapely.ops import linemerge

    from ..core.poses import quat_matrix

    best = None
    for marking in floor_markings(scene):
        pieces = []
        for shape in marking.shapes:
            if shape.kind != "box" or shape.size is None or shape.size[0] <= 0:
                continue   # a strip runs along its box's x axis, however short (a bend's pieces are shorter than wide)
            axis = quat_matrix(*shape.orientation)[:, 0] * shape.size[0] / 2
            centre = np.asarray(shape.position)
            pieces.append(((centre - axis)[:2], (centre + axis)[:2]))
        if not pieces:
            continue
        # the pieces' ends meet only to rounding: snapped to SNAP first, or linemerge would keep them apart
        lines = shapely.set_precision(shapely.MultiLineString([[tuple(a), tuple(b)] for a, b in pieces]), SNAP)
        merged = linemerge(lines)
        line = merged if merged.geom_type == "LineString" else max(merged.geoms, key=lambda g: g.length)
        if best is None or line.length > best[0].length:
            best = (line, marking)
    if best is None:
        raise InputError("the world has no tape on the floor to follow", path=where or None,
                         hint="add a line to the spec (lines: …), e.g. worldgen new --template line-track NAME")
    line, marking = best
    ends = line.coords[0], line.coords[-1]
    return Track(line, marking.width, marking.colors[0], marking.label, math.dist(ends[0], ends[1]) <= CLOSE)


def camera_floor_distance(robot: str) -> float | None:
    """How far ahead of the robot's base the middle of its first camera's bottom image row meets the floor (m),
    or None when the robot has no camera looking down on the floor. The ray leaves the sensor's pose on its link
    (tilted or not), along its +x with the image's lower edge half the vertical field of view below."""
    import numpy as np

    from ..core.poses import pose_matrix
    from ..robots import robot_urdf
    from ..robots.profile import link_frames, robot_profile

    profile = robot_profile(robot_urdf(robot))
    if not profile.cameras:
        return None
    camera = profile.cameras[0]
    frames = link_frames(profile.joints, profile.base_frame)
    if camera.link not in frames:
        return None
    xyz, rotation = frames[camera.link]
    link = np.eye(4)
    link[:3, :3], link[:3, 3] = rotation, xyz
    sensor = link @ pose_matrix(*camera.pose)
    below = math.tan(camera.hfov / 2) * camera.height / camera.width   # tan of half the vertical field of view
    origin, ray = sensor[:3, 3], sensor[:3, :3] @ np.array([1.0, 0.0, -below])
    if origin[2] <= 0 or ray[2] >= 0:
        return None   # the camera looks level or up: its image never meets the floor
    return float(origin[0] - origin[2] / ray[2] * ray[0])


def follow_numbers(track: Track, odom: list, lookahead: float, band: float) -> dict:
    """From odometry rows ``[t, x, y, yaw, …]``: the share of rows whose floor point (``lookahead`` m ahead)
    is within ``band`` m of the centre-line, the laps (a loop) or the share of the line travelled along it while
    on it, and the worst distance."""
    import shapely

    points = [shapely.Point(r[1] + lookahead * math.cos(r[3]), r[2] + lookahead * math.sin(r[3])) for r in odom]
    distances = [track.line.distance(p) for p in points]
    on = [d <= band for d in distances]
    along = [track.line.project(p) for p in points]
    length = track.length
    progress, seen = 0.0, set()
    for i in range(1, len(points)):
        if on[i] and on[i - 1]:
            step = along[i] - along[i - 1]
            if track.loop:
                step = math.remainder(step, length)
            progress += step
        if on[i]:
            seen.add(int(along[i] / 0.1))
    covered = min(1.0, len(seen) * 0.1 / length) if length > 0 else 0.0
    return {"share_on_line": sum(on) / len(on) if on else 0.0, "laps": abs(progress) / length if length else 0.0,
            "covered": covered, "worst_distance_m": max(distances, default=None), "tape_length_m": length}
