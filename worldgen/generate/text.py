"""A :class:`~worldgen.spec.model.Spec` written as spec text, in one fixed layout, byte for byte the same each time.

The layout is the README's: ``name``, ``walls``, then ``rooms`` (a ``rect`` when the room is an axis-aligned
rectangle listed from its minimum corner counter-clockwise, as the reader makes one; a ``polygon`` otherwise),
``segments``, ``obstacles``, ``lines``, ``patches`` and ``robot``, one flow mapping per item, keys in the reader's
order, values left out where they are the reader's defaults. Numbers are written to the millimetre (angles to
0.1 mrad) with :func:`number`, so reading the text back gives the numbers the generator meant. A header of
comment lines goes first. :func:`worldgen.spec.load.parse_spec` reads the text back into an equal spec.
"""

from __future__ import annotations

from typing import Iterable, List, Sequence

from ..spec.model import (DOOR_HEIGHT, DOOR_WIDTH, LINE_WIDTH, WINDOW_HEIGHT, WINDOW_SILL,
                          WINDOW_WIDTH, FloorLine, FloorPatch, Material, Obstacle, Opening, Room, Segment, Spec,
                          WallStyle)

LINE_LIMIT = 116   # characters: long point lists wrap after this


def number(value: float, places: int = 3) -> str:
    """``value`` rounded to ``places`` decimals, without trailing zeros (``1.5``, ``2``, ``-0.25``; never ``-0``)."""
    text = f"{value:.{places}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def angle(value: float) -> str:
    return number(value, 4)


def point(p: Sequence[float]) -> str:
    return f"[{number(p[0])}, {number(p[1])}]"


def material(m: Material) -> str:
    if m.rgba is not None:
        return "[" + ", ".join(number(v) for v in m.rgba) + "]"
    return str(m.script)


def _style(style: WallStyle, base: WallStyle | None) -> str | None:
    """A ``walls:`` mapping of the keys that differ from ``base`` (from the reader's defaults when None)."""
    base = base or WallStyle()
    parts = []
    if style.thickness != base.thickness:
        parts.append(f"thickness: {number(style.thickness)}")
    if style.height != base.height:
        parts.append(f"height: {number(style.height)}")
    if style.material != base.material:
        parts.append(f"material: {material(style.material)}")
    return "{" + ", ".join(parts) + "}" if parts else None


def _is_rect(vertices) -> bool:
    if len(vertices) != 4:
        return False
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = vertices
    return y0 == y1 and x1 == x2 and y2 == y3 and x3 == x0 and x1 > x0 and y2 > y1


def _opening(o: Opening) -> str:
    parts = [f"type: {o.type}", f"wall: {o.wall}", f"offset: {number(o.offset)}"]
    door = o.type == "door"
    if o.width != (DOOR_WIDTH if door else WINDOW_WIDTH):
        parts.append(f"width: {number(o.width)}")
    if o.height != (DOOR_HEIGHT if door else WINDOW_HEIGHT):
        parts.append(f"height: {number(o.height)}")
    if not door and o.sill != WINDOW_SILL:
        parts.append(f"sill: {number(o.sill)}")
    return "{" + ", ".join(parts) + "}"


def _room(room: Room, base: WallStyle) -> List[str]:
    lines = [f"  - name: {room.name}"]
    if _is_rect(room.vertices):
        (x0, y0), _, (x1, y1), _ = room.vertices
        centre = ((x0 + x1) / 2, (y0 + y1) / 2)
        lines.append(f"    rect: {{center: {point(centre)}, size: [{number(x1 - x0)}, {number(y1 - y0)}]}}")
    else:
        lines += _wrapped("    polygon: ", [point(v) for v in room.vertices])
    style = _style(room.style, base)
    if style:
        lines.append(f"    walls: {style}")
    if room.openings:
        lines.append("    openings:")
        lines += [f"      - {_opening(o)}" for o in room.openings]
    return lines


