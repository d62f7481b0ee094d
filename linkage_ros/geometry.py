"""Small pure functions on points, frames and rotations. Arrays in, arrays out; no state.

Units are whatever the caller passes (the package uses mm); angles in radians.
"""

import math

import numpy as np


def unit(v):
    """v / |v| along the last axis."""
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def cross(a, b):
    """Cross product along the last axis; faster than np.cross for small arrays."""
    out = np.empty(a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def exp_so3(omega):
    """Rotation matrix of the rotation vector omega (Rodrigues), shape (..., 3) -> (..., 3, 3).

    R = I + a K + b (w w^T - |w|^2 I) with K = [w]x, a = sin t / t, b = (1 - cos t) / t^2.

    >>> bool(np.allclose(exp_so3(np.array([0, 0, np.pi / 2])) @ [1, 0, 0], [0, 1, 0]))
    True
    """
    omega = np.asarray(omega, dtype=float)
    if omega.ndim == 1:
        return _exp_so3_one(*omega)
    t2 = np.einsum('...i,...i->...', omega, omega)
    t = np.sqrt(t2)
    small = t2 < 1e-16
    safe = np.where(small, 1.0, t)
    a = np.where(small, 1.0 - t2 / 6.0, np.sin(safe) / safe)[..., None, None]
    b = np.where(small, 0.5 - t2 / 24.0, (1.0 - np.cos(safe)) / safe**2)[..., None, None]
    x, y, z = omega[..., 0], omega[..., 1], omega[..., 2]
    k = np.zeros(omega.shape[:-1] + (3, 3))
    k[..., 0, 1], k[..., 0, 2], k[..., 1, 2] = -z, y, -x
    k[..., 1, 0], k[..., 2, 0], k[..., 2, 1] = z, -y, x
    outer = omega[..., :, None] * omega[..., None, :] - t2[..., None, None] * np.eye(3)
    return np.eye(3) + a * k + b * outer


def _exp_so3_one(x, y, z):
    """exp_so3 of one rotation vector, in scalar arithmetic (the hot path of a single solve)."""
    t2 = x * x + y * y + z * z
    if t2 < 1e-16:
        a, b = 1.0 - t2 / 6.0, 0.5 - t2 / 24.0
    else:
        t = math.sqrt(t2)
        a, b = math.sin(t) / t, (1.0 - math.cos(t)) / t2
    return np.array([[1.0 - b * (y * y + z * z), b * x * y - a * z, b * x * z + a * y],
                     [b * x * y + a * z, 1.0 - b * (x * x + z * z), b * y * z - a * x],
                     [b * x * z - a * y, b * y * z + a * x, 1.0 - b * (x * x + y * y)]])


def quaternion_from_matrix(rot):
    """Unit quaternion (x, y, z, w) of a rotation matrix, with w >= 0 (Shepperd's method)."""
    m = np.asarray(rot, dtype=float)
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    candidates = (trace, m[0, 0], m[1, 1], m[2, 2])
    i = int(np.argmax(candidates))
    if i == 0:
        s = 2.0 * np.sqrt(1.0 + trace)
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4]
    elif i == 1:
        s = 2.0 * np.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s]
    elif i == 2:
        s = 2.0 * np.sqrt(1.0 - m[0, 0] + m[1, 1] - m[2, 2])
        q = [(m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 - m[0, 0] - m[1, 1] + m[2, 2])
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4, (m[1, 0] - m[0, 1]) / s]
    q = np.array(q)
    return q if q[3] >= 0 else -q


def frame_from_points(m, n, p):
    """Orthonormal frame (columns e_x, e_y, e_z) of three non-collinear points.

    e_x along N - M, e_y in the M-N-P plane towards P, e_z = e_x x e_y.
    """
    ex = unit(n - m)
    v = p - m
    ey = unit(v - (v @ ex) * ex)
    return np.column_stack((ex, ey, np.cross(ex, ey)))


def trilaterate(m, n, p, radii, sign):
    """Point at distances radii = (|BM|, |BN|, |BP|) from M, N, P: eqs. 5-7 of the paper.

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


def local_coordinates(m, n, p, point):
    """Coordinates of point in the frame_from_points(m, n, p) frame, origin M."""
    return frame_from_points(m, n, p).T @ (point - m)


def camber_toe(spin_axis, side_sign):
    """Camber and toe (rad) of outboard spin-axis unit vector(s), shape (..., 3).

    camber = -atan2(a_z, |a_xy|): + = top of the wheel outboard (eq. 14 made side-aware).
    toe = atan2(a_x, a_y_outboard): + = toe-in. side_sign: +1 left wheel, -1 right wheel.
    """
    a = np.asarray(spin_axis, dtype=float)
    camber = -np.arctan2(a[..., 2], np.hypot(a[..., 0], a[..., 1]))
    toe = np.arctan2(a[..., 0], side_sign * a[..., 1])
    return camber, toe
