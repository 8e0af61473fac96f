"""Reading a spec's floor markings: ``lines:`` (tape along a polyline, a loop when ``closed``) and ``patches:``
(a coloured ``rect`` or ``disc``). Each is built as visual-only geometry lying on the floor, a link of its own in
the world's ``floor_markings`` model, named after it (or ``line_N`` / ``patch_N``, N from 0): a camera sees it,
the robot and its LiDAR do not.

Every check names the file and line of the value to change, as the rest of the spec's do.
"""

from __future__ import annotations

import math
from typing import List, Sequence, Tuple

from . import values
from .messages import describe, describe_sized, metres
from .model import (DISC_KEYS, LIMIT, LINE_KEYS, LINE_WIDTH, MAX_LINE_POINTS, MAX_LINE_WIDTH, MAX_MARKINGS,
                    MIN_SIZE, PATCH_KEYS, PATCH_RECT_KEYS, FloorLine, FloorPatch)
from .nodes import Node
from .values import Source

COLOR_HINT = "e.g. color: Gazebo/Yellow, or color: [1, 0.5, 0] (red, green, blue from 0 to 1)"


def marking_names(lines: Sequence[FloorLine], patches: Sequence[FloorPatch]) -> Tuple[List[str], List[str]]:
    """The link names of a spec's lines and of its patches: each one's own name, else ``line_N`` / ``patch_N``
    (N its place among the lines or patches, from 0)."""
    return ([ln.name or f"line_{i}" for i, ln in enumerate(lines)],
            [p.name or f"patch_{i}" for i, p in enumerate(patches)])


def read_markings(src: Source, keys: dict) -> Tuple[Tuple[FloorLine, ...], Tuple[FloorPatch, ...]]:
    """The spec's ``lines:`` and ``patches:``, at most :data:`MAX_MARKINGS` of them and :data:`MAX_LINE_POINTS`
    points in all the lines, their names unique."""
    line_nodes = values.listing(src, keys.get("lines"), "lines")
    patch_nodes = values.listing(src, keys.get("patches"), "patches")
    if len(line_nodes) + len(patch_nodes) > MAX_MARKINGS:
        extra = (line_nodes + patch_nodes)[MAX_MARKINGS]
        src.fail(f"the spec has {len(line_nodes) + len(patch_nodes)} lines and patches, more than the "
                 f"{MAX_MARKINGS} worldgen builds", extra.line,
                 hint="join lines that touch into one line with more points (see Limits in the README)")
    lines, points = [], 0
    for i, node in enumerate(line_nodes):
        line = read_line(src, node, i)
        points += len(line.points)
        if points > MAX_LINE_POINTS:
            src.fail(f"the lines have more than {MAX_LINE_POINTS:,} points in all, the most worldgen builds",
                     node.line, hint="a curve looks smooth with a point every 5 to 10 cm: use fewer points "
                                     "(see Limits in the README)")
        lines.append(line)
    patches = tuple(read_patch(src, node, i) for i, node in enumerate(patch_nodes))
    _check_names(src, lines, patches)
    return tuple(lines), patches


def read_line(src: Source, node: Node, index: int) -> FloorLine:
    label = f"line_{index}"   # the name an unnamed line gets (marking_names): the world's
    keys = values.mapping(src, node, label, LINE_KEYS, required=("points", "color"))
    name = values.name(src, keys["name"], "line name") if "name" in keys else None
    what = f"line '{name}'" if name else label
    closed = values.flag(src, keys["closed"], f"closed of {what}") if "closed" in keys else False
    width = values.length(src, keys["width"], f"width of {what}") if "width" in keys else LINE_WIDTH
    if width > MAX_LINE_WIDTH:
        src.fail(f"width of {what} is {metres(width)} m: a line is at most {metres(MAX_LINE_WIDTH)} m wide",
                 keys["width"].line, hint="widths are in metres (tape is about 0.05); for a coloured area use "
                                          "patches: with a rect")
    color = values.material(src, keys["color"], f"color of {what}", key="color")
    points = _points(src, keys["points"], what, closed)
    return FloorLine(points=points, width=width, color=color, closed=closed, name=name, line=node.line)