def _segment(segment: Segment, base: WallStyle) -> str:
    parts = [f"from: {point(segment.start)}", f"to: {point(segment.end)}"]
    style = _style(segment.style, base)
    if style:
        parts.append(f"walls: {style}")
    if segment.openings:
        parts.append("openings: [" + ", ".join(_opening(o) for o in segment.openings) + "]")
    return "  - {" + ", ".join(parts) + "}"


def _obstacle(o: Obstacle) -> str:
    parts = [f"name: {o.name}"] if o.name else []
    parts.append(f"shape: {o.shape}")
    if o.shape == "box":
        parts.append("size: [" + ", ".join(number(v) for v in o.size) + "]")
    else:
        parts.append(f"radius: {number(o.radius)}")
        if o.shape == "cylinder":
            parts.append(f"height: {number(o.height)}")
    parts.append(f"at: {point(o.at)}")
    if o.yaw:
        parts.append(f"yaw: {angle(o.yaw)}")
    if o.material != Material():
        parts.append(f"material: {material(o.material)}")
    return "  - {" + ", ".join(parts) + "}"


def _line(line: FloorLine) -> List[str]:
    lines = [f"  - name: {line.name}"] if line.name else ["  -"]
    if line.closed:
        lines.append("    closed: true")
    if line.width != LINE_WIDTH:
        lines.append(f"    width: {number(line.width)}")
    lines.append(f"    color: {material(line.color)}")
    lines += _wrapped("    points: ", [point(p) for p in line.points])
    if lines[0] == "  -":   # an unnamed line: its first key goes on the dash's line
        lines[1:2] = ["  - " + lines[1].lstrip()]
        del lines[0]
    return lines


def _patch(p: FloorPatch) -> str:
    parts = [f"name: {p.name}"] if p.name else []
    if p.shape == "disc":
        parts.append(f"disc: {{center: {point(p.center)}, radius: {number(p.radius)}}}")
    else:
        yaw = f", yaw: {angle(p.yaw)}" if p.yaw else ""
        parts.append(f"rect: {{center: {point(p.center)}, size: [{number(p.size[0])}, {number(p.size[1])}]{yaw}}}")
    parts.append(f"color: {material(p.color)}")
    return "  - {" + ", ".join(parts) + "}"


def _wrapped(lead: str, items: Iterable[str]) -> List[str]:
    """``lead`` followed by a flow list of ``items``, wrapped under it at :data:`LINE_LIMIT` characters."""
    lines, current = [], lead + "["
    indent = " " * (len(lead) + 1)
    items = list(items)
    for i, item in enumerate(items):
        text = item + ("," if i < len(items) - 1 else "]")
        if len(current) + 1 + len(text) > LINE_LIMIT and not current.endswith("["):
            lines.append(current)
            current = indent + text
        else:
            current += ("" if current.endswith("[") else " ") + text
    lines.append(current if items else lead + "[]")
    return lines


def spec_text(spec: Spec, header: Sequence[str] = ()) -> str:
    """The spec as text, ``header`` lines first as comments."""
    out = [f"# {line}".rstrip() for line in header]
    out.append(f"name: {spec.name}")
    style = _style(spec.style, None)
    if style:
        out.append(f"walls: {style}")
    if spec.rooms:
        out.append("rooms:")
        for room in spec.rooms:
            out += _room(room, spec.style)
    if spec.segments:
        out.append("segments:")
        out += [_segment(s, spec.style) for s in spec.segments]
    if spec.obstacles:
        out.append("obstacles:")
        out += [_obstacle(o) for o in spec.obstacles]
    if spec.lines:
        out.append("lines:")
        for line in spec.lines:
            out += _line(line)
    if spec.patches:
        out.append("patches:")
        out += [_patch(p) for p in spec.patches]
    if spec.robot is not None:
        r = spec.robot
        yaw = f", yaw: {angle(r.yaw)}" if r.yaw else ""
        out.append(f"robot: {{model: {r.model}, at: {point(r.at)}{yaw}}}")
    return "\n".join(out) + "\n"

