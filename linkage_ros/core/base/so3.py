# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled rotations and angles: the leaves of the kernels (numba).

A rotation is a (3, 3) matrix R; a rotation vector (x, y, z) has the rotation's angle (rad)
as its length and its axis as its direction; a quaternion is (x, y, z, w) with w >= 0.
Camber and toe follow the package's conventions (+ = top outboard, + = toe-in). geometry.py
gives these to Python code on arrays of any shape.

Every kernel compiles these in; base/compiled.py's one cache key makes an edit here
recompile them all.
"""

import math

from .compiled import jit


@jit
def rotate(rotation, x, y, z):
    """Return R v for v = (x, y, z), as three floats."""
    return (rotation[0, 0] * x + rotation[0, 1] * y + rotation[0, 2] * z,
            rotation[1, 0] * x + rotation[1, 1] * y + rotation[1, 2] * z,
            rotation[2, 0] * x + rotation[2, 1] * y + rotation[2, 2] * z)


@jit
def exp_so3(x, y, z, out):
    """
    Write into out (3, 3) the rotation matrix of the rotation vector (x, y, z) (Rodrigues).

    R = I + a K + b (w w^T - |w|^2 I), K = [w]x, a = sin t / t, b = (1 - cos t) / t^2.
    """
    t2 = x * x + y * y + z * z
    if t2 < 1e-16:
        a, b = 1.0 - t2 / 6.0, 0.5 - t2 / 24.0
    else:
        t = math.sqrt(t2)
        a, b = math.sin(t) / t, (1.0 - math.cos(t)) / t2
    out[0, 0], out[0, 1], out[0, 2] = (
        1.0 - b * (y * y + z * z), b * x * y - a * z, b * x * z + a * y)
    out[1, 0], out[1, 1], out[1, 2] = (
        b * x * y + a * z, 1.0 - b * (x * x + z * z), b * y * z - a * x)
    out[2, 0], out[2, 1], out[2, 2] = (
        b * x * z - a * y, b * y * z + a * x, 1.0 - b * (x * x + y * y))


@jit
def turn(x, y, z, rotation, out):
    """Write exp_so3(x, y, z) @ rotation into out (3, 3); out may be rotation itself."""
    # exp_so3's entries as scalars: the bare statics kernels call this, and they allocate
    # nothing (numba without reference counting refuses np.empty here)
    t2 = x * x + y * y + z * z
    if t2 < 1e-16:
        a, b = 1.0 - t2 / 6.0, 0.5 - t2 / 24.0
    else:
        t = math.sqrt(t2)
        a, b = math.sin(t) / t, (1.0 - math.cos(t)) / t2
    s00, s01, s02 = 1.0 - b * (y * y + z * z), b * x * y - a * z, b * x * z + a * y
    s10, s11, s12 = b * x * y + a * z, 1.0 - b * (x * x + z * z), b * y * z - a * x
    s20, s21, s22 = b * x * z - a * y, b * y * z + a * x, 1.0 - b * (x * x + y * y)
    for j in range(3):   # column by column, so that out may be rotation
        c0, c1, c2 = rotation[0, j], rotation[1, j], rotation[2, j]
        out[0, j] = s00 * c0 + s01 * c1 + s02 * c2
        out[1, j] = s10 * c0 + s11 * c1 + s12 * c2
        out[2, j] = s20 * c0 + s21 * c1 + s22 * c2


@jit
def quaternion(rotation, out):
    """Write into out (4,) the unit quaternion of rotation as x, y, z, w; w >= 0 (Shepperd)."""
    m = rotation
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace >= m[0, 0] and trace >= m[1, 1] and trace >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + trace)
        x, y, z, w = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s,
                      (m[1, 0] - m[0, 1]) / s, s / 4)
    elif m[0, 0] >= m[1, 1] and m[0, 0] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        x, y, z, w = (s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s,
                      (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] + m[1, 1] - m[2, 2])
        x, y, z, w = ((m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s,
                      (m[0, 2] - m[2, 0]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] - m[1, 1] + m[2, 2])
        x, y, z, w = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4,
                      (m[1, 0] - m[0, 1]) / s)
    sign = 1.0 if w >= 0.0 else -1.0
    out[0], out[1], out[2], out[3] = sign * x, sign * y, sign * z, sign * w


@jit
def camber_toe(ax, ay, az, side_sign):
    """
    Return camber and toe (rad) of an outboard spin-axis vector a (any length).

    camber = -atan2(a_z, |a_xy|): + = top of the wheel outboard (eq. 14 made side-aware);
    toe = atan2(a_x, a_y_outboard): + = toe-in. side_sign: +1 left wheel, -1 right wheel.
    """
    return -math.atan2(az, math.hypot(ax, ay)), math.atan2(ax, side_sign * ay)


# --- batches -------------------------------------------------------------------------------

@jit
def exp_so3_many(omegas, out):
    """Write the rotation matrices of n rotation vectors omegas (n, 3) into out (n, 3, 3)."""
    for n in range(omegas.shape[0]):
        exp_so3(omegas[n, 0], omegas[n, 1], omegas[n, 2], out[n])


@jit
def quaternion_many(rotations, out):
    """Write the quaternions (x, y, z, w) of rotations (n, 3, 3) into out (n, 4)."""
    for n in range(rotations.shape[0]):
        quaternion(rotations[n], out[n])


@jit
def camber_toe_many(axes, side_sign, camber, toe):
    """Write camber and toe (rad) of n spin-axis vectors axes (n, 3) into camber, toe (n,)."""
    for n in range(axes.shape[0]):
        camber[n], toe[n] = camber_toe(axes[n, 0], axes[n, 1], axes[n, 2], side_sign)