def _points(src: Source, node: Node, what: str, closed: bool) -> Tuple[Tuple[float, float], ...]:
    """A line's points: at least 2 (3 for a loop), no two in a row at the same place; a loop may repeat its
    first point at the end (the same loop)."""
    items = node.value
    if not isinstance(items, list):
        src.fail(f"points of {what} must be a list of points [[x, y], …], not {describe(items)}", node.line,
                 hint="e.g. points: [[0, 0], [2, 0], [2, 1]]")
    points = [values.point(src, p, f"point {i} of {what}") for i, p in enumerate(items)]
    repeated = len(points) >= 3 and math.dist(points[0], points[-1]) < MIN_SIZE
    if repeated and closed:
        points.pop()
    elif repeated:
        src.fail(f"{what} ends where it starts, but it is not closed", items[-1].line,
                 hint="write closed: true and leave out the repeated last point: a loop's corners are then "
                      "joined all round")
    least = 3 if closed else 2
    if len(points) < least:
        src.fail(f"{what} has {len(points)} point{'' if len(points) == 1 else 's'}; a "
                 f"{'closed line (a loop)' if closed else 'line'} needs at least {least}", node.line,
                 hint="list the points the tape runs through, e.g. points: [[0, 0], [2, 0], [2, 1]]")
    count = len(points) if closed else len(points) - 1
    for i in range(count):
        j = (i + 1) % len(points)
        if math.dist(points[i], points[j]) < MIN_SIZE:
            src.fail(f"points {i} and {j} of {what} are at the same place ({metres(points[i][0])}, "
                     f"{metres(points[i][1])}): a segment needs a length", items[j].line,
                     hint=f"remove point {j}" + (" (a closed line joins its last point to its first itself)"
                                                 if closed and j == 0 else ""))
    return tuple(points)


def read_patch(src: Source, node: Node, index: int) -> FloorPatch:
    label = f"patch_{index}"
    keys = values.mapping(src, node, label, PATCH_KEYS, required=("color",))
    name = values.name(src, keys["name"], "patch name") if "name" in keys else None
    what = f"patch '{name}'" if name else label
    if ("rect" in keys) == ("disc" in keys):
        src.fail(f"{what} needs exactly one of 'rect' or 'disc'", node.line,
                 hint="e.g. rect: {center: [0, 0], size: [0.5, 0.3]} or disc: {center: [0, 0], radius: 0.2}")
    color = values.material(src, keys["color"], f"color of {what}", key="color")
    if "disc" in keys:
        disc = values.mapping(src, keys["disc"], f"disc of {what}", DISC_KEYS, required=DISC_KEYS)
        center = values.point(src, disc["center"], f"center of {what}")
        radius = values.length(src, disc["radius"], f"radius of {what}")
        _within(src, center, radius, what, keys["disc"].line)
        return FloorPatch("disc", center, color, radius=radius, name=name, line=node.line)
    rect = values.mapping(src, keys["rect"], f"rect of {what}", PATCH_RECT_KEYS, required=("center", "size"))
    center = values.point(src, rect["center"], f"center of {what}")
    size = rect["size"]
    if not isinstance(size.value, list) or len(size.value) != 2:
        src.fail(f"size of {what} must be [x size, y size] in metres, not {describe_sized(size.value)}", size.line,
                 hint="e.g. size: [0.5, 0.3]")
    sx = values.length(src, size.value[0], f"x size of {what}")
    sy = values.length(src, size.value[1], f"y size of {what}")
    yaw = values.angle(src, rect["yaw"], f"yaw of {what}") if "yaw" in rect else 0.0
    _within(src, center, math.hypot(sx, sy) / 2, what, keys["rect"].line)
    return FloorPatch("rect", center, color, size=(sx, sy), yaw=yaw, name=name, line=node.line)


def _within(src: Source, center, reach: float, what: str, line: int) -> None:
    if max(abs(center[0]), abs(center[1])) + reach > LIMIT:
        src.fail(f"{what} reaches farther than {LIMIT:g} m from the origin", line, hint="coordinates are in metres")


def _check_names(src: Source, lines, patches) -> None:
    """Every line and patch names a link of its own: two given the same name, or a name another one gets by
    default (``patch_0``), are refused."""
    taken: dict = {}
    for kind, items in (("line", lines), ("patch", patches)):
        for i, item in enumerate(items):
            name = item.name or f"{kind}_{i}"
            if name in taken:
                what = f"{kind} name '{name}'" if item.name else f"{name} (the name an unnamed {kind} gets)"
                src.fail(f"{what} is already the name of {taken[name]}", item.line,
                         hint="give every line and patch its own name")
            taken[name] = f"the {kind} on line {item.line}"
