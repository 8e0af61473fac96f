"""Sine, cosine and arc tangent from + − × ÷ and √ only, so that a generated spec is the same on every machine.

IEEE 754 rounds those five operations exactly the same everywhere; the C library's ``sin``, ``cos`` and ``atan2``
(behind :mod:`math`) may differ in the last bit between platforms and versions, and a last bit is enough to turn
a coordinate written to the millimetre one way or the other. These are accurate to a few units in the last place,
which is far below the millimetre the generators round to.
"""

from __future__ import annotations

import math

PI = 3.141592653589793
TAU = 2 * PI
HALF_PI = PI / 2
QUARTER_PI = PI / 4


def _sin_small(x: float) -> float:
    """sin x for |x| ≤ π/4, Taylor series to x^19 (the next term is below 2⁻⁶⁰)."""
    x2 = x * x
    term, total = x, x
    for n in range(1, 10):
        term = -term * x2 / ((2 * n) * (2 * n + 1))
        total += term
    return total


def _cos_small(x: float) -> float:
    """cos x for |x| ≤ π/4, Taylor series to x^20."""
    x2 = x * x
    term, total = 1.0, 1.0
    for n in range(1, 11):
        term = -term * x2 / ((2 * n - 1) * (2 * n))
        total += term
    return total


def sin_cos(angle: float) -> tuple[float, float]:
    """(sin, cos) of ``angle`` (radians), reduced by quarter turns."""
    quarter = round(angle / HALF_PI)   # Python's round is exact: the same quarter everywhere
    x = angle - quarter * HALF_PI
    s, c = _sin_small(x), _cos_small(x)
    q = quarter % 4
    if q == 0:
        return s, c
    if q == 1:
        return c, -s
    if q == 2:
        return -s, -c
    return -c, s


def _atan_unit(x: float) -> float:
    """atan x for 0 ≤ x ≤ 1: halved twice with atan x = 2·atan(x / (1 + √(1 + x²))) to |x| ≤ 0.2, then its series."""
    halvings = 0
    while x > 0.2:
        x = x / (1.0 + math.sqrt(1.0 + x * x))   # sqrt is exactly rounded (IEEE 754); pow is not
        halvings += 1
    x2 = x * x
    term, total = x, x
    for n in range(1, 16):
        term = -term * x2
        total += term / (2 * n + 1)
    return total * (2 ** halvings)


def atan2(y: float, x: float) -> float:
    """The angle of the vector (x, y) in (−π, π], as :func:`math.atan2` (0 for the zero vector)."""
    if x == 0 and y == 0:
        return 0.0
    ax, ay = abs(x), abs(y)
    angle = _atan_unit(ay / ax) if ay <= ax else HALF_PI - _atan_unit(ax / ay)
    if x < 0:
        angle = PI - angle
    return -angle if y < 0 else angle
