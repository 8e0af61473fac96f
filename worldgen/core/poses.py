"""Rigid transforms as SDF means them: 4 × 4 numpy matrices built from ``x y z roll pitch yaw``.

SDF's roll-pitch-yaw is a rotation about the *fixed* axes x, then y, then z:
``R = Rz(yaw) · Ry(pitch) · Rx(roll)``.
A pose in a parent frame composes by matrix product: ``world_T_child = world_T_parent @ parent_T_child``.
"""

from __future__ import annotations

import math

import numpy as np

IDENTITY = np.eye(4)
IDENTITY.setflags(write=False)  # shared: never changed in place


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """The 3 × 3 rotation of a fixed-axis roll-pitch-yaw (SDF and URDF convention)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def quat_matrix(x: float, y: float, z: float, w: float) -> np.ndarray:
    """The 3 × 3 rotation of a quaternion given as x, y, z, w (normalised here)."""
    n = math.sqrt(x * x + y * y + z * z + w * w) or 1.0
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def transform(position=(0.0, 0.0, 0.0), rotation: np.ndarray | None = None) -> np.ndarray:
    """A 4 × 4 transform from a translation and an optional 3 × 3 rotation."""
    t = np.eye(4)
    if rotation is not None:
        t[:3, :3] = rotation
    t[:3, 3] = position
    return t


def pose_matrix(x: float, y: float, z: float, roll: float, pitch: float, yaw: float) -> np.ndarray:
    """The 4 × 4 transform of an SDF ``<pose>x y z roll pitch yaw</pose>``."""
    return transform((x, y, z), rpy_matrix(roll, pitch, yaw))


def inverse(t: np.ndarray) -> np.ndarray:
    """The inverse of a rigid transform (rotation transposed, translation rotated back)."""
    inv = np.eye(4)
    rt = t[:3, :3].T
    inv[:3, :3] = rt
    inv[:3, 3] = -rt @ t[:3, 3]
    return inv


def matrix_quat(r: np.ndarray) -> tuple[float, float, float, float]:
    """The unit quaternion (x, y, z, w) of a 3 × 3 rotation, with w ≥ 0 (pybullet's order)."""
    m00, m01, m02 = float(r[0, 0]), float(r[0, 1]), float(r[0, 2])
    m10, m11, m12 = float(r[1, 0]), float(r[1, 1]), float(r[1, 2])
    m20, m21, m22 = float(r[2, 0]), float(r[2, 1]), float(r[2, 2])
    trace = m00 + m11 + m22
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    n = math.sqrt(sum(c * c for c in q))
    sign = -1.0 if q[3] < 0 else 1.0
    return tuple(sign * c / n for c in q)  # type: ignore[return-value]


def yaw_of(t: np.ndarray) -> float:
    """The heading (rotation about world z) of a transform's x axis."""
    return math.atan2(float(t[1, 0]), float(t[0, 0]))
