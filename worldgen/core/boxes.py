"""Box corners: the eight vertices of an axis-aligned box centred on its own frame."""

from __future__ import annotations


def box_corners(size) -> "np.ndarray":
    """The 8 corners (8 × 3) of a box of full ``size`` (x, y, z) centred on its own frame."""
    import numpy as np

    hx, hy, hz = (s / 2 for s in size)
    return np.array([[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
