"""``track``: a closed loop of tape on the floor of a room, a smooth random curve whose tightest bend is no
tighter than ``min_radius``, for ``worldgen run --task line-follow``.

The curve is star-shaped round the room's centre: at angle θ its distance is r(θ) = 1 + Σ a_k cos(kθ + φ_k) for
k = 2, 3, 4 (random a_k, φ_k; r stays between 0.61 and 1.39, so it never crosses itself), stretched to fill the
room less :data:`WALL_MARGIN` from each wall. Its curvature is worked out from the exact derivatives of that
formula at 360 angles; while its tightest bend is tighter than ``min_radius`` (with 10 % to spare) the wobbles
are damped and it is tried again, down to an ellipse, which :func:`resolve` makes sure is gentle enough. The tape
is laid through points at most 6 cm apart. The robot (a TurtleBot3 with a camera) starts on the tape at θ = 0,
facing along it counter-clockwise.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from functools import lru_cache
from typing import List, Tuple

from ..spec.model import Material, FloorLine, RobotPose, Room, Spec, WallStyle
from .options import TrackOptions
from .rng import Rng
from .robot import RobotSpace
from .shapes import Point
from .trig import TAU, atan2, sin_cos

THICKNESS = 0.15
GRAIN = 0.05
WALL_MARGIN = 0.65     # m: from the tape's centre-line to a wall's face, more than a Waffle's turning circle
SAMPLES = 360          # angles the curve is measured at (a degree apart)
FINER = (720, 1440, 2880, 4320)   # the tape's angles in a room too big for SAMPLES points 6 cm apart
SPACING = 0.06         # m: the tape's points are at most this far apart
SPARE = 1.1            # the tightest bend is kept this much gentler than the limit
AMPLITUDES = (0.2, 0.12, 0.07)    # the largest a_2, a_3, a_4
DAMPING = (1.0, 0.6, 0.35, 0.15, 0.0)
COLOUR_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*(/[A-Za-z0-9_]+)+$")


def _half_extents(options: TrackOptions) -> Tuple[float, float]:
    w, h = options.size
    return w / 2 - THICKNESS / 2 - WALL_MARGIN, h / 2 - THICKNESS / 2 - WALL_MARGIN


def resolve(options: TrackOptions, space: RobotSpace) -> TrackOptions:
    from ..core.errors import InputError

    if not space.camera:
        raise InputError(f"the {space.model} has no camera to follow a line with",
                         hint="leave out --robot (the Waffle Pi), or give --robot waffle")
    if not COLOUR_NAME.match(options.color):
        raise InputError(f"--color {options.color!r} is not a Gazebo material name",
                         hint="give a name such as Gazebo/Yellow, Gazebo/Red, Gazebo/Blue or Gazebo/Black")
    options = replace(options, size=tuple(round(round(v / GRAIN) * GRAIN, 3) for v in options.size))
    ax, ay = _half_extents(options)
    tightest = min(ax * ax / ay, ay * ay / ax) if min(ax, ay) > 0 else 0.0   # an ellipse's tightest bend
    if min(ax, ay) < 0.5 or tightest < SPARE * options.min_radius:
        need = 2 * (THICKNESS / 2 + WALL_MARGIN + max(0.5, SPARE * options.min_radius))
        raise InputError(f"--size {options.size[0]:g}x{options.size[1]:g} is too small for a loop whose bends are "
                         f"no tighter than {options.min_radius:g} m, {WALL_MARGIN:g} m from the walls",
                         hint=f"make the room at least about {need:.1f} m each way, or lower --min-radius")
    return options


@lru_cache(maxsize=len(FINER) + 1)
def _circle(n: int) -> Tuple[Tuple[float, float], ...]:
    """(sin, cos) of the ``n`` angles 2πi/n, worked out once."""
    return tuple(sin_cos(TAU * i / n) for i in range(n))


class _Curve:
    """x(θ) = sx·r(θ)·cos θ, y(θ) = sy·r(θ)·sin θ with r as in the module docstring, and its derivatives, at the
    angles θ_i = 2πi/:data:`SAMPLES` (kθ_i + φ by the angle-sum rule from one table: no trigonometry per point)."""

    def __init__(self, terms: List[Tuple[int, float, float]], sx: float = 1.0, sy: float = 1.0):
        self.terms, self.sx, self.sy = terms, sx, sy
        self.phases = [(k, a) + sin_cos(phase) for k, a, phase in terms]

    def at(self, i: int, n: int = SAMPLES) -> Tuple[Point, Point, Point]:
        """The point at θ = 2πi/n, its first and second derivatives in θ."""
        circle = _circle(n)
        r, r1, r2 = 1.0, 0.0, 0.0
        for k, a, sp, cp in self.phases:
            sk, ck = circle[(k * i) % n]
            s, c = sk * cp + ck * sp, ck * cp - sk * sp   # sin and cos of kθ + φ
            r, r1, r2 = r + a * c, r1 - k * a * s, r2 - k * k * a * c
        s, c = circle[i]
        sx, sy = self.sx, self.sy
        return ((sx * r * c, sy * r * s), (sx * (r1 * c - r * s), sy * (r1 * s + r * c)),
                (sx * (r2 * c - 2 * r1 * s - r * c), sy * (r2 * s + 2 * r1 * c - r * s)))

    def point(self, i: int, n: int = SAMPLES) -> Point:
        """The point at θ = 2πi/n alone."""
        circle = _circle(n)
        r = 1.0
        for k, a, sp, cp in self.phases:
            sk, ck = circle[(k * i) % n]
            r += a * (ck * cp - sk * sp)
        s, c = circle[i]
        return (self.sx * r * c, self.sy * r * s)

    def measure(self) -> Tuple[float, float]:
        """(the smallest radius of curvature, the largest |dP/dθ|) over the :data:`SAMPLES` angles."""
        tightest, fastest = math.inf, 0.0
        for i in range(SAMPLES):
            _, (dx, dy), (ddx, ddy) = self.at(i)
            speed2 = dx * dx + dy * dy
            speed = math.sqrt(speed2)
            fastest = max(fastest, speed)
            bend = abs(dx * ddy - dy * ddx)
            if bend > 0:
                tightest = min(tightest, speed2 * speed / bend)
        return tightest, fastest


def _fitted(terms, ax: float, ay: float) -> _Curve:
    """The curve stretched so that its points just fill [−ax, ax] × [−ay, ay]."""
    unit = _Curve(terms)
    points = [unit.point(i) for i in range(SAMPLES)]
    return _Curve(terms, ax / max(abs(p[0]) for p in points), ay / max(abs(p[1]) for p in points))


def _points(curve: _Curve, fastest: float) -> List[Point]:
    """The tape's points: every step-th of the :data:`SAMPLES` angles, the step as large as keeps them at most
    :data:`SPACING` apart (``fastest``: the largest |dP/dθ|), or all of :data:`FINER` angles in a big room."""
    need = TAU * fastest / SPACING
    if need > SAMPLES:
        n = next((n for n in FINER if n >= need), FINER[-1])
        return [(round(x, 3), round(y, 3)) for x, y in (curve.point(i, n) for i in range(n))]
    step = max(k for k in range(1, SAMPLES + 1) if SAMPLES % k == 0 and SAMPLES / k >= need)
    return [(round(x, 3), round(y, 3)) for x, y in (curve.point(i) for i in range(0, SAMPLES, step))]


def make(name: str, options: TrackOptions, space: RobotSpace, rng: Rng) -> Tuple[Spec, str]:
    ax, ay = _half_extents(options)
    drawn = [(k, rng.uniform(-top, top), rng.uniform(0, TAU)) for k, top in zip((2, 3, 4), AMPLITUDES)]
    for damping in DAMPING:
        curve = _fitted([(k, a * damping, phase) for k, a, phase in drawn], ax, ay)
        tightest, fastest = curve.measure()
        if tightest >= SPARE * options.min_radius:
            break
    points = _points(curve, fastest)
    _, (dx, dy), _ = curve.at(0)
    w, h = options.size
    style = WallStyle(THICKNESS, options.wall_height, Material())
    room = Room("room", ((-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)), style)
    tape = FloorLine(tuple(points), options.tape_width, Material(options.color), closed=True, name="track")
    spec = Spec(name=name, style=style, rooms=(room,), lines=(tape,),
                robot=RobotPose(options.robot, points[0], round(atan2(dy, dx), 4)))
    length = sum(math.sqrt((points[i][0] - points[i - 1][0]) ** 2 + (points[i][1] - points[i - 1][1]) ** 2)
                 for i in range(len(points)))
    return spec, (f"a {w:g} x {h:g} m room with a {length:.1f} m loop of {options.color} tape, its tightest bend "
                  f"{tightest:.2f} m in radius")
