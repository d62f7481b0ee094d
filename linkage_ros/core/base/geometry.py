# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Small pure functions on points, frames and rotations. Arrays in, arrays out; no state.

Units are whatever the caller passes (the package uses mm); angles in radians. Rotations are
converted here and nowhere else: rotation vector -> matrix (exp_so3), matrix <-> quaternion
(x, y, z, w), spin axis -> camber and toe; the compiled forms are so3.py's.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from . import so3
from .patch import point_velocity  # noqa: F401 (the face's, beside the other formulas)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

M_PER_MM = 1e-3   # the core works in mm; ROS messages and recordings are in m
MM_PER_M = 1e3
N_MM_PER_NM_DEG = MM_PER_M * 180.0 / math.pi   # a torsional rate: N m/deg -> N mm/rad


def unit(v: ArrayLike) -> np.ndarray:
    """Return v / |v| along the last axis."""
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def perpendicular(axis: ArrayLike) -> np.ndarray:
    """Return a unit vector square to axis (3,): axis x z, or axis x x when axis is near z."""
    axis = unit(axis)
    helper = [0.0, 0.0, 1.0] if abs(axis[2]) < 0.9 else [1.0, 0.0, 0.0]
    return unit(np.cross(axis, helper))


def carrier_points(offsets: ArrayLike, center: ArrayLike, rotation: ArrayLike) -> np.ndarray:
    """
    Return the carrier points M + R b of a pose.

    offsets b = b0 - M0 (m, 3) are the design points' offsets from the design wheel centre,
    M (..., 3) the wheel centre and R (..., 3, 3) the rotation relative to design. Returns
    (..., m, 3), same units as offsets and center (mm).
    """
    return np.asarray(center)[..., None, :] + np.asarray(offsets) @ np.swapaxes(
        np.asarray(rotation), -1, -2)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return the cross product along the last axis; faster than np.cross for small arrays."""
    out = np.empty(a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def exp_so3(omega: ArrayLike) -> np.ndarray:
    """
    Return the rotation matrix of rotation vector omega (Rodrigues): (..., 3) -> (..., 3, 3).

    >>> bool(np.allclose(exp_so3(np.array([0, 0, np.pi / 2])) @ [1, 0, 0], [0, 1, 0]))
    True
    """
    omega = np.asarray(omega, dtype=float)
    flat = np.ascontiguousarray(omega.reshape(-1, 3))
    out = np.empty((len(flat), 3, 3))
    so3.exp_so3_many(flat, out)
    return out.reshape(omega.shape[:-1] + (3, 3))


def quaternion_from_matrix(rot: ArrayLike) -> np.ndarray:
    """Return unit quaternions (x, y, z, w) of rotation matrices (..., 3, 3), w >= 0 (Shepperd)."""
    rot = np.asarray(rot, dtype=float)
    flat = np.ascontiguousarray(rot.reshape(-1, 3, 3))
    out = np.empty((len(flat), 4))
    so3.quaternion_many(flat, out)
    return out.reshape(rot.shape[:-2] + (4,))


def matrix_from_quaternion(q: ArrayLike) -> np.ndarray:
    """
    Return the rotation matrices (..., 3, 3) of quaternions (..., 4) as (x, y, z, w).

    The quaternions are normalised first (a recorded one holds to float64 rounding only);
    q and -q give the same matrix. The inverse of quaternion_from_matrix.
    """
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def frame_from_points(m: np.ndarray, n: np.ndarray, p: np.ndarray) -> np.ndarray:
    """
    Return the orthonormal frame (columns e_x, e_y, e_z) of three non-collinear points.

    e_x along N - M, e_y in the M-N-P plane towards P, e_z = e_x x e_y.
    """
    ex = unit(n - m)
    v = p - m
    ey = unit(v - (v @ ex) * ex)
    return np.column_stack((ex, ey, np.cross(ex, ey)))


def trilaterate(m: np.ndarray, n: np.ndarray, p: np.ndarray, radii: ArrayLike,
                sign: float) -> tuple[np.ndarray | None, float]:
    """
    Locate the point at distances radii = (|BM|, |BN|, |BP|) from M, N, P (eqs. 5-7).

    Subtracting the first sphere equation from the other two leaves two linear equations
    (eq. 6); the first then gives a quadratic for the remaining coordinate (eq. 7). Solved
    in the M-N-P frame rather than global axes, so the linear step never degenerates.
    sign (+1 or -1) picks the root on the same side of the M-N-P plane as at design.
    Returns (B, discriminant); B is None when the spheres do not meet (discriminant < 0).
    """
    frame = frame_from_points(m, n, p)
    d = np.linalg.norm(n - m)
    i, j = (p - m) @ frame[:, 0], (p - m) @ frame[:, 1]
    r1, r2, r3 = radii
    x = (r1**2 - r2**2 + d**2) / (2 * d)
    y = (r1**2 - r3**2 + i**2 + j**2) / (2 * j) - i * x / j
    disc = r1**2 - x**2 - y**2
    if disc < 0:
        return None, disc
    return m + frame @ np.array([x, y, sign * np.sqrt(disc)]), disc


def local_coordinates(m: np.ndarray, n: np.ndarray, p: np.ndarray,
                      point: np.ndarray) -> np.ndarray:
    """Return the coordinates of point in the frame_from_points(m, n, p) frame, origin M."""
    return frame_from_points(m, n, p).T @ (point - m)


def spin_axis_of(camber: float, toe: float, side_sign: float) -> np.ndarray:
    """
    Return the outboard spin-axis unit vector (3,) of a camber and toe (rad): camber_toe's inverse.

    a = (cos c sin t, s cos c cos t, -sin c), s = side_sign (+1 left, -1 right); camber + =
    top outboard, toe + = toe-in. Chrono::Vehicle turns its left spindle so too (Rz(-toe)
    Rx(-camber), ChDoubleWishbone::Initialize).
    """
    return np.array([math.cos(camber) * math.sin(toe), side_sign * math.cos(camber)
                     * math.cos(toe), -math.sin(camber)])


def camber_toe(spin_axis: ArrayLike,
               side_sign: float) -> tuple[float | np.ndarray, float | np.ndarray]:
    """
    Return camber and toe (rad) of outboard spin-axis unit vector(s), shape (..., 3).

    camber = -atan2(a_z, |a_xy|): + = top of the wheel outboard (eq. 14 made side-aware).
    toe = atan2(a_x, a_y_outboard): + = toe-in. side_sign: +1 left wheel, -1 right wheel.
    """
    axes = np.asarray(spin_axis, dtype=float)
    flat = np.ascontiguousarray(axes.reshape(-1, 3))
    camber, toe = np.empty(len(flat)), np.empty(len(flat))
    so3.camber_toe_many(flat, float(side_sign), camber, toe)
    if axes.ndim == 1:
        return camber[0], toe[0]
    return camber.reshape(axes.shape[:-1]), toe.reshape(axes.shape[:-1])
